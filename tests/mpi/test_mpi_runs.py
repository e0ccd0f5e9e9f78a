#!/usr/bin/env python3
"""The PETSc backend under mpirun against the serial backend (issue 20, must-haves 3 and 4).

    test_mpi_runs.py NODUS MPIRUN EXAMPLES_DIR WORK_DIR

For each scenario: the serial run as the scenario says (its own linear solver), then the same scenario with
solver.linear_solver: petsc on 1, 2 and 3 ranks; each must give the same steps, the same contact counts and
final nodes within 1e-8 mm (compare_runs.py). Then, on 2 ranks: bad input is reported once with exit status
2 on every rank and nothing written; a run stopped after 7 steps and resumed ends with the files of the run
never stopped, byte for byte. Needs the nodus Python module (PYTHONPATH) to rewrite the scenarios.
"""
import os
import subprocess
import sys
from pathlib import Path

import nodus

HERE = Path(__file__).resolve().parent
# The verification-type examples: large rotations without contact; contact with friction and a tool; a
# twisted pair's detection; a bent beam released. No knot: a coarse knot's path is decided by round-off
# (docs/parallel.md).
SCENARIOS = ["cantilever_roll_up", "tool_drag", "twisted_pair_detection", "bend_and_release"]
RANKS = [1, 2, 3]


def mpirun(launcher, n, args):
    # More ranks than cores (3 on CI's 2): one OpenMP thread a rank, and ranks that yield the core while they
    # wait for each other (OpenMPI polls otherwise: 55 s instead of 3 s for the cantilever on 3 ranks).
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_MCA_mpi_yield_when_idle="1")
    command = [launcher, "--oversubscribe", "--allow-run-as-root", "-n", str(n)] + args
    return subprocess.run(command, capture_output=True, text=True, env=env)


def with_petsc(source, target):
    scenario = nodus.Scenario.from_yaml(source)
    data = scenario.to_dict()
    data.setdefault("solver", {})["linear_solver"] = "petsc"
    nodus.Scenario(data).to_yaml(target)


def main():
    exe, launcher, examples, work = sys.argv[1], sys.argv[2], Path(sys.argv[3]), Path(sys.argv[4])
    work.mkdir(parents=True, exist_ok=True)
    failures = []

    for name in SCENARIOS:
        source = examples / f"{name}.yaml"
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
            c = subprocess.run([sys.executable, str(HERE / "compare_runs.py"), str(serial), str(out)],
                               capture_output=True, text=True)
            print(f"{name}, {n} ranks: " + c.stdout.strip().replace("\n", "; "))
            if c.returncode != 0:
                failures.append(f"{name} on {n} ranks differs from the serial run: {c.stdout}")

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
    for f in ["steps.csv", "final_nodes.csv", "contact_final.csv"]:
        same = (whole / f).read_bytes() == (resumed / f).read_bytes()
        print(f"resumed on 2 ranks: {f} {'identical' if same else 'DIFFERS'}")
        if not same:
            failures.append(f"resumed on 2 ranks: {f} differs from the run never stopped")

    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
