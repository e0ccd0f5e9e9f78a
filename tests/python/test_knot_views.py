"""scripts/knot_views.py (3D views of a knot run) on a synthetic run folder, and its geometry against closed forms.

Checked against what:
  files        a run folder with one stage end (the rod and a second beam in contact with it), a final state
               that differs from it and one branch listed in summary.json: the script exits 0 and writes
               exactly view3d_stage_000_loop.png, view3d_final.png and view3d_mu_0.30.png, PNG files that
               are not blank (some pixels of the rod's blue), and no temporary file.
  tube         on a helix (closed form), every tube vertex lies at distance R from the centreline point of
               its ring, and the parallel-transport frame is orthonormal, normal to the tangent and turns
               about it by less than the turning angle of the tangent between nodes (rotation-minimising).
  stripe       directors made by turning the frame by a known angle give back that angle.
  bad input    a folder with nothing to draw: exit status 2 and one line on stderr naming the folder.
Needs Debian's python3-matplotlib (skipped without it); not the nodus module.
"""

import importlib.util
import json
import subprocess
import sys

import numpy as np
import pytest

from conftest import SOURCE_DIR

pytest.importorskip("matplotlib")

SCRIPT = SOURCE_DIR / "scripts" / "knot_views.py"
NODE_HEADER = "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z"
CONTACT_HEADER = ("zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,"
                  "nx,ny,nz,gap,normal_force,tangential_force,tx,ty,tz,state")
RADIUS = 0.1


