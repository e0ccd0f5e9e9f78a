#!/usr/bin/env python3
"""The PETSc backend under mpirun against the serial backend.

    test_mpi_runs.py NODUS MPIRUN EXAMPLES_DIR WORK_DIR

For each scenario: the serial run as the scenario says (its own linear solver), then the same scenario with
solver.linear_solver: petsc on 1, 2 and 3 ranks; each must give the same steps, the same contact counts and
final nodes within 1e-8 mm (compare_runs.py). The scenarios: four verification-type examples and a coarse knot
(the flagship's program on 60 elements, its stages loop, clamp and thread, scripts/knot_program.py). Then, on
2 ranks: the same for tool_drag with the lagged factorisation (solver.reuse_factor, PETSc's GMRES on the kept
factor) against that policy in one process; LU by SuperLU_dist from the scenario's petsc_options, and MUMPS
from the command line over them (PETSc's -ksp_view says which factorised, and summary.json the same), against
the serial run; a serial solver on 2 ranks said once; bad input
is reported once with exit status 2 on every rank and nothing written; a run stopped after 7 steps and resumed
ends with the files of the run never stopped, byte for byte, and so does a longer run killed (SIGKILL) after
60 steps and resumed, and the same run stopped by SIGTERM to mpirun (which must say so) and resumed. Needs the
nodus Python module (PYTHONPATH) to rewrite the scenarios.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import nodus
from mpi_launch import mpirun_command

HERE = Path(__file__).resolve().parent
# The verification-type examples: large rotations without contact; contact with friction and a tool; a
# twisted pair's detection; a bent beam released.
SCENARIOS = ["cantilever_roll_up", "tool_drag", "twisted_pair_detection", "bend_and_release"]
# And a coarse knot.
KNOT = "knot_60"


def write_coarse_knot(scripts, target):
    """The flagship's program on 60 elements, tied and threaded (loop, clamp, thread: contact between parts
    of the rod and with the clamping beams, detections, cutbacks), with end B lifted 0.05 mm out of the plane
    at the start: without the lift the side to which the compressed straight rod buckles out of that plane is
    decided by round-off, and two linear solvers can tie different knots (docs/parallel.md)."""
    sys.path.insert(0, str(scripts))
    import knot_program
    data = knot_program.knot_scenario(60, lift=0.05)
    data["stages"] = [s for s in data["stages"] if s["name"] in ("loop", "clamp", "thread")]
    data.pop("branches", None)
    data.setdefault("output", {}).update(vtk_every=0)
    nodus.Scenario(data).to_yaml(target)
RANKS = [1, 2, 3]


def mpirun(launcher, n, args):
    command, env = mpirun_command(launcher, n, args)
    return subprocess.run(command, capture_output=True, text=True, env=env)


def compare(reference, run, label, failures):
    """compare_runs.py of `run` against `reference`: prints its summary after `label`; a difference is a
    failure. Returns compare_runs.py's output."""
    c = subprocess.run([sys.executable, str(HERE / "compare_runs.py"), str(reference), str(run)],
                       capture_output=True, text=True)
    print(f"{label}: " + c.stdout.strip().replace("\n", "; "))
    if c.returncode != 0:
        failures.append(f"{label} differs from the serial run: {c.stdout}")
    return c.stdout


def with_solver(source, target, **solver):
    scenario = nodus.Scenario.from_yaml(source)
    data = scenario.to_dict()
    data.setdefault("solver", {}).update(solver)
    nodus.Scenario(data).to_yaml(target)


def with_petsc(source, target):
    with_solver(source, target, linear_solver="petsc")


def expect_same_files(whole, other, label, failures):
    """steps.csv, final_nodes.csv and contact_final.csv of `other` byte for byte those of `whole` (the run
    never stopped); prints each verdict after `label`, and adds a failure for each that differs."""
    for f in ["steps.csv", "final_nodes.csv", "contact_final.csv"]:
        same = (whole / f).read_bytes() == (other / f).read_bytes()
        print(f"{label}: {f} {'identical' if same else 'DIFFERS'}")
        if not same:
            failures.append(f"{label}: {f} differs from the run never stopped")


