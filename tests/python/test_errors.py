"""3. Bad input raises Python exceptions: ScenarioError (a ValueError) with the command line's message for a
bad value, and no crash for data that is no scenario at all."""

import numpy as np
import pytest

import nodus
from conftest import EXAMPLES, run_cli


def bad_file(tmp_path):
    """tool_drag.yaml with a negative Young's modulus; returns its path and the (1-based) line of the value."""
    lines = (EXAMPLES / "tool_drag.yaml").read_text(encoding="utf-8").splitlines(keepends=True)
    line = next(i for i, text in enumerate(lines) if "young_modulus: 4000" in text)
    lines[line] = lines[line].replace("young_modulus: 4000", "young_modulus: -4000")
    path = tmp_path / "bad.yaml"
    path.write_text("".join(lines), encoding="utf-8")
    return path, line + 1


def test_bad_value_in_a_file_has_the_command_lines_message(tmp_path):
    path, line = bad_file(tmp_path)
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.Scenario.from_yaml(path)
    e = error.value
    assert isinstance(e, ValueError)
    cli = run_cli("check", path, check_status=2)
    assert cli.stderr.strip() == f"nodus: {e}"
    assert "\n" not in str(e)
    assert e.file == str(path)
    assert e.line == line
    assert e.key == "materials[0].young_modulus"
    assert e.expected.startswith("a number > 0")
    # nodus.run refuses it the same way, before writing anything.
    out = tmp_path / "out"
    with pytest.raises(nodus.ScenarioError) as run_error:
        nodus.run(path, out, quiet=True)
    assert str(run_error.value) == str(e)
    assert not out.exists()


def test_a_missing_timing_folder_is_refused_before_anything_is_written(tmp_path):
    out, missing = tmp_path / "out", tmp_path / "no_such_run"
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.run(EXAMPLES / "tool_drag.yaml", out, quiet=True, timing_from=missing)
    assert str(error.value) == (f"{missing}: --timing-from: expected the output folder of an earlier run, "
                                "got nothing there")
    cli = run_cli("run", EXAMPLES / "tool_drag.yaml", "--out", out, "--timing-from", missing, check_status=2)
    assert cli.stderr.strip() == f"nodus: {error.value}"
    assert not out.exists()


def test_bad_value_in_a_dict_names_the_key_without_a_line(tmp_path):
    path, _ = bad_file(tmp_path)
    with pytest.raises(nodus.ScenarioError) as file_error:
        nodus.Scenario.from_yaml(path)
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["materials"][0]["young_modulus"] = -4000
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.Scenario(d)
    e = error.value
    assert isinstance(e, ValueError)
    # The file's message with '<dict>' for 'FILE:LINE'.
    after_location = str(file_error.value).split(": ", 1)[1]
    assert str(e) == f"<dict>: {after_location}"
    assert str(e).startswith("<dict>: materials[0].young_modulus: expected ")
    assert e.file == "<dict>"
    assert e.line is None
    assert e.key == "materials[0].young_modulus"
    with pytest.raises(nodus.ScenarioError):
        nodus.Simulation(d)


@pytest.mark.parametrize("data", [
    {1: 2},                                          # a non-str key at the top
    "to_dict_with_int_key",                          # a non-str key inside a section
    {"materials": object()},                         # an object of a type with no YAML form
    "to_dict_with_object",
    "to_dict_with_complex_array",
    [1, 2], 3, None, "examples/tool_drag.yaml", b"materials: []",  # not a dict
])
def test_data_that_is_no_scenario_raises(data):
    if data == "to_dict_with_int_key":
        data = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
        data["beams"][0][7] = 1
    elif data == "to_dict_with_object":
        data = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
        data["stages"][0]["motions"]["press"]["translation"] = [0, 0, object()]
    elif data == "to_dict_with_complex_array":
        data = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
        data["beams"][0]["start"] = np.array([1j, 0, 0])
    with pytest.raises(Exception) as error:
        nodus.Scenario(data)
    assert isinstance(error.value, (ValueError, TypeError)), repr(error.value)
    assert str(error.value)


def test_missing_file_raises(tmp_path):
    with pytest.raises(Exception) as error:
        nodus.Scenario.from_yaml(tmp_path / "missing.yaml")
    assert isinstance(error.value, (nodus.ScenarioError, OSError)), repr(error.value)
    assert "missing.yaml" in str(error.value)
    with pytest.raises(Exception):
        nodus.run(tmp_path / "missing.yaml", tmp_path / "out", quiet=True)
    assert not (tmp_path / "out").exists()


def test_out_folder_that_is_a_file_raises(tmp_path):
    target = tmp_path / "a_file"
    target.write_text("kept\n")
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.run(EXAMPLES / "bend_and_release.yaml", target, quiet=True)
    cli = run_cli("run", EXAMPLES / "bend_and_release.yaml", "--out", target, "--quiet", check_status=2)
    assert cli.stderr.strip() == f"nodus: {error.value}"
    assert target.read_text() == "kept\n"
    with pytest.raises(nodus.ScenarioError):
        nodus.run(EXAMPLES / "bend_and_release.yaml", target / "below", quiet=True)


def test_data_that_contains_itself_is_refused():
    d = nodus.Scenario.from_yaml(EXAMPLES / "bend_and_release.yaml").to_dict()
    d["beams"].append(d["beams"])
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.Scenario(d)
    assert "nested at most" in str(error.value) and error.value.line is None


def test_error_parts():
    d = nodus.Scenario.from_yaml(EXAMPLES / "bend_and_release.yaml").to_dict()
    d["materials"][0]["young_modulus"] = -4000
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.Scenario(d)
    e = error.value
    assert (e.file, e.line, e.key, e.got) == ("<dict>", None, "materials[0].young_modulus", "-4000")
    assert e.expected.startswith("a number > 0") and ", got" not in e.expected
