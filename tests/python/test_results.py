"""nodus.results.Results against independent references: the records of the same scenario stepped in memory
(nodus.Simulation), its final state there, and the files as text."""

import numpy as np
import pytest

import nodus
from conftest import DRAG_WITH_BRANCHES, EXAMPLES
from nodus.results import Results, read_table


@pytest.fixture(scope="module")
def drag(tmp_path_factory):
    """examples/tool_drag.yaml run to a folder, and the records and final state of the same stepped in memory."""
    out = tmp_path_factory.mktemp("results") / "drag"
    assert nodus.run(str(EXAMPLES / "tool_drag.yaml"), out, quiet=True).converged
    sim = nodus.Simulation(nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml"))
    records = []
    while not sim.finished:
        records.append(sim.step())
    return Results(out), records, sim


def test_steps_are_the_records_of_the_run(drag):
    run, records, _ = drag
    steps = run.steps
    assert len(steps["step"]) == len(records) == 16
    for name in ("step", "time", "newton_iterations", "cutbacks", "contact_elements", "normal_force"):
        np.testing.assert_allclose(steps[name], [r[name] for r in records], rtol=1e-9, atol=1e-15, err_msg=name)
    assert list(steps["stage"]) == [r["stage"] for r in records]
    assert run.summary["steps"] == 16


def test_final_nodes_are_the_state_in_memory(drag):
    run, _, sim = drag
    nodes = run.nodes()
    np.testing.assert_allclose(nodes.x, sim.positions, rtol=0, atol=1e-9)
    assert sorted(set(nodes.beam)) == ["beam", "tool"]
    beam = nodes.of("beam")
    assert list(beam.node) == list(range(len(beam.node))) and np.all(np.diff(beam.s) > 0)
    with pytest.raises(KeyError):
        nodes.of("rope")


def test_stage_tables_and_pictures(drag):
    run, records, _ = drag
    assert run.stages == ["press", "drag", "lift"]
    last_of_press = max(r["step"] for r in records if r["stage"] == "press")
    # The end of `press` (by name or index) is the picture of its last step (the table's 12 digits).
    for stage in ("press", 0):
        np.testing.assert_allclose(run.nodes(stage).x, run.picture(last_of_press).points[:len(run.nodes().x)],
                                   rtol=1e-11, atol=1e-14)
    contact = run.contact("press")
    np.testing.assert_allclose(contact["normal_force"].sum(),
                               run.contact_picture(last_of_press).cell_data["normal_force"].sum(), rtol=1e-9)
    assert run.contact()["normal_force"].sum() == 0.0  # lifted: no force at the end
    with pytest.raises(FileNotFoundError, match="no nodes table of stage 'twist'"):
        run.nodes("twist")


def test_branches_and_text_columns(tmp_path):
    scenario = tmp_path / "branches.yaml"
    scenario.write_text(DRAG_WITH_BRANCHES)
    assert nodus.run(str(scenario), tmp_path / "out", quiet=True).converged
    run = Results(tmp_path / "out")
    assert sorted(run.branches) == ["mu_0.1", "same"]
    assert run.branches["same"].steps["stage"][-1] == "lift"
    # A quoted text column (cutback causes hold commas) stays text; an empty one too.
    table = tmp_path / "t.csv"
    table.write_text('a,b,c\n1,"x, y",\n2.5,z,\n')
    t = read_table(table)
    assert t["a"].dtype == float and list(t["b"]) == ["x, y", "z"] and list(t["c"]) == ["", ""]
    with pytest.raises(FileNotFoundError, match="expected a run's folder"):
        Results(tmp_path)
