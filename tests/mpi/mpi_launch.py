"""How tests/mpi starts a program on n ranks."""
import os


def mpirun_command(launcher, n, args):
    """The command and environment of `args` on n ranks. More ranks than cores (3 on CI's 2): one OpenMP
    thread a rank, and ranks that yield the core while they wait for each other (OpenMPI polls otherwise: 55 s
    instead of 3 s for the cantilever on 3 ranks)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_MCA_mpi_yield_when_idle="1")
    return [launcher, "--oversubscribe", "--allow-run-as-root", "-n", str(n)] + args, env
