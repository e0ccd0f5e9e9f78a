"""6. Ctrl-C: SIGINT sent to a Python process running nodus raises KeyboardInterrupt there, the run stops at
its last converged state, and it can go on (Simulation.step, nodus.run(resume=True)) to the results of a run
never interrupted."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import nodus
from conftest import DRAG_WITH_BRANCHES, EXAMPLES, assert_same_outputs, run_cli

PYTHON = "/usr/bin/python3"
# A hang guard, not a timing check: the child is killed if it has not answered by then.
GUARD_SECONDS = 120


def long_tool_drag(factor):
    """tool_drag with `factor` times its steps (16 steps, a fraction of a second, become seconds)."""
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    for stage in d["stages"]:
        stage["steps"] *= factor
    return d


def child(script, tmp_path):
    """Starts `python3 -c script` with the module on its path (the test's own environment)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    return subprocess.Popen([PYTHON, "-c", textwrap.dedent(script)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env, cwd=tmp_path)


def interrupt(process, started):
    """Waits for `started()` to be true, sends SIGINT and returns (stdout, stderr, seconds to exit)."""
    deadline = time.monotonic() + GUARD_SECONDS
    while not started():
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "the child never started"
        time.sleep(0.01)
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    try:
        out, err = process.communicate(timeout=GUARD_SECONDS)
    except subprocess.TimeoutExpired:
        process.kill()
        raise AssertionError("the child did not stop after SIGINT")
    seconds = time.monotonic() - sent
    print(f"SIGINT to exit: {seconds:.3f} s")
    return out, err, seconds


def test_ctrl_c_stops_a_simulation_at_its_last_converged_step(tmp_path):
    (tmp_path / "scenario.json").write_text(json.dumps(long_tool_drag(20)))
    process = child("""
        import json, signal, sys
        import numpy as np
        import nodus
        signal.signal(signal.SIGINT, signal.default_int_handler)
        data = json.load(open("scenario.json"))
        sim = nodus.Simulation(data)
        def started(record):
            if record["step"] == 3:
                print("started", flush=True)
        try:
            sim.run(callback=started)
            print(json.dumps({"interrupted": False}))
            sys.exit(0)
        except KeyboardInterrupt:
            pass
        result = {"interrupted": True, "steps": sim.steps, "time": sim.time,
                  "last_step": sim.last_step["step"], "last_time": sim.last_step["time"],
                  "finished": sim.finished, "failure": sim.failure}
        # The reference: a Simulation of the same scenario stepped as many steps, never interrupted.
        fresh = nodus.Simulation(data)
        fresh.step(sim.steps)
        result["same_time"] = fresh.time == sim.time and fresh.steps == sim.steps
        result["same_state"] = bool(np.array_equal(fresh.state, sim.state))
        # And it goes on.
        record = sim.step()
        fresh.step()
        result["next_step"] = record["step"]
        result["same_after_next_step"] = bool(np.array_equal(fresh.state, sim.state)) and fresh.time == sim.time
        print(json.dumps(result), flush=True)
    """, tmp_path)
    first_line = []

    def started():
        first_line.append(process.stdout.readline())
        return first_line[-1].strip() == "started"

    out, err, _ = interrupt(process, started)
    assert process.returncode == 0, err
    result = json.loads(out.strip().splitlines()[-1])
    assert result["interrupted"], "the run ended before SIGINT"
    total = sum(stage["steps"] for stage in long_tool_drag(20)["stages"])
    assert 3 <= result["steps"] < total and not result["finished"] and result["failure"] == ""
    assert result["steps"] == result["last_step"] and result["time"] == result["last_time"]
    assert result["same_time"] and result["same_state"]
    assert result["next_step"] == result["steps"] + 1 and result["same_after_next_step"]


def test_ctrl_c_stops_nodus_run_and_resume_completes_it(tmp_path):
    data = long_tool_drag(10)
    data["output"] = {"checkpoint_every": 2, "vtk_every": 0}
    scenario = tmp_path / "long.yaml"
    nodus.Scenario(data).to_yaml(scenario)
    reference = tmp_path / "reference"
    run_cli("run", scenario, "--out", reference, "--quiet", check_status=0)

    out = tmp_path / "python"
    process = child(f"""
        import signal, sys
        import nodus
        signal.signal(signal.SIGINT, signal.default_int_handler)
        try:
            nodus.run({str(scenario)!r}, {str(out)!r}, quiet=True)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted")
    """, tmp_path)
    steps_csv = out / "steps.csv"

    def started():  # four steps written: a checkpoint exists
        return steps_csv.exists() and len(steps_csv.read_text().splitlines()) >= 5

    stdout, err, _ = interrupt(process, started)
    assert process.returncode == 0, err
    assert stdout.strip() == "interrupted"
    assert not (out / "summary.json").exists()  # as if killed
    rows = len(steps_csv.read_text().splitlines()) - 1
    total = sum(stage["steps"] for stage in data["stages"])
    assert 4 <= rows < total

    outcome = nodus.run(scenario, out, quiet=True, resume=True)
    assert outcome.converged and not outcome.interrupted
    assert_same_outputs(reference, out)


def test_ctrl_c_stops_branch_processes_and_resume_completes_them(tmp_path):
    """With jobs=2 the branches run in processes of the nodus executable: SIGINT to the Python process stops
    them (SIGTERM, waited for), and resume=True ends with the files of a run never interrupted."""
    data = nodus._nodus.yaml_to_data(DRAG_WITH_BRANCHES)
    for branch in data["branches"]:
        for stage in branch["stages"]:
            stage["steps"] *= 100
    data["output"] = {"checkpoint_every": 10, "vtk_every": 0, "contact_csv": False}
    scenario = tmp_path / "branches.yaml"
    nodus.Scenario(data).to_yaml(scenario)
    reference = tmp_path / "reference"
    run_cli("run", scenario, "--out", reference, "--quiet", "--jobs", "2", check_status=0)
    out = tmp_path / "python"
    process = child(f"""
        import signal
        import nodus
        signal.signal(signal.SIGINT, signal.default_int_handler)
        try:
            nodus.run({str(scenario)!r}, {str(out)!r}, quiet=True, jobs=2)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted")
    """, tmp_path)
    branch_steps = [out / "branches" / b["name"] / "steps.csv" for b in data["branches"]]

    def started():  # both branch processes have written steps
        return all(p.exists() and len(p.read_text().splitlines()) >= 12 for p in branch_steps)
    stdout, err, _ = interrupt(process, started)
    assert process.returncode == 0, err
    assert stdout.strip() == "interrupted"
    assert not (out / "summary.json").exists()
    # No branch process outlives the run (they were waited for).
    left = subprocess.run(["pgrep", "-f", f"--out {out}"], capture_output=True, text=True).stdout.split()
    assert left == []
    outcome = nodus.run(scenario, out, quiet=True, resume=True, jobs=2)
    assert outcome.converged and not outcome.interrupted
    assert_same_outputs(reference, out)
