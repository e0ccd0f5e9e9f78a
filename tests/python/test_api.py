"""1. The API surface: names, docstrings, help(), and the names a Scenario reports against the file's text."""

import inspect
import pydoc

import pytest

import nodus
from conftest import DRAG_WITH_BRANCHES, EXAMPLES, run_cli, yaml_names

SHORT_EXAMPLES = ["bend_and_release.yaml", "tool_drag.yaml", "twisted_pair_detection.yaml"]


def own_doc(obj):
    return (obj.__doc__ or "").strip()


def test_every_public_name_exists_and_is_documented():
    for name in nodus.__all__:
        assert hasattr(nodus, name), name
        obj = getattr(nodus, name)
        if inspect.isclass(obj) or callable(obj):
            assert own_doc(obj), f"nodus.{name} has no docstring"
    # The data names: the version a text, and the two tables of names as docs/output.md lists them.
    assert isinstance(nodus.__version__, str) and nodus.__version__
    assert nodus.contact_states == ("open", "stick", "slip")
    assert nodus.strain_names == ("e11", "e22", "e12", "e13", "e23", "e33", "q11", "q12", "q21", "q22",
                                  "k1", "k2", "m11", "m22", "m12")


@pytest.mark.parametrize("cls", [nodus.Scenario, nodus.Simulation, nodus.RunOutcome, nodus.ScenarioError])
def test_public_members_are_documented(cls):
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if callable(member) or isinstance(member, (property, classmethod, staticmethod)) or \
                hasattr(member, "__get__"):
            assert own_doc(member), f"{cls.__name__}.{name} has no docstring"


def test_help_renders():
    text = pydoc.render_doc(nodus, renderer=pydoc.plaintext)
    for name in ("Scenario", "Simulation", "ScenarioError", "RunOutcome", "run", "keys", "knot_invariant"):
        assert name in text
    assert "mm, N, MPa, s" in text  # the module docstring


@pytest.mark.parametrize("example", SHORT_EXAMPLES)
def test_scenario_names_are_those_of_the_file(example):
    path = EXAMPLES / example
    s = nodus.Scenario.from_yaml(path)
    assert s.beams == yaml_names(path, "beams")
    assert s.conditions == yaml_names(path, "conditions")
    assert s.stages == yaml_names(path, "stages")
    assert s.branches == yaml_names(path, "branches") == []
    assert s.path == str(path)
    assert len(s.beams) > 0 and len(s.stages) > 0


def test_scenario_branch_names(tmp_path):
    path = tmp_path / "branches.yaml"
    path.write_text(DRAG_WITH_BRANCHES)
    s = nodus.Scenario.from_yaml(path)
    assert s.branches == ["same", "mu_0.1"]
    assert s.stages == ["press", "drag", "back", "lift"]
    assert names_from_dict(s) == (s.beams, s.conditions, s.stages, s.branches)


def names_from_dict(s):
    """The names of the Scenario built from s's data (a dict: no path)."""
    d = nodus.Scenario(s.to_dict())
    assert d.path is None
    return d.beams, d.conditions, d.stages, d.branches


def test_keys_is_the_command_lines_table():
    assert nodus.keys() == run_cli("keys", check_status=0).stdout


def test_distances_of_polylines_against_closed_forms():
    """min_distance_between: two skew lines h apart, closest at their origins (no vertices); min_self_distance:
    the same lines joined far away, with the separation larger than any pair on one line."""
    np = pytest.importorskip("numpy")
    h, n = 0.4, 6
    a = np.column_stack([np.linspace(-3, 3, n), np.zeros(n), np.zeros(n)])
    b = np.column_stack([np.zeros(n + 2), np.linspace(-3, 3, n + 2), np.full(n + 2, h)])
    s_a, s_b = np.linspace(0, 6, n), np.linspace(0, 6, n + 2)
    distance, s1, s2 = nodus.min_distance_between(a, s_a, b, s_b)
    assert distance == pytest.approx(h, abs=1e-14)
    assert (s1, s2) == (pytest.approx(3, abs=1e-12), pytest.approx(3, abs=1e-12))
    joined = np.vstack([a, b[::-1]])  # a, then b from its far end: the connector joins (3, 0, 0) to (0, 3, h)
    s_joined = np.concatenate([s_a, s_a[-1] + np.hypot(3, np.hypot(3, h)) + s_b])
    distance, s1, s2 = nodus.min_self_distance(joined, s_joined, 7.0)
    assert distance == pytest.approx(h, abs=1e-14)
    with pytest.raises(ValueError):
        nodus.min_distance_between(a, s_a[:-1], b, s_b)
