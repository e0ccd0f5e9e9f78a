"""2. Scenarios from files and from Python data: the same scenario (canonical_text()) whichever way it is
built, written back as YAML and read by the command line."""

import numpy as np
import pytest

import nodus
from conftest import DRAG_WITH_BRANCHES, EXAMPLES, run_cli

SHORT_EXAMPLES = ["bend_and_release.yaml", "tool_drag.yaml", "twisted_pair_detection.yaml"]


@pytest.mark.parametrize("example", SHORT_EXAMPLES)
def test_dict_and_yaml_round_trips_give_the_same_scenario(example, tmp_path):
    path = EXAMPLES / example
    from_file = nodus.Scenario.from_yaml(path)
    reference = from_file.canonical_text()
    assert "materials[0].young_modulus" in reference

    from_dict = nodus.Scenario(from_file.to_dict())
    assert from_dict.canonical_text() == reference
    assert nodus.Scenario(from_dict).canonical_text() == reference  # a Scenario is accepted as data too

    written = tmp_path / "written.yaml"
    text = from_dict.to_yaml(written)
    assert written.read_text(encoding="utf-8") == text
    run_cli("check", written, check_status=0)
    assert nodus.Scenario.from_yaml(written).canonical_text() == reference
    # The resolved-settings echo is the command line's.
    assert from_file.describe() in run_cli("check", path, check_status=0).stdout


def test_branches_survive_the_round_trip(tmp_path):
    path = tmp_path / "branches.yaml"
    path.write_text(DRAG_WITH_BRANCHES)
    s = nodus.Scenario.from_yaml(path)
    again = tmp_path / "again.yaml"
    nodus.Scenario(s.to_dict()).to_yaml(again)
    run_cli("check", again, check_status=0)
    assert nodus.Scenario.from_yaml(again).branches == ["same", "mu_0.1"]
    assert nodus.Scenario.from_yaml(again).canonical_text() == s.canonical_text()


def test_friction_pairs_survive_the_round_trip(tmp_path):
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["contact"]["friction_pairs"] = [{"beams": ["tool"], "with": ["beam"], "friction": 0.05}]
    s = nodus.Scenario(d)
    assert "contact.friction_pairs[0].friction = 0.050000000000000003" in s.canonical_text()
    assert "- {beams: [tool], with: [beam], friction: 0.05}" in s.describe()
    written = tmp_path / "pairs.yaml"
    s.to_yaml(written)
    assert nodus.Scenario.from_yaml(written).canonical_text() == s.canonical_text()
    d["contact"]["friction_pairs"][0]["beams"] = ["tol"]
    with pytest.raises(nodus.ScenarioError, match=r"contact.friction_pairs\[0\].beams\[0\]: expected the name of a beam"):
        nodus.Scenario(d)


def test_to_dict_is_a_copy():
    s = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml")
    d = s.to_dict()
    d["materials"][0]["young_modulus"] = 1234
    assert s.to_dict()["materials"][0]["young_modulus"] == 4000  # the file's value
    changed = nodus.Scenario(d).canonical_text()
    assert "materials[0].young_modulus = 1234" in changed
    assert changed != s.canonical_text()


def test_numpy_values_are_accepted():
    s = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml")
    d = s.to_dict()
    d["beams"][0]["start"] = np.array([-5.0, 0.0, 0.0])
    d["beams"][0]["direction"] = np.array([1, 0, 0], dtype=np.int32)
    d["beams"][0]["elements"] = np.int64(60)
    d["beams"][1]["radius"] = np.float32(0.2)  # 0.2 is not a float32: the value read is float32(0.2)
    d["materials"][0]["young_modulus"] = np.float64(4000)
    d["stages"][0]["motions"]["press"]["translation"] = np.array([0, 0, -0.1])
    d["contact"]["self_contact"] = np.bool_(False)
    from_numpy = nodus.Scenario(d)
    reference = s.to_dict()
    reference["beams"][1]["radius"] = float(np.float32(0.2))
    assert from_numpy.canonical_text() == nodus.Scenario(reference).canonical_text()
    assert nodus.Scenario(reference).canonical_text() != s.canonical_text()  # the float32 did change it
    # A to_dict() of a scenario built from numpy values holds plain Python types.
    plain = from_numpy.to_dict()
    assert type(plain["beams"][0]["elements"]) is int
    assert all(type(x) in (int, float) for x in plain["beams"][0]["start"])


def test_validate(tmp_path):
    for example in SHORT_EXAMPLES:
        nodus.Scenario.from_yaml(EXAMPLES / example).validate()
    # A check of the model, not of the reader: a node held by two conditions. Built, then refused by
    # validate() with the message of `nodus check`.
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["conditions"].append({"name": "again", "type": "clamp", "beam": "beam", "at": "start"})
    path = tmp_path / "two_clamps.yaml"
    nodus.Scenario(d).to_yaml(path)
    s = nodus.Scenario.from_yaml(path)
    with pytest.raises(nodus.ScenarioError) as error:
        s.validate()
    cli = run_cli("check", path, check_status=2)
    assert cli.stderr.strip() == f"nodus: {error.value}"
    assert error.value.key == "conditions[3].dofs"
    assert "'left' and 'again'" in str(error.value)


def test_validate_of_a_dict_names_the_dict():
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["conditions"].append({"name": "again", "type": "clamp", "beam": "beam", "at": "start"})
    with pytest.raises(nodus.ScenarioError) as error:
        nodus.Scenario(d).validate()
    assert str(error.value).startswith("<dict>: conditions[3].dofs: expected ")
    assert error.value.line is None
