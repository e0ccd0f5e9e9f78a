"""scripts/knot_force_series.py (docs/knot.md, "The tightening force"): the contact-element spacing it reports
against spacings laid out by hand, the scenario it writes for a force against the example's program, and bad
--forces rejected with one line and exit status 2 (the runs themselves take minutes and are not made here)."""

import importlib.util
import math
import re
import sys

import pytest

from conftest import SOURCE_DIR

pytest.importorskip("matplotlib")


@pytest.fixture(scope="module")
def series():
    sys.path.insert(0, str(SOURCE_DIR / "scripts"))
    path = SOURCE_DIR / "scripts" / "knot_force_series.py"
    spec = importlib.util.spec_from_file_location("knot_force_series", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_spacing_is_the_median_gap_within_each_zone(series):
    # Zone 0: gaps 0.03, 0.03, 0.05; zone 1 (its abscissa restarts after zone 0's): gaps 0.02, 0.04. The jump
    # between zones (0.11 -> 0.5) is not a gap. Median of (0.03, 0.03, 0.05, 0.02, 0.04) = 0.03.
    reactions = {"zone": [0, 0, 0, 0, 1, 1, 1], "abscissa_mm": [0.0, 0.03, 0.06, 0.11, 0.5, 0.52, 0.56]}
    assert series.element_spacing(reactions) == pytest.approx(0.03, abs=1e-15)
    assert math.isnan(series.element_spacing({"zone": [0], "abscissa_mm": [0.2]}))  # one element: no gap


def test_scenario_of_a_force_is_the_example_program_with_that_pull(series, tmp_path):
    run_dir = series.run_force(tmp_path, 2.0, 300, True, "/bin/true", 1)  # /bin/true: nothing is run
    text = (tmp_path / "force_2" / "knot.yaml").read_text()
    assert run_dir == tmp_path / "force_2" / "run"
    assert "pull_b: {force: [2.0, 0, 0]}" in text or "pull_b: {force: [2, 0, 0]}" in text
    assert "name: mu_0.30" in text and "mu_0.25" not in text and "mu_0.20" not in text
    # pull and settle take the line search (without it 2 N crawls once the knot slips); the example's do not.
    tightening = text[text.index("  - name: pull"):text.index("branches:")]
    assert tightening.count("line_search: true") == 2
    assert "line_search: true" not in example_stages_before_branches()
    # The sections paired by bisector (the example: the paper's plane, the default, not written).
    assert "section_pairing: bisector" in text
    assert "section_pairing" not in (SOURCE_DIR / "examples" / "monofilament_knot.yaml").read_text()
    # The same OUT asked for another scenario, with the first one's run there: refused, nothing overwritten.
    (tmp_path / "force_2" / "run").mkdir()
    with pytest.raises(ValueError, match="another scenario"):
        series.run_force(tmp_path, 2.0, 300, True, "/bin/true", 1, "plane")
    assert (tmp_path / "force_2" / "knot.yaml").read_text() == text
    example = (SOURCE_DIR / "examples" / "monofilament_knot.yaml").read_text()
    # Everything but the pull force and the branches is the example's: same stages, keyframes and settings.
    # The numbers are compared to 1e-9: the rotation vectors' round-off components (7e-14 degrees) depend on
    # the machine's floating-point kernels.
    number = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
    written = re.split(f"({number})", text[text.index("stages:"):text.index("  - name: pull")])
    expected = re.split(f"({number})", example[example.index("stages:"):example.index("  - name: pull")])
    assert len(written) == len(expected)
    for i, (w, e) in enumerate(zip(written, expected)):
        if i % 2:  # the numbers (re.split puts the captured separators at odd positions)
            assert float(w) == pytest.approx(float(e), rel=1e-9, abs=1e-9), (i, w, e)
        else:
            assert w == e


def example_stages_before_branches():
    example = (SOURCE_DIR / "examples" / "monofilament_knot.yaml").read_text()
    return example[example.index("stages:"):example.index("branches:")]


def test_smallest_clearance_skips_steps_without_contact(series, tmp_path):
    # nan: no contact in that step; inf: nothing within reach. The smallest finite value is the answer.
    path = tmp_path / "steps.csv"
    path.write_text("step,min_clearance\n1,nan\n2,inf\n3,-0.0021\n4,0.004\n5,-0.0007\n")
    assert series.smallest_clearance(path) == pytest.approx(-0.0021, abs=1e-15)
    path.write_text("step,min_clearance\n1,nan\n2,inf\n")
    assert math.isnan(series.smallest_clearance(path))


@pytest.mark.parametrize("forces", ["1,x", "0,1", "-2"])
def test_bad_forces_fail_with_one_line(series, tmp_path, capsys, forces):
    assert series.main(["knot_force_series.py", str(tmp_path), "--forces", forces]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("knot_force_series: --forces: expected")
    assert not any(tmp_path.iterdir())  # nothing written


def test_travel_to_a_force_is_read_where_the_reaction_first_reaches_it(series, tmp_path):
    # `hold` ends at load time 14 s; end B then travels at 0.1 mm/s. The reaction first reaches 4 N at 20.25 s:
    # a travel of 0.625 mm (not at 20.5 s, where it is higher, nor where it falls back below later).
    path = tmp_path / "steps.csv"
    path.write_text("step,stage,time,end_b_fx\n1,settle,13,0\n2,hold,13.5,1.0\n3,hold,14,2.0\n"
                    "4,drive,17,3.1\n5,drive,20.25,4.02\n6,drive,20.5,4.1\n7,drive,21,3.9\n")
    assert series.travel_to(path, 4.0) == pytest.approx(0.625, abs=1e-12)
    assert math.isnan(series.travel_to(path, 4.5))  # never reached
    assert math.isnan(series.travel_to(tmp_path / "missing.csv", 4.0))


def test_driven_scenario_holds_end_b_drives_it_and_releases_its_support(series):
    scenario = series.driven_scenario(300, 2.0, "bisector", 0.62, True)
    main = series.knot_program.knot_scenario(300, 2.0, tighten_line_search=True, section_pairing="bisector")
    assert scenario["stages"] == main["stages"]  # the knot tightened at 2 N, as the series' 2 N run
    driven, released = scenario["branches"]
    assert driven["name"] == "driven" and released["name"] == "driven_mu_0.30"
    assert driven["from"] == released["from"] == "settle"
    hold, drive, keep = driven["stages"]
    assert hold["activate"] == ["end_b"] and hold["loads"] == {"pull_b": {"force": [0, 0, 0]}}
    assert drive["motions"] == {"end_b": {"translation": [0.62, 0, 0]}}
    assert drive["duration"] == pytest.approx(6.2) and drive["steps"] == 62  # 0.1 mm/s, 0.01 mm a step
    assert "motions" not in keep and "loads" not in keep
    assert [st["name"] for st in released["stages"]] == ["hold", "drive", "keep", "release", "rest"]
    assert released["stages"][1]["motions"] == drive["motions"] and released["contact"] == {"friction": 0.3}
    release, rest = released["stages"][3:]
    assert release["release"] == ["end_b"] and rest["stabilization_end"] == 0
    assert [b["name"] for b in series.driven_scenario(300, 2.0, "bisector", 0.62, False)["branches"]] == ["driven"]


@pytest.mark.parametrize("arguments, option", [
    (["--driven", "2"], "--driven"), (["--driven", "1.5"], "--driven"), (["--driven", "4,x"], "--driven"),
    (["--driven", "4,,5"], "--driven"), (["--driven", "nan"], "--driven"),
    (["--driven", "4", "--driven-from", "0"], "--driven-from"), ([], "--forces")])
def test_bad_driven_forces_fail_with_one_line(series, tmp_path, capsys, arguments, option):
    assert series.main(["knot_force_series.py", str(tmp_path), "--forces", ""] + arguments) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"knot_force_series: {option}: expected")
    assert not any(tmp_path.iterdir())  # nothing written


def test_travel_to_skips_a_partly_written_last_line(series, tmp_path):
    path = tmp_path / "steps.csv"
    path.write_text("step,stage,time,end_b_fx\n1,hold,14,2.0\n2,drive,14.5,2.5\n3,drive,15")  # no end_b_fx yet
    assert math.isnan(series.travel_to(path, 4.0))