def start_and_wait_for_steps(launcher, args, folder, steps):
    """Starts `nodus ARGS` on 2 ranks in a session of its own (stderr kept, text) and waits until FOLDER's
    steps.csv has `steps` rows, the run ends, or 300 s pass. Returns the process and the rows seen."""
    command, env = mpirun_command(launcher, 2, args)
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    deadline, seen = time.monotonic() + 300, 0
    while process.poll() is None and seen < steps and time.monotonic() < deadline:
        time.sleep(0.05)
        if (folder / "steps.csv").exists():
            seen = (folder / "steps.csv").read_text().count("\n") - 1
    return process, seen


def wait_for_no_process_with(text, deadline):
    """Waits until no process has `text` in its command line, or the deadline (time.monotonic()) passes."""
    while time.monotonic() < deadline:
        alive = False
        for entry in Path("/proc").iterdir():
            if entry.name.isdigit():
                try:
                    alive = alive or text in (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
                except OSError:
                    pass
        if not alive:
            return
        time.sleep(0.1)


def main():
    exe, launcher, examples, work = sys.argv[1], sys.argv[2], Path(sys.argv[3]), Path(sys.argv[4])
    work.mkdir(parents=True, exist_ok=True)
    failures = []

    write_coarse_knot(examples.parent / "scripts", work / f"{KNOT}.yaml")
    for name in SCENARIOS + [KNOT]:
        source = work / f"{KNOT}.yaml" if name == KNOT else examples / f"{name}.yaml"
        serial = work / f"{name}_serial"
        r = subprocess.run([exe, "run", str(source), "--out", str(serial), "--quiet"], capture_output=True,
                           text=True)
        if r.returncode != 0:
            failures.append(f"{name}: serial run failed ({r.returncode}): {r.stderr[-500:]}")
            continue
        petsc = work / f"{name}_petsc.yaml"
        with_petsc(source, petsc)
        for n in RANKS:
            out = work / f"{name}_petsc_{n}"
            r = mpirun(launcher, n, [exe, "run", str(petsc), "--out", str(out), "--quiet"])
            if r.returncode != 0:
                failures.append(f"{name} on {n} ranks: exit status {r.returncode}: {r.stderr[-800:]}")
                continue
            compare(serial, out, f"{name}, {n} ranks", failures)

    # Several ranks share the evaluation (each its own blocks' rows), unless the factor is kept (below).
    r = mpirun(launcher, 2, [exe, "run", str(work / "twisted_pair_detection_petsc.yaml"), "--out",
                             str(work / "distributed_log"), "--verbose"])
    shared = "evaluation distributed over 2 ranks" in r.stderr
    print(f"twisted_pair_detection on 2 ranks: evaluation {'distributed' if shared else 'NOT distributed'}")
    if r.returncode != 0 or not shared:
        failures.append(f"twisted_pair_detection on 2 ranks: status {r.returncode}, no distributed evaluation "
                        f"in the log: {r.stderr[-500:]}")

    # The lagged factorisation (solver.reuse_factor: GMRES preconditioned by a kept factor, refactorised when
    # it no longer serves) through PETSc on 2 ranks, the evaluation distributed as without it, against the same
    # policy in one process. The GMRES differ (PETSc's on the right, tested on the true residual; Eigen's on
    # the left, asked for 1e-3 of the tolerance on its preconditioned residual), so the counts may differ:
    # the answer must not, and the factor must be kept for most iterations on both.
    lagged_serial, lagged_petsc = work / "tool_drag_lagged.yaml", work / "tool_drag_lagged_petsc.yaml"
    with_solver(examples / "tool_drag.yaml", lagged_serial, reuse_factor=True)
    with_solver(examples / "tool_drag.yaml", lagged_petsc, reuse_factor=True, linear_solver="petsc")
    serial, out = work / "tool_drag_lagged_serial", work / "tool_drag_lagged_petsc_2"
    r = subprocess.run([exe, "run", str(lagged_serial), "--out", str(serial), "--quiet"], capture_output=True,
                       text=True)
    r2 = mpirun(launcher, 2, [exe, "run", str(lagged_petsc), "--out", str(out), "--verbose"])
    if r.returncode != 0 or r2.returncode != 0:
        failures.append(f"lagged factorisation: exit status {r.returncode} serial, {r2.returncode} on 2 ranks: "
                        f"{r.stderr[-400:]} {r2.stderr[-400:]}")
    else:
        compare(serial, out, "tool_drag with reuse_factor, 2 ranks", failures)
        counts = [json.loads((d / "summary.json").read_text()) for d in (serial, out)]
        counts = [(s["newton_iterations"], s["factorizations"], s["krylov_iterations"]) for s in counts]
        shared = "evaluation distributed over 2 ranks" in r2.stderr
        print("tool_drag with reuse_factor, 2 ranks: (Newton iterations, factorisations, GMRES iterations): "
              "serial {}, 2 ranks {}".format(*counts) + f"; evaluation {'distributed' if shared else 'NOT distributed'}")
        if not shared:
            failures.append("tool_drag with reuse_factor on 2 ranks: the evaluation was not distributed")
        for where, (iterations, factorizations, krylov) in zip(["serial", "2 ranks"], counts):
            if not (factorizations < iterations / 2 and krylov > 0):
                failures.append(f"tool_drag with reuse_factor, {where}: {factorizations} factorisations for "
                                f"{iterations} Newton iterations, {krylov} GMRES iterations")

    # PETSc's options from the scenario (LU by SuperLU_dist) and from the command line, which wins over the
    # scenario's (MUMPS): PETSc's -ksp_view names the package that factorised; both give the serial answers.
    options = work / "tool_drag_superlu.yaml"
    with_solver(examples / "tool_drag.yaml", options, linear_solver="petsc",
                petsc_options="-pc_type lu -pc_factor_mat_solver_type superlu_dist")
    for package, extra in [("superlu_dist", []), ("mumps", ["-pc_factor_mat_solver_type", "mumps"])]:
        out = work / f"tool_drag_{package}_2"
        r = mpirun(launcher, 2, [exe, "run", str(options), "--out", str(out), "--quiet", "-ksp_view"] + extra)
        used = {p for p in ("superlu_dist", "mumps")
                if f"package used to perform factorization: {p}" in r.stdout + r.stderr}
        if r.returncode != 0 or used != {package}:
            failures.append(f"tool_drag, {package} on 2 ranks: exit status {r.returncode}, factorised by "
                            f"{sorted(used)}: {r.stderr[-400:]}")
            continue
        compare(work / "tool_drag_serial", out, f"tool_drag, {package} on 2 ranks "
                f"({'scenario' if not extra else 'command line over scenario'})", failures)
        # summary.json says so: the ranks, and the package -ksp_view named.
        provenance = json.loads((out / "summary.json").read_text())["provenance"]
        solvers = provenance["linear_solvers"]
        print(f"tool_drag, {package} on 2 ranks: provenance says {provenance['mpi_ranks']} ranks, {solvers}")
        if provenance["mpi_ranks"] != 2 or len(solvers) != 1 or not solvers[0].endswith(f"by {package}"):
            failures.append(f"tool_drag, {package} on 2 ranks: summary.json's provenance says {provenance}")

    # A serial solver named under mpirun: every rank repeats the run, and rank 0 says so once.
    with_solver(examples / "tool_drag.yaml", work / "tool_drag_cholmod.yaml", linear_solver="cholmod")
    r = mpirun(launcher, 2, [exe, "run", str(work / "tool_drag_cholmod.yaml"), "--out", str(work / "serial_on_2"),
                             "--quiet"])
    said = r.stderr.count("2 MPI ranks, but solver.linear_solver: cholmod solves in one process")
    print(f"tool_drag with cholmod on 2 ranks: exit status {r.returncode}, said {said} time(s)")
    if r.returncode != 0 or said != 1:
        failures.append(f"cholmod on 2 ranks: status {r.returncode}, said {said} times: {r.stderr[-400:]}")

    # The example as written (solver.linear_solver: auto) on 2 ranks: the ranks share PETSc's factorisation,
    # with the serial run's answers.
    out = work / "auto_on_2"
    r = mpirun(launcher, 2, [exe, "run", str(examples / "tool_drag.yaml"), "--out", str(out), "--quiet"])
    said = r.stderr.count("solves in one process")
    provenance = json.loads((out / "summary.json").read_text())["provenance"] if r.returncode == 0 else {}
    solvers = provenance.get("linear_solvers", [])
    print(f"tool_drag with auto on 2 ranks: exit status {r.returncode}, {solvers}, warned {said} time(s)")
    if r.returncode != 0 or said != 0 or len(solvers) != 1 or not solvers[0].startswith("petsc"):
        failures.append(f"auto on 2 ranks: status {r.returncode}, solvers {solvers}, warned {said} times: "
                        f"{r.stderr[-400:]}")
    else:
        compare(work / "tool_drag_serial", out, "tool_drag, auto on 2 ranks", failures)

    # auto with a stage that names its own solver: one process's solvers, so the serial choice, said once (PETSc's
    # ranks share the rows of one solver, which the stage's would not).
    data = nodus.Scenario.from_yaml(examples / "tool_drag.yaml").to_dict()
    data.get("solver", {}).pop("linear_solver", None)
    data["stages"][0]["linear_solver"] = "klu"
    nodus.Scenario(data).to_yaml(work / "tool_drag_stage_klu.yaml")
    r = mpirun(launcher, 2, [exe, "run", str(work / "tool_drag_stage_klu.yaml"), "--out",
                             str(work / "stage_klu_on_2"), "--quiet"])
    said = r.stderr.count("solves in one process")
    print(f"tool_drag, auto with a stage's own klu on 2 ranks: exit status {r.returncode}, said {said} time(s)")
    if r.returncode != 0 or said != 1:
        failures.append(f"auto with a stage solver on 2 ranks: status {r.returncode}, said {said} times: "
                        f"{r.stderr[-400:]}")

    # A preconditioner type from the command line keeps MUMPS: LU for the twisted pair's symmetric tangent. On
    # one rank PETSc would otherwise take its own LU (it did, until the solver named MUMPS among its options).
    for n in (1, 2):
        out = work / f"twisted_pair_lu_{n}"
        r = mpirun(launcher, n, [exe, "run", str(work / "twisted_pair_detection_petsc.yaml"), "--out", str(out),
                                 "--quiet", "-ksp_view", "-pc_type", "lu"])
        log = r.stdout + r.stderr
        lu_by_mumps = ("type: lu" in log and "package used to perform factorization: mumps" in log
                       and "package used to perform factorization: petsc" not in log)
        print(f"twisted_pair_detection with -pc_type lu on {n} rank(s): exit status {r.returncode}, "
              f"{'LU by MUMPS' if lu_by_mumps else 'NOT LU by MUMPS'}")
        if r.returncode != 0 or not lu_by_mumps:
            failures.append(f"twisted_pair_detection with -pc_type lu on {n} rank(s): exit status "
                            f"{r.returncode}: {log[-600:]}")
            continue
        compare(work / "twisted_pair_detection_serial", out, f"twisted_pair_detection, LU on {n} rank(s)",
                failures)

    # Bad input: one message, status 2 on every rank (mpirun returns a rank's non-zero status), no folder.
    bad = work / "bad.yaml"
    bad.write_text((work / "tool_drag_petsc.yaml").read_text().replace("friction: 0.3", "friction: -1"))
    r = mpirun(launcher, 2, [exe, "run", str(bad), "--out", str(work / "bad_out")])
    messages = r.stderr.count("contact.friction: expected a number >= 0")
    print(f"bad input on 2 ranks: exit status {r.returncode}, the message {messages} time(s)")
    if r.returncode != 2 or messages != 1 or (work / "bad_out").exists():
        failures.append(f"bad input on 2 ranks: status {r.returncode}, {messages} messages: {r.stderr[-800:]}")

    # Killed after 7 steps, resumed on the same ranks: the files of the run never stopped.
    scenario = work / "tool_drag_petsc.yaml"
    whole, resumed = work / "tool_drag_petsc_2", work / "tool_drag_resumed"
    r = mpirun(launcher, 2, [exe, "run", str(scenario), "--out", str(resumed), "--quiet", "--stop-after-steps",
                             "7"])
    if r.returncode != 3:
        failures.append(f"stop after 7 steps: exit status {r.returncode} (expected 3): {r.stderr[-500:]}")
    r = mpirun(launcher, 2, [exe, "run", str(scenario), "--out", str(resumed), "--quiet", "--resume"])
    if r.returncode != 0:
        failures.append(f"resume: exit status {r.returncode}: {r.stderr[-500:]}")
    expect_same_files(whole, resumed, "resumed on 2 ranks", failures)

    # Killed for real (SIGKILL to mpirun and both ranks, mid-run) and resumed on 2 ranks: the files of the run
    # never stopped. tool_drag with 20 times its steps (320), a checkpoint every 5, so that the kill falls
    # between checkpoints, or in one, while the ranks are working.
    data = nodus.Scenario.from_yaml(examples / "tool_drag.yaml").to_dict()
    for stage in data["stages"]:
        stage["steps"] *= 20
    data.setdefault("solver", {}).update(linear_solver="petsc")
    data.setdefault("output", {}).update(checkpoint_every=5, vtk_every=0)
    long_drag = work / "tool_drag_long_petsc.yaml"
    nodus.Scenario(data).to_yaml(long_drag)
    whole, killed = work / "tool_drag_long_2", work / "tool_drag_long_killed"
    r = mpirun(launcher, 2, [exe, "run", str(long_drag), "--out", str(whole), "--quiet"])
    if r.returncode != 0:
        failures.append(f"long tool_drag on 2 ranks: exit status {r.returncode}: {r.stderr[-500:]}")
    else:
        shutil.rmtree(killed, ignore_errors=True)  # a steps.csv of an earlier run would be read as progress
        process, steps = start_and_wait_for_steps(launcher, [exe, "run", str(long_drag), "--out", str(killed),
                                                             "--quiet"], killed, 60)
        finished = process.poll() is not None
        if not finished:
            os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        # The ranks outlive mpirun by a moment (they are not in its process group): until they end, the folder
        # is theirs, and a resume into it is refused (one run at a time in a folder).
        wait_for_no_process_with(str(killed), deadline=time.monotonic() + 60)
        r = mpirun(launcher, 2, [exe, "run", str(long_drag), "--out", str(killed), "--quiet", "--resume"])
        print(f"killed on 2 ranks after {steps} steps (of 320), resumed: exit status {r.returncode}")
        if finished or steps < 60 or r.returncode != 0:
            failures.append(f"kill and resume on 2 ranks: {steps} steps before the kill (finished: {finished}), "
                            f"resume status {r.returncode}: {r.stderr[-500:]}")
        else:
            expect_same_files(whole, killed, "killed and resumed on 2 ranks", failures)

        # Stopped by SIGTERM to mpirun mid-run (as a scheduler at the end of a job's time): every rank stops at
        # the same Newton iteration, the last converged state is saved and said, and the run resumed on 2 ranks
        # ends with the files of the run never stopped.
        stopped = work / "tool_drag_long_stopped"
        shutil.rmtree(stopped, ignore_errors=True)
        process, steps = start_and_wait_for_steps(launcher, [exe, "run", str(long_drag), "--out", str(stopped),
                                                             "--quiet"], stopped, 60)
        finished = process.poll() is not None
        if not finished:
            process.send_signal(signal.SIGTERM)
        _, err = process.communicate(timeout=120)
        wait_for_no_process_with(str(stopped), deadline=time.monotonic() + 60)
        said = "run stopped by SIGTERM at step" in err and "continue it with --resume" in err
        r = mpirun(launcher, 2, [exe, "run", str(long_drag), "--out", str(stopped), "--quiet", "--resume"])
        print(f"SIGTERM to mpirun after {steps} steps (of 320): said {said}; resumed: exit status {r.returncode}")
        if finished or not said or r.returncode != 0:
            failures.append(f"SIGTERM and resume on 2 ranks: finished {finished}, stderr {err[-500:]!r}, "
                            f"resume status {r.returncode}: {r.stderr[-500:]}")
        else:
            expect_same_files(whole, stopped, "stopped by SIGTERM and resumed on 2 ranks", failures)

    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
