"""4. nodus.run against `nodus run`: the same files, byte for byte (summary.json without its wall times, the
checkpoints by name), with branches one at a time and side by side, and stopped then resumed; and the folder
lock they share."""

import subprocess
import time

import pytest

import nodus
from conftest import DRAG_WITH_BRANCHES, EXAMPLES, assert_same_outputs, run_cli


@pytest.fixture
def branches_scenario(tmp_path):
    path = tmp_path / "drag_with_branches.yaml"
    path.write_text(DRAG_WITH_BRANCHES)
    return path


def cli_run(scenario, out, *extra):
    run_cli("run", scenario, "--out", out, "--quiet", *extra, check_status=0)
    return out


@pytest.mark.parametrize("jobs", [1, 2])
def test_run_with_branches_gives_the_files_of_the_command_line(branches_scenario, tmp_path, jobs):
    reference = cli_run(branches_scenario, tmp_path / "cli", "--jobs", str(jobs))
    out = tmp_path / "python"
    outcome = nodus.run(str(branches_scenario), out, jobs=jobs, quiet=True)
    assert outcome.converged and not outcome.interrupted and not outcome.already_complete
    assert (out / "branches" / "mu_0.1" / "summary.json").is_file()
    assert (out / "branches" / "same" / "checkpoints").is_dir()
    assert_same_outputs(reference, out)


def test_run_of_an_example_gives_the_files_of_the_command_line(tmp_path):
    scenario = EXAMPLES / "bend_and_release.yaml"
    reference = cli_run(scenario, tmp_path / "cli")
    out = tmp_path / "python"
    assert nodus.run(scenario, out, quiet=True).converged
    assert_same_outputs(reference, out)
    assert nodus.run(scenario, out, quiet=True, resume=True).already_complete


def test_stopped_and_resumed_gives_the_files_of_a_run_never_stopped(branches_scenario, tmp_path):
    reference = cli_run(branches_scenario, tmp_path / "cli")
    out = tmp_path / "python"
    # Stopped inside the main run (step 5 of its 11); resumed from the checkpoint of the end of `press` (step
    # 3) and stopped again inside the first branch: 8 steps to the end of the main run, then 2 of `same`.
    first = nodus.run(str(branches_scenario), out, quiet=True, stop_after_steps=5)
    assert first.interrupted and not first.converged
    assert not (out / "summary.json").exists()
    second = nodus.run(str(branches_scenario), out, quiet=True, resume=True, stop_after_steps=10)
    assert second.interrupted and not second.converged
    assert len((out / "branches" / "same" / "steps.csv").read_text().splitlines()) == 1 + 2
    assert not (out / "branches" / "mu_0.1").exists()
    assert not (out / "summary.json").exists()
    last = nodus.run(str(branches_scenario), out, quiet=True, resume=True)
    assert last.converged and not last.interrupted and not last.already_complete
    assert_same_outputs(reference, out)
    assert nodus.run(str(branches_scenario), out, quiet=True, resume=True).already_complete


def test_run_of_a_dict_gives_the_files_of_its_yaml(tmp_path):
    # A scenario built from data has no file for branch processes: they run here, with the same results.
    s = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml")
    path = tmp_path / "written.yaml"
    s.to_yaml(path)
    reference = cli_run(path, tmp_path / "cli")
    out = tmp_path / "python"
    assert nodus.run(s.to_dict(), out, quiet=True).converged
    files = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(reference).as_posix() for p in reference.rglob("*") if p.is_file())
    for name in files:
        if name.endswith("timing.csv"):  # all but its wall times
            assert ([line.rsplit(",", 1)[0] for line in (out / name).read_text().splitlines()] ==
                    [line.rsplit(",", 1)[0] for line in (reference / name).read_text().splitlines()]), name
        elif name.endswith(".csv") or name.endswith(".vtp") or name.endswith(".pvd"):
            assert (out / name).read_bytes() == (reference / name).read_bytes(), name


def test_a_folder_another_run_is_writing_into_is_refused(tmp_path, nodus_binary):
    """nodus.run takes the folder's lock as `nodus run` does: while a command-line run writes into a folder,
    nodus.run into it raises ScenarioError naming the folder and that process, and writes nothing there."""
    data = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    for stage in data["stages"]:
        stage["steps"] *= 100  # a run of tens of seconds
    data.setdefault("output", {}).update(vtk_every=0)
    scenario = tmp_path / "long_drag.yaml"
    nodus.Scenario(data).to_yaml(scenario)
    out = tmp_path / "out"
    other = subprocess.Popen([str(nodus_binary), "run", str(scenario), "--out", str(out), "--quiet"])
    try:
        deadline = time.monotonic() + 60
        while not (out / "steps.csv").exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        assert other.poll() is None, "the command-line run ended before the test could try its folder"
        rows = (out / "steps.csv").read_text()
        with pytest.raises(nodus.ScenarioError) as refused:
            nodus.run(str(scenario), out, quiet=True)
        message = str(refused.value)
        assert "--out: expected a folder no other run is writing into" in message, message
        assert f"process {other.pid} is writing into" in message, message
        assert other.poll() is None and (out / "steps.csv").read_text().startswith(rows)
    finally:
        other.kill()
        other.wait()