@pytest.fixture(scope="module")
def views():
    spec = importlib.util.spec_from_file_location("knot_views", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def helix(turns=1.5, radius=1.0, pitch=0.8, nodes=121):
    """(s, r): nodes of a helix by arc length."""
    theta = np.linspace(0.0, 2 * np.pi * turns, nodes)
    c = np.hypot(radius, pitch / (2 * np.pi))
    r = np.column_stack([radius * np.cos(theta), radius * np.sin(theta), pitch * theta / (2 * np.pi)])
    return c * theta, r


def write_nodes(path, beams):
    """beams: [(name, s, r)]; directors g1 = z x t (normalised), g2 = t x g1, with t the chord direction."""
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [NODE_HEADER]
    for name, s, r in beams:
        t = np.gradient(r, axis=0)
        t /= np.linalg.norm(t, axis=1, keepdims=True)
        g1 = np.cross([0.0, 0.0, 1.0], t)
        g1 /= np.linalg.norm(g1, axis=1, keepdims=True)
        g2 = np.cross(t, g1)
        for k in range(len(s)):
            lines.append(",".join([name, str(k)] + [repr(float(v)) for v in (s[k], *r[k], *g1[k], *g2[k])]))
    path.write_text("\n".join(lines) + "\n")


def write_contact(path, pairs):
    """pairs: [(beam_i, beam_j, s_i, s_j, x_i, x_j, n, R_N)], all in zone 0."""
    lines = [CONTACT_HEADER]
    for k, (bi, bj, si, sj, xi, xj, n, force) in enumerate(pairs):
        values = [0, bi, bj, k / max(len(pairs) - 1, 1), si, sj, 0, 0, 0, 0, *xi, *xj, *n, 0.0, force, 0, 0, 0, 0,
                  "stick" if force > 0 else "open"]
        lines.append(",".join(str(v) for v in values))
    path.write_text("\n".join(lines) + "\n")


def helix_state(folder_nodes, folder_contact, pitch, with_tool):
    """A helix rod whose successive turns touch when pitch = 2 R: contact elements between nodes a turn
    apart, particles on the surfaces facing each other; optionally a straight second beam beside it."""
    s, r = helix(pitch=pitch)
    beams = [("rod", s, r)]
    if with_tool:
        beams.append(("clamp", np.linspace(0, 2, 13), np.column_stack([np.full(13, 1.3), np.linspace(-1, 1, 13),
                                                                       np.zeros(13)])))
    write_nodes(folder_nodes, beams)
    per_turn = 80
    pairs = []
    for k in range(10, 30, 2):
        lower, upper = r[k], r[k + per_turn]
        n = (upper - lower) / np.linalg.norm(upper - lower)
        pairs.append(("rod", "rod", s[k], s[k + per_turn], lower + RADIUS * n, upper - RADIUS * n, n,
                      0.01 * k))
    write_contact(folder_contact, pairs)


def test_views_of_a_run_folder(tmp_path):
    run = tmp_path / "run"
    helix_state(run / "stages" / "000_loop_nodes.csv", run / "stages" / "000_loop_contact.csv", 0.3, True)
    helix_state(run / "final_nodes.csv", run / "contact_final.csv", 0.2, False)
    helix_state(run / "branches" / "mu_0.30" / "final_nodes.csv",
                run / "branches" / "mu_0.30" / "contact_final.csv", 0.25, False)
    (run / "summary.json").write_text(json.dumps(
        {"branches": [{"name": "mu_0.30", "folder": "branches/mu_0.30", "friction": 0.3}]}))
    out = tmp_path / "views"
    result = subprocess.run([sys.executable, str(SCRIPT), str(run), "--out", str(out), "--dpi", "60"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    expected = ["view3d_final.png", "view3d_mu_0.30.png", "view3d_stage_000_loop.png"]
    assert sorted(p.name for p in out.iterdir()) == expected      # no temporary left either
    import matplotlib.image
    for name in expected:
        data = (out / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 5_000, name
        pixels = matplotlib.image.imread(out / name)[..., :3]
        blue = (pixels[..., 2] > pixels[..., 0] + 0.15) & (pixels[..., 2] > 0.4)
        assert blue.mean() > 0.005, f"{name}: no rod drawn"


def test_tube_around_a_helix(views):
    s, r = helix()
    t = views.tangents(r)
    e1, e2 = views.transport_frame(t)
    np.testing.assert_allclose(np.einsum("ij,ij->i", e1, t), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(e1, axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(np.cross(t, e1), e2, atol=1e-12)
    # Rotation-minimising: e1 turns between nodes by no more than the tangent does.
    turn_t = np.arccos(np.clip(np.einsum("ij,ij->i", t[1:], t[:-1]), -1, 1))
    turn_e1 = np.arccos(np.clip(np.einsum("ij,ij->i", e1[1:], e1[:-1]), -1, 1))
    assert np.all(turn_e1 <= turn_t + 1e-9)
    sides = 10
    polygons, normals, _ = views.tube_facets(r, t, e1, e2, RADIUS, sides)
    assert len(polygons) == (len(r) - 1) * sides + 2
    quads = np.array(polygons[:-2])                    # vertices 0, 1 on ring k; 2, 3 on ring k + 1
    ring = np.repeat(np.arange(len(r) - 1), sides)
    np.testing.assert_allclose(np.linalg.norm(quads[:, 0] - r[ring], axis=1), RADIUS, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(quads[:, 2] - r[ring + 1], axis=1), RADIUS, rtol=1e-12)
    outward = quads.mean(axis=1) - 0.5 * (r[ring] + r[ring + 1])
    assert np.all(np.einsum("ij,ij->i", normals[:-2], outward) > 0)


def test_director_stripe_angle(views):
    s, r = helix(nodes=41)
    t = views.tangents(r)
    e1, e2 = views.transport_frame(t)
    angle = np.linspace(-3.0, 3.0, len(s))
    g1 = np.cos(angle)[:, None] * e1 + np.sin(angle)[:, None] * e2
    beam = views.Beam("rod", s, r, g1, np.cross(t, g1))
    np.testing.assert_allclose(views.director_angle(beam, t, e1, e2), angle, atol=1e-12)
    # g1 along the tangent (a folded element): the angle comes from g2, turned back by 90 degrees.
    g1_folded = g1.copy()
    g1_folded[5] = t[5]
    beam = views.Beam("rod", s, r, g1_folded, np.cross(t, g1))
    assert views.director_angle(beam, t, e1, e2)[5] == pytest.approx(angle[5], abs=1e-12)


def test_nothing_to_draw_is_one_line(views, tmp_path, capsys):
    assert views.main(["knot_views.py", str(tmp_path)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and str(tmp_path) in lines[0]
