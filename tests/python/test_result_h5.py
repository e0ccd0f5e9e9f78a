"""nodus.results.open: a run's result.h5 read with h5py, against the run's CSV files (docs/output.md) and the
scenario; a scenario with branches, whose result.h5 links each branch's own; the XDMF index beside it."""

import pathlib
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np
import pytest

import nodus.results
from conftest import DRAG_WITH_BRANCHES, run_cli
from nodus.results import read_table


@pytest.fixture(scope="module")
def drag(tmp_path_factory):
    """The drag scenario with two branches (conftest), run by the command line."""
    folder = tmp_path_factory.mktemp("result_h5")
    scenario = folder / "drag.yaml"
    scenario.write_text(DRAG_WITH_BRANCHES)
    run_cli("run", scenario, "--out", folder / "run", "-q", check_status=0)
    return folder / "run"


def close(a, b, digits):
    """`a` equals `b`, which was printed with `digits` significant digits."""
    np.testing.assert_allclose(a, b, rtol=10.0 ** (1 - digits), atol=1e-300)


def test_steps_equal_steps_csv(drag):
    r = nodus.results.open(drag)
    table = read_table(drag / "steps.csv")
    assert list(r.steps) == list(table)  # the same columns, in order
    for name, column in table.items():
        if column.dtype.kind == "U":
            assert list(r.steps[name]) == list(column), name
        else:
            close(r.steps[name], column, 10)
    assert r.steps["step"].dtype.kind == "i" and list(r.steps["step"]) == list(range(1, 12))


def test_last_state_equals_the_final_files(drag):
    r = nodus.results.open(drag)
    assert r.name == "main" and r.attrs["format"] == "nodus-result" and r.attrs["format_version"] == 1
    assert r.attrs["units"] == "mm, N, MPa, s"
    # Beams and stages as the scenario declares them.
    assert list(r.beams["name"]) == ["beam", "tool"]
    assert list(r.beams["radius"]) == [0.1, 0.2] and list(r.beams["young_modulus"]) == [4000, 4000]
    assert list(r.beams["node_count"]) == [41, 5] and list(r.beams["first_node"]) == [0, 41]
    assert list(r.beams["tool"]) == [0, 1]
    assert list(r.stages["name"]) == ["press", "drag", "back", "lift"]
    assert list(r.stages["end_time"]) == [1, 2, 3, 4] and list(r.stages["start_time"]) == [0, 1, 2, 3]
    assert r.segments.shape == (40 + 4, 2)
    # States at the steps of the VTK pictures.
    pictures = sorted(int(p.name[5:11]) for p in (drag / "vtk").glob("step_*.vtp"))
    assert [s.step for s in r.states] == pictures == [0, 2, 4, 6, 8, 10, 11]
    last = r.states[-1]
    assert last.stage == "lift" and last.load_time == 4.0
    nodes = read_table(drag / "final_nodes.csv")
    close(last.centre, np.column_stack([nodes[k] for k in ("x", "y", "z")]), 12)
    close(last.g1, np.column_stack([nodes[k] for k in ("g1x", "g1y", "g1z")]), 12)
    close(last.g2, np.column_stack([nodes[k] for k in ("g2x", "g2y", "g2z")]), 12)
    assert sorted(last.fields) == sorted(["e11", "e22", "e12", "e13", "e23", "e33", "q11", "q12", "q21",
                                          "q22", "k1", "k2", "m11", "m22", "m12"])


def test_contact_of_a_state_equals_its_csv(drag):
    """The contact tables of the state at step 6 (in `drag`, the tool pressing) equal contact/contact_000006.csv
    (output.contact_csv), beam names as indices."""
    r = nodus.results.open(drag)
    state = r.state(6)
    table = read_table(drag / "contact" / "contact_000006.csv")
    assert len(table["gap"]) > 0
    names = list(r.beams["name"])
    for name, column in table.items():
        if name in ("beam_i", "beam_j"):
            assert [names[i] for i in state.contact[name]] == list(column)
        elif name == "state":
            assert list(state.contact[name]) == list(column)
        else:
            close(state.contact[name], column, 10)
    assert r.state(6).contact["normal_force"].sum() > 0
    # The zones of the last state: zones_final.csv.
    zones = read_table(drag / "zones_final.csv")
    for name, column in zones.items():
        if name not in ("beam_i", "beam_j"):
            close(r.states[-1].zones[name], column, 10)
    # The initial state has no computed force: geometry columns only.
    assert "normal_force" not in r.states[0].contact


def test_branches_are_linked_and_read(drag):
    r = nodus.results.open(drag)
    assert sorted(r.branches) == ["mu_0.1", "same"]
    with h5py.File(drag / "result.h5", "r") as f:
        link = f["branches"].get("same", getlink=True)
        assert isinstance(link, h5py.ExternalLink) and link.filename == "branches/same/result.h5"
    same = r.branches["same"]
    assert same.name == "same"
    steps = read_table(drag / "branches" / "same" / "steps.csv")
    close(same.steps["normal_force"], steps["normal_force"], 10)
    # The branch starts from the end of drag (step 7) under its step number there.
    assert same.states[0].step == 7 and same.states[0].stage == "drag"
    nodes = read_table(drag / "branches" / "same" / "final_nodes.csv")
    close(same.states[-1].centre[:, 0], nodes["x"], 12)


def test_xdmf_index_is_well_formed_and_names_the_datasets(drag):
    root = ElementTree.parse(drag / "result.xmf").getroot()
    assert root.tag == "Xdmf"
    grids = root.find("Domain").find("Grid").findall("Grid")
    r = nodus.results.open(drag)
    assert [float(g.find("Time").get("Value")) for g in grids] == [s.load_time for s in r.states]
    with h5py.File(drag / "result.h5", "r") as f:
        for grid in grids:
            for item in grid.iter("DataItem"):
                file, path = item.text.split(":")
                assert file == "result.h5"
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                assert f[path].shape == dims, path


def test_missing_file_is_named(tmp_path):
    with pytest.raises(FileNotFoundError, match="result.h5: expected a nodus result file"):
        nodus.results.open(tmp_path)
    (tmp_path / "result.h5").write_text("not HDF5")
    with pytest.raises(OSError, match="expected an HDF5 file"):
        nodus.results.open(tmp_path)


def test_example_compares_two_runs(drag):
    import runpy
    import sys
    example = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "compare_runs.py"
    argv = sys.argv
    try:
        sys.argv = [str(example), str(drag / "branches" / "same"), str(drag / "branches" / "mu_0.1")]
        runpy.run_path(str(example), run_name="__main__")
    finally:
        sys.argv = argv
