"""5. Simulation: its arrays against the CSV files of a command-line run of the same scenario, its views, and
stepping (step, run_stage, callbacks) against running in one call and against steps.csv."""

import csv

import numpy as np
import pytest

import nodus
from conftest import EXAMPLES, run_cli

# final_nodes.csv prints 12 significant digits, contact_final.csv 10 (docs/output.md): the rounding error of
# a printed value is at most half a unit of its last digit, below 5e-12 and 5e-10 of the value.
NODES_RTOL = 1e-11
CONTACT_RTOL = 1e-9


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def columns(rows, names, dtype=float):
    return np.array([[dtype(r[n]) for n in names] for r in rows])


def tool_drag_in_contact():
    """tool_drag without its last stage (`lift` takes the tool off): the run ends pressing and dragging, with
    contact forces and friction."""
    d = nodus.Scenario.from_yaml(EXAMPLES / "tool_drag.yaml").to_dict()
    d["stages"] = [st for st in d["stages"] if st["name"] != "lift"]
    return d


def cli_outputs(scenario, tmp_path):
    """The output folder of `nodus run` on the scenario, written to a file first."""
    path = tmp_path / "scenario.yaml"
    scenario.to_yaml(path)
    out = tmp_path / "cli"
    run_cli("run", path, "--out", out, "--quiet", check_status=0)
    return out


@pytest.fixture(scope="module", params=["bend_and_release", "tool_drag_in_contact", "twisted_pair_detection"])
def finished(request, tmp_path_factory):
    """(scenario, Simulation run to its end, the CLI's output folder of the same scenario)."""
    if request.param == "tool_drag_in_contact":
        scenario = nodus.Scenario(tool_drag_in_contact())
    else:
        scenario = nodus.Scenario.from_yaml(EXAMPLES / f"{request.param}.yaml")
    sim = nodus.Simulation(scenario)
    sim.run()
    assert sim.finished and sim.failure == ""
    return scenario, sim, cli_outputs(scenario, tmp_path_factory.mktemp(request.param))


def test_node_arrays_equal_final_nodes_csv(finished):
    scenario, sim, out = finished
    rows = read_csv(out / "final_nodes.csv")
    assert list(rows[0].keys()) == ["beam", "node", "s", "x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"]
    assert sim.positions.shape == sim.d1.shape == sim.d2.shape == (len(rows), 3)
    np.testing.assert_allclose(sim.positions, columns(rows, ["x", "y", "z"]), rtol=NODES_RTOL, atol=0)
    np.testing.assert_allclose(sim.d1, columns(rows, ["g1x", "g1y", "g1z"]), rtol=NODES_RTOL, atol=0)
    np.testing.assert_allclose(sim.d2, columns(rows, ["g2x", "g2y", "g2z"]), rtol=NODES_RTOL, atol=0)
    np.testing.assert_array_equal(sim.state.reshape(-1, 9)[:, 0:3], sim.positions)
    np.testing.assert_array_equal(sim.state.reshape(-1, 9)[:, 3:6], sim.d1)
    np.testing.assert_array_equal(sim.state.reshape(-1, 9)[:, 6:9], sim.d2)
    # The beam of each node, and its local index, as the file lists them.
    assert [scenario.beams[b] for b in sim.node_beam] == [r["beam"] for r in rows]
    local = np.concatenate([np.arange(np.count_nonzero(sim.node_beam == b)) for b in range(len(scenario.beams))])
    np.testing.assert_array_equal(local, [int(r["node"]) for r in rows])
    # s: the reference arc length, the distance from the beam's first node in the (straight) reference.
    ref = sim.reference_positions
    first = np.array([np.flatnonzero(sim.node_beam == b)[0] for b in sim.node_beam])
    np.testing.assert_allclose(np.linalg.norm(ref - ref[first], axis=1), columns(rows, ["s"])[:, 0],
                               rtol=NODES_RTOL, atol=1e-12)
    # The last record is the last row of steps.csv.
    steps = read_csv(out / "steps.csv")
    assert sim.steps == sim.last_step["step"] == int(steps[-1]["step"])
    assert sim.time == pytest.approx(float(steps[-1]["time"]), rel=1e-9)


