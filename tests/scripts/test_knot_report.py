#!/usr/bin/env python3
"""Tests scripts/knot_report.py on synthetic run folders of known geometry. Each expected number comes
from the construction in closed form. None is taken from the script's own output.

Checked against what:
  tail angle       rods whose tails leave the knot straight for 2 mm (then turn) along unit directions
                   u_a, u_b set at a chosen angle (120, 180, and 90 with tail B shorter than the 2 mm
                   chord, so the chord stops at the rod end): the reported angle is that angle. s_a, s_b
                   are the extreme abscissas of the elements with normal_force > 0 (the elements with zero
                   force lie outside).
  loop             a "lasso" rod: straight, then a circular arc (radius 0.8 mm, 300 or 330 degrees, in a
                   tilted plane), then straight again. Contact elements cover only the straight parts, and
                   the elements nearest the arc sit exactly at its ends s_1, s_2. By the documented
                   definition the loop is [s_1 + h, s_2 - h] (h = half the element spacing, floored at
                   0.05 / 2): the radius is 0.8, the length is (s_2 - s_1) - 2 h, and the tail angle is
                   arc - 180 degrees.
  intermediate     two zones of particle pairs placed symmetrically about a straight midline (spacing d)
                   and a circular one (radius rho, step dtheta). The abscissa is k d, then the end of zone
                   0 plus k 2 rho sin(dtheta / 2), since the polyline of a circle's points uses chords.
                   Also checked: the length between the first and last element in contact (zero-force
                   elements at both ends), the max and sum of the reactions, and the max penetration.
  other beams      a stage table with the rod and two other beams, one paired with the rod in the stage's
                   contact table: that one only is returned for drawing, its nodes sorted by s.
  end to end       a fake run folder (tightened state, branch mu_0.30, one stage). The script exits 0 and
                   writes knot_report.csv: one row per state, friction 0.3 for the branch, pull force
                   |(0.3, 0.4, 0)| = 0.5 from the last row of steps.csv, tail angles 120 and 150, loop
                   radius 0.8. It also writes the reactions CSVs, the four PNG figures and the three 3D
                   views (scripts/knot_views.py), and leaves no temporary file.
  bad input        a missing contact_final.csv or a missing column: the exit status is not 0, and stderr
                   holds one line that names the file.

Run: /usr/bin/python3 tests/scripts/test_knot_report.py (Debian's numpy and matplotlib), from any directory.
"""

import csv
import importlib.util
import math
import random
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "knot_report.py"
_spec = importlib.util.spec_from_file_location("knot_report", SCRIPT)
kr = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(kr)

NODE_HEADER = "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z".split(",")
CONTACT_HEADER = ("zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,"
                  "x_j,y_j,z_j,nx,ny,nz,gap,normal_force,tangential_force,tx,ty,tz,state").split(",")
STEPS_HEADER = ("step,stage,time,stabilization_force,min_orientation,min_chord,pull_b_fx,pull_b_fy,"
                "pull_b_fz").split(",")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FIGURES = ["fig14_tightened_reactions.png", "fig17_released_reactions.png", "fig12_stages.png",
           "fig15_released_knots.png",
           # the 3D views of scripts/knot_views.py: the stage end, the final state (not the stage end's),
           # the branch
           "view3d_stage_000_loop.png", "view3d_final.png", "view3d_mu_0.30.png"]

S = np.linspace(0.0, 20.0, 401)   # rod arc length of the nodes: 0 to 20 mm, spacing 0.05 mm


def rotation(axis, angle):
    """Rotation matrix about `axis` by `angle` (Rodrigues)."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


E1, E2, E3 = rotation([1.0, 2.0, 3.0], 0.7).T   # an orthonormal frame tilted out of the xy plane


def unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def direction_at(u, w, degrees):
    """The unit vector at `degrees` from unit u, in the plane of u and w (w perpendicular to u)."""
    a = math.radians(degrees)
    return math.cos(a) * u + math.sin(a) * w


# ---------------------------------------------------------------------------------------- tables

def write_table(path, header, rows):
    """Writes rows (dicts; missing columns as 0) with floats in full precision (repr)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(header)
        for row in rows:
            out.writerow([repr(float(v)) if isinstance(v, (float, np.floating)) else v
                          for v in (row.get(c, 0) for c in header)])


