"""nodus.vtk.read_vtp against independent references: the final state of final_nodes.csv, the same run written
in the other encoding (output.vtk_format), and, where Debian's python3-vtk9 is installed, VTK's own reader (the
one ParaView uses)."""

import csv

import numpy as np
import pytest

import nodus
from conftest import EXAMPLES
from nodus.vtk import read_vtp


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """examples/tool_drag.yaml (a beam dragged by a tool, with contact) run in both encodings."""
    folder = tmp_path_factory.mktemp("vtk")
    outs = {}
    for encoding in ("binary", "ascii"):
        data = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
        data.setdefault("output", {})["vtk_format"] = encoding
        scenario = folder / f"{encoding}.yaml"
        nodus.Scenario(data).to_yaml(scenario)
        outs[encoding] = folder / encoding
        assert nodus.run(str(scenario), outs[encoding], quiet=True).converged
    return outs


def pictures(out):
    return sorted(p.name for p in (out / "vtk").glob("*.vtp"))


def test_binary_files_are_smaller_and_hold_the_ascii_values(runs):
    names = pictures(runs["binary"])
    assert names == pictures(runs["ascii"]) and any(n.startswith("contact_") for n in names)
    binary_bytes = sum((runs["binary"] / "vtk" / n).stat().st_size for n in names)
    ascii_bytes = sum((runs["ascii"] / "vtk" / n).stat().st_size for n in names)
    assert binary_bytes < ascii_bytes / 4
    for name in names:
        b, a = read_vtp(runs["binary"] / "vtk" / name), read_vtp(runs["ascii"] / "vtk" / name)
        assert b.time == a.time
        np.testing.assert_allclose(b.points, a.points, rtol=1e-11, atol=1e-14)
        for data in ("point_data", "cell_data", "lines", "polys"):
            mine, theirs = getattr(b, data), getattr(a, data)
            assert mine.keys() == theirs.keys(), (name, data)
            for key in mine:
                assert mine[key].dtype == theirs[key].dtype, (name, key)
                np.testing.assert_allclose(mine[key], theirs[key], rtol=1e-11, atol=1e-14, err_msg=name + key)


def test_the_last_picture_holds_the_final_state(runs):
    out = runs["binary"]
    last = read_vtp(out / "vtk" / [n for n in pictures(out) if n.startswith("step_")][-1])
    with open(out / "final_nodes.csv") as f:
        rows = list(csv.DictReader(f))
    centres = np.array([[float(r[c]) for c in "xyz"] for r in rows])
    g1 = np.array([[float(r[c]) for c in ("g1x", "g1y", "g1z")] for r in rows])
    np.testing.assert_allclose(last.points[:len(rows)], centres, rtol=0, atol=1e-10)
    np.testing.assert_allclose(last.point_data["g1"][:len(rows)], g1, rtol=0, atol=1e-10)
    assert list(last.point_data["node"][:len(rows)]) == list(range(len(rows)))


def test_vtk_reads_the_binary_files_as_nodus_vtk_does(runs):
    vtk = pytest.importorskip("vtk", reason="python3-vtk9 not installed")
    from vtk.util.numpy_support import vtk_to_numpy

    for name in pictures(runs["binary"]):
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(str(runs["binary"] / "vtk" / name))
        reader.Update()
        assert reader.GetErrorCode() == 0, name
        poly = reader.GetOutput()
        mine = read_vtp(runs["binary"] / "vtk" / name)
        assert poly.GetNumberOfPoints() == len(mine.points)
        if len(mine.points):
            np.testing.assert_array_equal(vtk_to_numpy(poly.GetPoints().GetData()), mine.points)
        for data, arrays in ((poly.GetPointData(), mine.point_data), (poly.GetCellData(), mine.cell_data)):
            assert data.GetNumberOfArrays() == len(arrays), name
            for key, values in arrays.items():
                np.testing.assert_array_equal(vtk_to_numpy(data.GetArray(key)), values, err_msg=name + key)
        if mine.lines:
            assert poly.GetNumberOfLines() == len(mine.lines["offsets"])