def test_mesh_arrays_are_consistent(finished):
    scenario, sim, _ = finished
    beams = scenario.to_dict()["beams"]
    elements = [b["elements"] for b in beams]
    np.testing.assert_array_equal(np.bincount(sim.element_beam, minlength=len(beams)), elements)
    np.testing.assert_array_equal(np.bincount(sim.node_beam, minlength=len(beams)), [2 * n + 1 for n in elements])
    assert np.all(np.diff(sim.node_beam) >= 0) and np.all(np.diff(sim.element_beam) >= 0)
    nodes = sim.element_nodes
    assert nodes.shape == (sum(elements), 3)
    np.testing.assert_array_equal(nodes[:, 1] - nodes[:, 0], 1)
    np.testing.assert_array_equal(nodes[:, 2] - nodes[:, 1], 1)
    for k in range(3):
        np.testing.assert_array_equal(sim.node_beam[nodes[:, k]], sim.element_beam)
    # Consecutive elements of a beam share their end node; every node of a beam is in one of its elements.
    same_beam = sim.element_beam[1:] == sim.element_beam[:-1]
    np.testing.assert_array_equal(nodes[1:, 0][same_beam], nodes[:-1, 2][same_beam])
    assert set(nodes.ravel()) == set(range(len(sim.node_beam)))
    assert sim.element_strains().shape == (sum(elements), 15)
    assert sim.node_strains().shape == (len(sim.node_beam), 15)


def test_contact_arrays_equal_contact_final_csv(finished):
    scenario, sim, out = finished
    c = sim.contact_elements()
    if "contact" not in scenario.to_dict():  # bend_and_release: no contact, no contact files
        assert not (out / "contact_final.csv").exists()
        assert all(len(v) == 0 for v in c.values())
        return
    rows = read_csv(out / "contact_final.csv")
    assert len(rows) > 0 and len(c["zone"]) == len(rows)
    names = scenario.beams
    np.testing.assert_array_equal(c["zone"], [int(r["zone"]) for r in rows])
    assert [names[b] for b in c["beam_i"]] == [r["beam_i"] for r in rows]
    assert [names[b] for b in c["beam_j"]] == [r["beam_j"] for r in rows]
    for key, cols in [("zeta", ["zeta"]), ("abscissa_i", ["abscissa_i"]), ("abscissa_j", ["abscissa_j"]),
                      ("gap", ["gap"]), ("normal_force", ["normal_force"]),
                      ("tangential_force", ["tangential_force"])]:
        np.testing.assert_allclose(c[key], columns(rows, cols)[:, 0], rtol=CONTACT_RTOL, atol=0, err_msg=key)
    for key, cols in [("position_i", ["x_i", "y_i", "z_i"]), ("position_j", ["x_j", "y_j", "z_j"]),
                      ("normal", ["nx", "ny", "nz"]), ("friction_force", ["tx", "ty", "tz"])]:
        np.testing.assert_allclose(c[key], columns(rows, cols), rtol=CONTACT_RTOL, atol=0, err_msg=key)
    assert [nodus.contact_states[s] for s in c["state"]] == [r["state"] for r in rows]
    # The columns of steps.csv are sums over these rows (docs/output.md).
    last = sim.last_step
    assert last["contact_elements"] == len(rows)
    assert last["normal_force"] == pytest.approx(c["normal_force"].sum(), rel=1e-12)
    assert last["slipping"] == np.count_nonzero(c["state"] == 2)
    zones = sim.zones()
    assert len(zones["beam_i"]) == last["zones"] == len(read_csv(out / "zones_final.csv"))
    assert zones["contact_elements"].sum() == len(rows)


