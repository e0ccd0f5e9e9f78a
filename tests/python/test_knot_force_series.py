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