def node_rows(s, points, beam="rod"):
    """Rows of final_nodes.csv: one beam, node k at arc length s[k], position points[k]."""
    return [{"beam": beam, "node": k, "s": s[k], "x": p[0], "y": p[1], "z": p[2], "g1x": 1.0, "g2y": 1.0}
            for k, p in enumerate(points)]


def contact_row(zone, zeta, s_i, s_j, x_i, x_j, normal, tangential=0.0, gap=0.0):
    """A row of contact_final.csv; state open without normal force, else slip or stick."""
    n = unit(np.subtract(x_j, x_i))
    state = "open" if normal <= 0 else ("slip" if tangential > 0 else "stick")
    return {"zone": zone, "beam_i": "rod", "beam_j": "rod", "zeta": zeta, "abscissa_i": s_i,
            "abscissa_j": s_j, "x_i": x_i[0], "y_i": x_i[1], "z_i": x_i[2], "x_j": x_j[0], "y_j": x_j[1],
            "z_j": x_j[2], "nx": n[0], "ny": n[1], "nz": n[2], "gap": gap, "normal_force": normal,
            "tangential_force": tangential, "state": state}


def write_run(folder, nodes, contact, steps=None):
    """final_nodes.csv, contact_final.csv and (if given) steps.csv of one state in folder."""
    write_table(folder / "final_nodes.csv", NODE_HEADER, nodes)
    write_table(folder / "contact_final.csv", CONTACT_HEADER, contact)
    if steps is not None:
        write_table(folder / "steps.csv", STEPS_HEADER, steps)


# ---------------------------------------------------------------------------------------- geometries

def straight_tails(u_a, u_b, s_a, s_b):
    """Node positions on S: tail A is c(s) = p_a + (s_a - s) u_a for s_a - 2 <= s <= s_a, tail B is
    c(s) = p_b + (s - s_b) u_b for s_b <= s <= s_b + 2, and a bulging curve joins p_a to p_b in the knot.
    Farther than the 2 mm chord the tails turn (to u_a + k, u_b + k), so another chord length would
    give another angle."""
    p_a, p_b, bulge = np.array([0.3, -0.2, 0.1]), np.array([1.0, 0.5, 0.3]), np.array([0.0, 0.4, 0.7])
    k = np.array([0.2, -0.5, 0.4])
    points = []
    for s in S:
        if s <= s_a - 2.0:
            points.append(p_a + 2.0 * u_a + (s_a - 2.0 - s) * unit(u_a + k))
        elif s <= s_a:
            points.append(p_a + (s_a - s) * u_a)
        elif s >= s_b + 2.0:
            points.append(p_b + 2.0 * u_b + (s - s_b - 2.0) * unit(u_b + k))
        elif s >= s_b:
            points.append(p_b + (s - s_b) * u_b)
        else:
            tau = (s - s_a) / (s_b - s_a)
            points.append(p_a + tau * (p_b - p_a) + math.sin(math.pi * tau) * bulge)
    return np.array(points)


def knot_contact(s_a, s_b, centreline):
    """Elements in contact pairing s_a + 0.1 k with s_b - 0.1 k (k = 0..15), plus two open elements
    outside [s_a, s_b] that must not widen the knot."""
    rows = [contact_row(1, k / 15, s_a + 0.1 * k, s_b - 0.1 * k, centreline(s_a + 0.1 * k),
                        centreline(s_b - 0.1 * k), normal=0.05) for k in range(16)]
    rows.append(contact_row(0, 0.0, s_a - 3.0, s_a - 2.5, centreline(s_a - 3.0), centreline(s_a - 2.5), 0.0))
    rows.append(contact_row(2, 1.0, s_b + 0.4, s_b + 0.2, centreline(s_b + 0.4), centreline(s_b + 0.2), 0.0))
    return rows