def test_contact_has_forces_where_expected(finished):
    scenario, sim, out = finished
    c = sim.contact_elements()
    if scenario.path is None:  # tool_drag_in_contact: the tool presses and drags with friction
        assert c["normal_force"].max() > 0 and c["tangential_force"].max() > 0
    elif not scenario.to_dict().get("contact"):  # bend_and_release: no contact section
        assert len(c["zone"]) == 0 and len(sim.zones()["beam_i"]) == 0
    else:  # twisted_pair_detection: contact forces on, so every element has its force and state
        assert len(c["zone"]) > 0 and np.isfinite(c["normal_force"]).all() and (c["state"] >= 0).all()


def test_step_count_must_be_positive_and_a_running_simulation_is_not_reentered():
    sim = nodus.Simulation(EXAMPLES / "bend_and_release.yaml")
    with pytest.raises(ValueError):
        sim.step(0)
    assert sim.steps == 0
    with pytest.raises(RuntimeError, match="already running"):
        sim.step(callback=lambda record: sim.step())
    assert sim.steps == 1  # the step that called back converged; the run stopped after it
    assert sim.step()["step"] == 2


def test_views_are_read_only_and_follow_the_run():
    sim = nodus.Simulation(EXAMPLES / "bend_and_release.yaml")
    views = [sim.positions, sim.d1, sim.d2]
    for view in views:
        with pytest.raises(ValueError):
            view[0, 0] = 1.0
        with pytest.raises(ValueError):
            view.setflags(write=True)
    before = [np.array(v) for v in views]
    np.testing.assert_array_equal(before[0], sim.reference_positions)
    sim.step()
    after = [np.array(v) for v in (sim.positions, sim.d1, sim.d2)]
    assert not np.array_equal(before[0], after[0])  # the tip moved
    for view, now in zip(views, after):
        np.testing.assert_array_equal(view, now)  # the old view shows the new state
    del sim  # a view keeps the state alive
    np.testing.assert_array_equal(views[0], after[0])


def test_steps_and_callbacks(tmp_path):
    path = EXAMPLES / "bend_and_release.yaml"
    run_cli("run", path, "--out", tmp_path / "cli", "--quiet", check_status=0)
    expected = read_csv(tmp_path / "cli" / "steps.csv")
    stage_of_row = [r["stage"] for r in expected]
    sim = nodus.Simulation(path)
    assert sim.steps == 0 and sim.last_step is None and sim.stage == "bend" and sim.reactions == {}
    records = []
    first = sim.run_stage(callback=records.append)
    assert first["ends_stage"] and first["stage"] == "bend"
    assert len(records) == stage_of_row.count("bend") and records[-1] == first
    assert all(not r["ends_stage"] for r in records[:-1])
    assert sim.stage == "release"
    assert sim.run(callback=records.append) == stage_of_row.count("release")
    assert [r["step"] for r in records] == list(range(1, len(expected) + 1))
    assert [r["stage"] for r in records] == stage_of_row
    assert [r["time"] for r in records] == pytest.approx([float(r["time"]) for r in expected], rel=1e-9)
    # What made each step hard, as steps.csv says it (csv reads its quoted causes back as one field).
    for r, row in zip(records, expected):
        assert r["step_size"] == pytest.approx(float(row["step_size"]), rel=1e-9)
        assert [r[k] for k in ("entered", "left", "to_slip", "to_stick")] == \
            [int(row[k]) for k in ("entered", "left", "to_slip", "to_stick")]
        assert len(r["cutback_causes"]) == r["cutbacks"] == int(row["cutbacks"])
        assert " | ".join(r["cutback_causes"]) == row["cutback_causes"]
    assert sim.finished and sim.stage is None and sim.steps == len(expected)
    assert sim.run() == 0 and sim.run_stage() is None and sim.step() is None  # nothing left to do
    assert sim.last_step["step"] == sim.steps == len(expected)
    assert set(sim.reactions) == set(nodus.Scenario.from_yaml(path).conditions)
    np.testing.assert_allclose(sim.reactions["root"]["force"],
                               [float(expected[-1][f"root_f{a}"]) for a in "xyz"], rtol=1e-9, atol=1e-12)


