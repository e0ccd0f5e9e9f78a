#pragma once
/// The processes of one run: MPI and PETSc, when nodus is built with them (CMake finds Debian's petsc-dev and
/// OpenMPI; NODUS_HAVE_PETSC). Without them there is one process, rank 0 of 1, and every call here is cheap.
///
/// `mpirun -n N nodus run ...` starts N processes. Each reads the scenario, builds the whole model, detects
/// contact and holds the whole state; with solver.linear_solver: petsc each rank evaluates the elements of
/// its range of nodes and assembles those rows of the residual and the tangent, PETSc factorises the
/// distributed matrix, and every rank receives the solution bit for bit, so the ranks take the same Newton
/// path. Rank 0 alone writes files and logs (docs/parallel.md, "What runs where").

#include <cstddef>
#include <string>
#include <vector>

namespace nodus::parallel {

/// Whether this build has MPI and PETSc.
bool available();

/// Whether this process was started by an MPI launcher (mpirun, mpiexec, srun): its environment says so.
bool launched_by_mpi();

/// Starts MPI and PETSc with these PETSc options (the command line's `-ksp_...`, `-pc_...`, `-mat_...`,
/// without the program name), unless they have started. Throws std::runtime_error when PETSc refuses.
/// Without PETSc, a non-empty `petsc_options` throws std::invalid_argument.
void initialize(const std::vector<std::string>& petsc_options);

/// Starts MPI and PETSc without options if they have not started (a lone process: MPI's singleton start),
/// and stops them at exit. Called by the solvers that need MPI; a no-op without PETSc.
void ensure_initialized();

/// Stops PETSc and MPI if this module started them. Idempotent; nothing may use MPI afterwards.
void finalize();

/// Whether MPI has been started and not yet stopped.
bool active();

/// This process's rank in MPI_COMM_WORLD, and their number (0 and 1 before MPI starts, or without it).
int rank();
int size();
inline bool is_root() {
  return rank() == 0;
}

/// Waits until every rank has reached this point (a no-op on one rank).
void barrier();
/// Rank 0's `value`, on every rank (every rank must call it): for a decision that only rank 0 can take, such
/// as whether to log (the other ranks do not log), when it leads to collective work.
bool root_value(bool value);
/// Every rank's segment [starts[r], starts[r + 1]) of `values` to every rank (the same array on all ranks;
/// starts has size() + 1 entries): afterwards every rank holds every segment as its owner computed it.
void share_segments(double* values, const std::vector<int>& starts);
/// The sum over the ranks of `values` (count of them), on every rank. Where at most one rank holds a value
/// other than zero, the sum is that value exactly.
void sum_over_ranks(double* values, std::size_t count);

/// Ends every rank with this exit status, when there are several (MPI_Abort): one rank's failure would
/// otherwise leave the others waiting for it. Returns on one rank.
void abort_all(int status);

/// This process's environment (NAME=VALUE) for a program it starts, without the variables of MPI's runtime
/// (OMPI_*, PMIX_*, PMI_*, OPAL_*, ORTE_*) once MPI has started: MPI sets them in this process, even as a
/// singleton, and a child holding them would take itself for a rank of this job.
std::vector<std::string> environment_for_another_program();

/// The arguments of a command line split into the PETSc options (`-ksp_*`, `-pc_*`, `-mat_*`, `-log_view`,
/// `-options_*` and each one's value, if the next argument is not an option) and the rest, the program name
/// first, in their order.
struct SplitArguments {
  std::vector<std::string> petsc;
  std::vector<std::string> rest;
};
SplitArguments split_petsc_options(int argc, const char* const* argv);

/// The PETSc options of the command line given to initialize() (empty before, or without PETSc).
const std::vector<std::string>& command_line_options();

/// Whether `options` reads as PETSc options on a command line: words separated by blanks, each an option
/// (`-name`) or the one value that follows an option (solver.petsc_options).
bool well_formed_options(const std::string& options);

}  // namespace nodus::parallel