def lasso(arc_degrees, radius=0.8, s_1=8.0):
    """(c, s_2, t_1, t_2): centreline c(s) with s its arc length, straight along t_1 up to s_1, then an
    arc of `radius` through arc_degrees in the tilted plane (E1, E2) up to s_2, then straight along t_2."""
    length = radius * math.radians(arc_degrees)
    s_2 = s_1 + length
    centre = np.array([1.0, -2.0, 0.5])

    def tangent(theta):
        return -math.sin(theta) * E1 + math.cos(theta) * E2

    def c(s):
        theta = (min(max(s, s_1), s_2) - s_1) / radius
        on_arc = centre + radius * (math.cos(theta) * E1 + math.sin(theta) * E2)
        return on_arc + (s - min(max(s, s_1), s_2)) * tangent(theta)
    return c, s_2, tangent(0.0), tangent(length / radius)


def lasso_contact(c, s_1, s_2, spacing, rod_radius=0.1, elements=11):
    """Elements in contact pairing s_1 - k spacing with s_2 + k spacing (k = 0..elements-1), particles at
    rod_radius from the centreline towards each other, and one open element with both ends on the arc
    (it must not cut the loop; its spacing does not move the median)."""
    rows = []
    for k in range(elements):
        s_i, s_j = s_1 - k * spacing, s_2 + k * spacing
        n = unit(c(s_j) - c(s_i))
        gap = np.linalg.norm(c(s_j) - c(s_i)) - 2 * rod_radius
        rows.append(contact_row(0, k / elements, s_i, s_j, c(s_i) + rod_radius * n, c(s_j) - rod_radius * n,
                                normal=0.01 * (k + 1), tangential=0.002 * k, gap=gap))
    s_i, s_j = s_1 + 1.0, s_2 - 1.0
    rows.append(contact_row(0, 1.0, s_i, s_j, c(s_i), c(s_j), normal=0.0, gap=0.3))
    return rows


def lasso_state(arc_degrees, spacing=0.2):
    """(nodes, contact, s_2) of a lasso with s_1 = 8."""
    c, s_2, _, _ = lasso(arc_degrees)
    return node_rows(S, [c(s) for s in S]), lasso_contact(c, 8.0, s_2, spacing), s_2


# ---------------------------------------------------------------------------------------- tests

class KnotReportTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self._tmp.cleanup)
        self.tmp = Path(self._tmp.name)

    def analyse(self, nodes, contact, name="state"):
        """knot_report.analyse of the state read back from the files it would read."""
        folder = self.tmp / name
        write_run(folder, nodes, contact, steps=[{"step": 1}])
        return kr.analyse(kr.load_state(folder, name, None))

    def run_script(self, run_dir):
        return subprocess.run([sys.executable, str(SCRIPT), str(run_dir)], cwd=self.tmp, capture_output=True,
                              text=True, timeout=300)

    # tail angle -----------------------------------------------------------------------------------
    def test_tail_angle_of_straight_tails(self):
        u_a, w = unit(E1 + 0.3 * E3), unit(E2)   # w is perpendicular to u_a
        for angle, i_a, i_b in [(120.0, 160, 240), (180.0, 160, 240), (90.0, 200, 390)]:
            with self.subTest(angle=angle):
                s_a, s_b = S[i_a], S[i_b]   # on nodes: c(s_a), c(s_b) are exact
                points = straight_tails(u_a, direction_at(u_a, w, angle), s_a, s_b)
                nodes = node_rows(S, points)
                centreline = lambda s: np.array([np.interp(s, S, points[:, d]) for d in range(3)])
                row, _, extent = self.analyse(nodes, knot_contact(s_a, s_b, centreline), f"tail_{angle:g}")
                self.assertEqual(extent, (s_a, s_b))   # open elements outside do not count
                # chords 2 u_a and 2 u_b (0.5 u_b when tail B is 0.5 mm long): angle(u_a, u_b) = angle;
                # not tighter: arccos is ill-conditioned at 180 (1e-16 in the cosine is 1e-6 degrees)
                self.assertAlmostEqual(row["tail_angle_deg"], angle, delta=1e-6)

    # loop -----------------------------------------------------------------------------------------
    def test_loop_of_a_lasso(self):
        # spacing 0.2 gives h = 0.1; spacing 0.04 is below the 0.05 floor, so h = 0.025
        for arc, spacing, h in [(300.0, 0.2, 0.1), (330.0, 0.04, 0.025)]:
            with self.subTest(arc=arc, spacing=spacing):
                nodes, contact, s_2 = lasso_state(arc, spacing)
                arc_length = 0.8 * math.radians(arc)
                row, _, extent = self.analyse(nodes, contact, f"lasso_{arc:g}")
                self.assertAlmostEqual(extent[0], 8.0 - 10 * spacing, delta=1e-12)
                self.assertAlmostEqual(extent[1], s_2 + 10 * spacing, delta=1e-12)
                self.assertAlmostEqual(row["loop_radius_mm"], 0.8, delta=0.8e-9)
                # the loop is [s_1 + h, s_2 - h]: the arc, less h at each end
                self.assertAlmostEqual(row["loop_length_mm"], arc_length - 2 * h, delta=1e-9)
                self.assertLessEqual(abs(row["loop_length_mm"] - arc_length), 0.05 + 2 * h)
                # tails: -t_1 and t_2 = t_1 turned by the arc, so the angle is arc - 180 degrees
                self.assertAlmostEqual(row["tail_angle_deg"], arc - 180.0, delta=1e-6)

    # intermediate geometry ------------------------------------------------------------------------
    def test_intermediate_geometry_and_reactions(self):
        r, d, rho, dtheta, n0, n1 = 0.1, 0.15, 1.5, 0.1, 12, 20
        w = unit(E1 + E2)                              # zone 0: straight midline along w
        normal_0 = unit(np.cross(w, E3))               # perpendicular to w
        centre = np.array([4.0, 1.0, -1.0])            # zone 1: circle of radius rho in plane (E1, E2)
        rows, midline, force = [], {}, {}
        for k in range(n0):                            # in contact: k = 2 .. n0 - 2, R_N = 0.01 k
            m = np.array([0.5, 0.5, 0.5]) + k * d * w
            f = 0.01 * k if 2 <= k <= n0 - 2 else 0.0
            midline[0, k], force[0, k] = m, f
            rows.append(contact_row(0, k / (n0 - 1), 2.0 + 0.1 * k, 9.0 - 0.1 * k, m + r * normal_0,
                                    m - r * normal_0, normal=f, tangential=0.3 * f, gap=-0.01 * f))
        for k in range(n1):                            # in contact: k = 1 .. n1 - 3, R_N = 0.02 k
            m = centre + rho * (math.cos(k * dtheta) * E1 + math.sin(k * dtheta) * E2)
            f = 0.02 * k if 1 <= k <= n1 - 3 else 0.0
            midline[1, k], force[1, k] = m, f
            rows.append(contact_row(1, k / (n1 - 1), 11.0 + 0.1 * k, 19.0 - 0.1 * k, m + r * E3, m - r * E3,
                                    normal=f, tangential=0.3 * f, gap=-0.01 * f))
        random.Random(1).shuffle(rows)                 # the script must sort by (zone, zeta)
        nodes = node_rows(S, np.column_stack([S, np.zeros_like(S), np.zeros_like(S)]))
        row, reactions, _ = self.analyse(nodes, rows, "intermediate")

        chord = 2 * rho * math.sin(dtheta / 2)         # polyline of points on a circle: chords
        expected = [k * d for k in range(n0)] + [(n0 - 1) * d + k * chord for k in range(n1)]
        np.testing.assert_allclose(reactions["abscissa_mm"], expected, rtol=0, atol=1e-12)
        np.testing.assert_allclose(np.column_stack([reactions[c] for c in "xyz"]),
                                   [midline[z, k] for z, n in ((0, n0), (1, n1)) for k in range(n)], atol=1e-12)
        np.testing.assert_allclose(reactions["normal_N"], [force[z, k] for z, n in ((0, n0), (1, n1))
                                                           for k in range(n)], atol=0)
        self.assertAlmostEqual(row["intermediate_length_mm"], (n0 - 4) * d + (n1 - 4) * chord, delta=1e-12)
        self.assertEqual((row["zones"], row["contact_elements"]), (2, n0 + n1))
        self.assertEqual(row["elements_in_contact"], (n0 - 3) + (n1 - 3))
        # R_N: 0.01 k for k = 2..10 in zone 0, 0.02 k for k = 1..17 in zone 1; R_T = 0.3 R_N
        total = 0.01 * (2 + 10) * 9 / 2 + 0.02 * (1 + 17) * 17 / 2
        self.assertAlmostEqual(row["max_normal_N"], 0.02 * 17, delta=1e-12)
        self.assertAlmostEqual(row["total_normal_N"], total, delta=1e-12)
        self.assertAlmostEqual(row["max_tangential_N"], 0.3 * 0.02 * 17, delta=1e-12)
        self.assertAlmostEqual(row["total_tangential_N"], 0.3 * total, delta=1e-12)
        self.assertAlmostEqual(row["max_penetration_mm"], 0.01 * 0.02 * 17, delta=1e-15)

    # end to end -----------------------------------------------------------------------------------
    def test_run_folder_end_to_end(self):
        run_dir = self.tmp / "run"
        nodes, contact, _ = lasso_state(300.0)
        write_run(run_dir, nodes, contact, steps=[
            {"step": 1, "stage": "form", "time": 0.5, "stabilization_force": 0.02, "min_orientation": 0.9,
             "min_chord": 0.8, "pull_b_fx": 1.0, "pull_b_fy": 2.0, "pull_b_fz": 0.0},
            {"step": 2, "stage": "tighten", "time": 1.0, "stabilization_force": 0.01, "min_orientation": 0.95,
             "min_chord": 0.97, "pull_b_fx": 0.3, "pull_b_fy": 0.4, "pull_b_fz": 0.0}])
        branch_nodes, branch_contact, _ = lasso_state(330.0)
        write_run(run_dir / "branches" / "mu_0.30", branch_nodes, branch_contact, steps=[
            {"step": 3, "stage": "release", "time": 1.0, "stabilization_force": 0.0, "min_orientation": -0.5,
             "min_chord": 0.01, "pull_b_fx": 0.0, "pull_b_fy": 0.0, "pull_b_fz": 0.25}])
        stage_nodes, stage_contact, _ = lasso_state(350.0)
        write_table(run_dir / "stages" / "000_loop_nodes.csv", NODE_HEADER, stage_nodes)
        write_table(run_dir / "stages" / "000_loop_contact.csv", CONTACT_HEADER, stage_contact)

        result = self.run_script(run_dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        out = run_dir / "report"
        with open(out / "knot_report.csv", newline="") as f:
            rows = {row["state"]: row for row in csv.DictReader(f)}
        self.assertEqual(list(rows), ["tightened", "mu_0.30"])
        tightened, branch = rows["tightened"], rows["mu_0.30"]
        self.assertEqual(tightened["friction"], "")                      # no summary.json
        self.assertAlmostEqual(float(branch["friction"]), 0.3)           # from the name mu_0.30
        self.assertAlmostEqual(float(tightened["tightening_force_N"]), 0.5, delta=1e-9)  # |(0.3, 0.4, 0)|
        self.assertAlmostEqual(float(tightened["stabilization_force_N"]), 0.01, delta=1e-12)
        self.assertAlmostEqual(float(branch["tightening_force_N"]), 0.25, delta=1e-9)
        for row, angle in ((tightened, 120.0), (branch, 150.0)):         # arc - 180 degrees
            self.assertAlmostEqual(float(row["tail_angle_deg"]), angle, delta=1e-3)   # 6 digits written
            self.assertAlmostEqual(float(row["loop_radius_mm"]), 0.8, delta=1e-6)
            self.assertEqual((row["contact_elements"], row["elements_in_contact"]), ("12", "11"))
        for name in ("tightened", "mu_0.30"):
            with open(out / f"reactions_{name}.csv", newline="") as f:
                reader = csv.DictReader(f)
                self.assertEqual(len(list(reader)), 12)
                for column in ("zone", "zeta", "abscissa_mm", "s_i", "s_j", "x", "y", "z", "normal_N",
                               "tangential_N", "state"):
                    self.assertIn(column, reader.fieldnames)
        for figure in FIGURES:
            with self.subTest(figure=figure):
                data = (out / figure).read_bytes()
                self.assertGreater(len(data), 1000)
                self.assertEqual(data[:8], PNG_SIGNATURE)
        # The fold check: each stage end, then each run's smallest values over all its steps.
        with open(out / "fold_check.csv", newline="") as f:
            folds = [(r["run"], r["stage"], r["step"], float(r["min_orientation"]), float(r["min_chord"]))
                     for r in csv.DictReader(f)]
        self.assertEqual(folds, [("main", "form", "1", 0.9, 0.8), ("main", "tighten", "2", 0.95, 0.97),
                                 ("main", "all steps", "2", 0.9, 0.8), ("mu_0.30", "release", "3", -0.5, 0.01),
                                 ("mu_0.30", "all steps", "3", -0.5, 0.01)])
        self.assertIn("fold check: smallest det[g1, g2, r'] -0.5 (mu_0.30, release), smallest chord / h 0.01: "
                      "FOLDED ELEMENTS in 2 rows", result.stdout)
        self.assertEqual([p.name for p in out.iterdir() if p.name.startswith(".")], [])  # no temporary

    # other beams in the stage pictures ----------------------------------------------------------------
    def test_tools_in_contact_with_the_rod(self):
        # A stage table with the rod and two straight beams, `clamp` paired with the rod in the contact table
        # and `far` paired with nothing: only `clamp` is drawn, its nodes sorted by s; a table without its
        # _contact.csv companion gives none.
        stage = self.tmp / "stages"
        rod = node_rows(S, [(s, 0.0, 0.0) for s in S])
        clamp_s = np.array([2.0, 0.0, 1.0])  # written out of order
        clamp = node_rows(clamp_s, [(3.0, s - 1.0, 0.2) for s in clamp_s], beam="clamp")
        far = node_rows(clamp_s, [(9.0, s, 5.0) for s in clamp_s], beam="far")
        write_table(stage / "001_clamp_nodes.csv", NODE_HEADER, rod + clamp + far)
        row = contact_row(0, 0.5, 3.0, 1.0, (3.0, 0.0, 0.0), (3.0, 0.0, 0.2), 0.01)
        write_table(stage / "001_clamp_contact.csv", CONTACT_HEADER, [{**row, "beam_j": "clamp"}])
        tools = kr.tools_in_contact(stage / "001_clamp_nodes.csv")
        self.assertEqual(len(tools), 1)
        self.assertEqual(list(tools[0]["beam"]), ["clamp"] * 3)
        np.testing.assert_array_equal(tools[0]["s"], [0.0, 1.0, 2.0])
        np.testing.assert_array_equal(tools[0]["y"], [-1.0, 0.0, 1.0])
        write_table(stage / "002_free_nodes.csv", NODE_HEADER, rod + clamp)
        self.assertEqual(kr.tools_in_contact(stage / "002_free_nodes.csv"), [])

    # bad input ------------------------------------------------------------------------------------
    def test_bad_input_fails_with_one_line(self):
        nodes, contact, _ = lasso_state(300.0)
        no_column = [{k: v for k, v in row.items() if k != "normal_force"} for row in contact]
        for case, contact_rows, message in [("no_contact_file", None, "contact_final.csv: missing"),
                                            ("no_normal_force", no_column, "normal_force")]:
            with self.subTest(case=case):
                run_dir = self.tmp / case
                write_table(run_dir / "final_nodes.csv", NODE_HEADER, nodes)
                if contact_rows is not None:
                    write_table(run_dir / "contact_final.csv",
                                [c for c in CONTACT_HEADER if c != "normal_force"], contact_rows)
                result = self.run_script(run_dir)
                self.assertEqual(result.returncode, 2)  # bad input: status 2
                lines = result.stderr.strip().splitlines()
                self.assertEqual(len(lines), 1, result.stderr)
                self.assertTrue(lines[0].startswith("knot_report: "), lines[0])
                self.assertIn(str(run_dir / "contact_final.csv"), lines[0])
                self.assertIn(message, lines[0])


if __name__ == "__main__":
    unittest.main()