def test_step_of_a_finished_run_returns_none():
    sim = nodus.Simulation(EXAMPLES / "bend_and_release.yaml")
    sim.run()
    assert sim.step() is None


def test_callback_returning_false_stops_the_run():
    sim = nodus.Simulation(EXAMPLES / "bend_and_release.yaml")
    seen = []
    sim.run(callback=lambda r: seen.append(r["step"]) or r["step"] < 3)
    assert seen == [1, 2, 3] and sim.steps == 3 and not sim.finished
    record = sim.step(2)
    assert record["step"] == 5 and sim.steps == 5


def test_callback_raising_propagates():
    class Stop(Exception):
        pass

    def callback(record):
        if record["step"] == 2:
            raise Stop("from the callback")

    sim = nodus.Simulation(EXAMPLES / "bend_and_release.yaml")
    with pytest.raises(Stop, match="from the callback"):
        sim.run(callback=callback)
    assert sim.steps == 2 and sim.failure == ""
    assert sim.step()["step"] == 3  # the run goes on


def test_one_step_at_a_time_equals_one_run():
    whole = nodus.Simulation(EXAMPLES / "tool_drag.yaml")
    whole.run()
    stepped = nodus.Simulation(EXAMPLES / "tool_drag.yaml")
    n = 0
    while not stepped.finished:
        assert stepped.step()["step"] == n + 1
        n += 1
    assert n == whole.steps and stepped.time == whole.time
    np.testing.assert_array_equal(stepped.state, whole.state)
    np.testing.assert_array_equal(stepped.positions, whole.positions)


def test_rigid_bodies_equal_the_body_columns_of_steps_csv(tmp_path):
    """A yarn of three fibres pulled by its end bodies: rigid_bodies() against the BODY_* columns of the command
    line's steps.csv (10 significant digits), and the body's point moved with its motion."""
    scenario = nodus.Scenario({
        "materials": [{"name": "m", "young_modulus": 4000, "poisson_ratio": 0.3}],
        "yarns": [{"name": "y", "rovings": 3, "fibres_per_roving": 1, "fibre_radius": 0.05, "length": 2,
                   "elements": 4, "material": "m"}],
        "conditions": [
            {"name": "hold", "type": "clamp", "bodies": ["y.r1.start", "y.r2.start", "y.r3.start"]},
            {"name": "pull", "type": "motion", "bodies": ["y.r1.end", "y.r2.end", "y.r3.end"]}],
        "stages": [{"name": "stretch", "steps": 2, "motions": {"pull": {"translation": [0.002, 0, 0]}}}],
    })
    sim = nodus.Simulation(scenario)
    assert sim.rigid_bodies() == {}
    sim.run()
    bodies = sim.rigid_bodies()
    assert sorted(bodies) == sorted(f"y.r{k}.{end}" for k in (1, 2, 3) for end in ("start", "end"))
    last = read_csv(cli_outputs(scenario, tmp_path) / "steps.csv")[-1]
    for name, body in bodies.items():
        got = np.concatenate([body["force"], body["moment"], [body["error"], body["tie"]]])
        want = [float(last[f"{name}_{c}"]) for c in ("fx", "fy", "fz", "mx", "my", "mz", "error", "tie")]
        np.testing.assert_allclose(got, want, rtol=CONTACT_RTOL, atol=1e-15)
    end = bodies["y.r1.end"]
    start = sim.reference_positions[sim.node_beam == 0][-1]  # the fibre's end node, before the pull
    np.testing.assert_allclose(end["position"][0] - start[0], 0.002, rtol=1e-12)
    assert end["force"][0] > 0 and bodies["y.r1.start"]["force"][0] < 0
