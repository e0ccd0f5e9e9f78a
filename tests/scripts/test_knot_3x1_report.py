#!/usr/bin/env python3
"""Tests scripts/knot_3x1_report.py on a synthetic run folder of a 3x1 yarn of known geometry. Each expected
number comes from the construction, in closed form; none is taken from the script's own output.

The run folder (fibres yarn.r1.f1, yarn.r2.f1, yarn.r3.f1, radius R_f = 0.0564 mm; the fibres' centrelines
at rho = 2 R_f / sqrt(3) from the yarn's centreline c, at 0, 120 and 240 degrees in a parallel-transported
normal frame, so that their node-by-node mean is c and neighbouring fibres are 2 R_f apart):
  tightened       c is a trefoil, A (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t) with A = 0.5 mm, cut open
                  at its outermost point (t = pi/3 +- 0.3) and continued by straight tails 2.5 mm long
                  pointing away from the origin, along u_A = c(t_A) / |c(t_A)| and u_B = c(t_B) / |c(t_B)|.
                  Each fibre is a (1, n) cable of the trefoil, hence a trefoil; so is the mean. The contact
                  table holds knot contacts (a fibre with itself; two fibres 0.9 mm or more apart along the
                  yarn) and, in contact too, side-by-side contacts between fibres (|s_i - s_j| = 0.01 and
                  0.5 < 0.68 mm) on tail A, on tail B and in the middle of the knot's longest free stretch.
                  Expected: the knot spans [s_a, s_b] = the ends of the trefoil arc (s_0, s_1), so the tail
                  angle is the angle between u_A and u_B (the 2 mm chords lie on the tails), and the loop is
                  the longest gap between the knot contacts' abscissas, less h = 0.05 mm at each end
                  (h = half the 0.1 mm spacing of their elements): (s_1 - 0.2) - (s_0 + 6.1) - 2 h. Were the
                  side-by-side contacts counted, s_a would fall on tail A and the gap would be cut in two.
                  Sums and counts of the reactions from the table as written; end B x from the nodes, which
                  are written in reverse order (the script sorts them by s). A beam `anchor` in the table is
                  not a fibre.
  branch mu_0.30  fibres r1 and r3 as above; r2 a straight line far off (slid out of the knot): an unknot,
                  r1 and r3 trefoils. Friction 0.3 from summary.json.
  branch mu_0.20  a straight yarn: the fibres parallel lines 2 R_f apart, all unknots, the mean too; the
                  smallest distance between fibres is 2 R_f, and within a fibre, between points 0.68 mm apart
                  along it, 0.68 mm; only side-by-side contacts, so no knot extent and no tail angle.
                  Friction 0.2 parsed from the name (summary.json gives none).
  Also: the tightening force is |sum of the fibres' pull vectors| (0.5 N, not the sum of their lengths); the
  figures (Figs. 19, 20, 21 and the 3D views of the stage end and the branches) are written as PNG files and
  no temporary file is left; a yarn name with no fibre in the table fails with one line on stderr.

Run: PYTHONPATH=build/release/python /usr/bin/python3 tests/scripts/test_knot_3x1_report.py (Debian's numpy
and matplotlib), from any directory.
"""

import csv
import importlib.util
import json
import math
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "knot_3x1_report.py"
_spec = importlib.util.spec_from_file_location("knot_3x1_report", SCRIPT)
k3 = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(k3)

NODE_HEADER = "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z".split(",")
CONTACT_HEADER = ("zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,"
                  "x_j,y_j,z_j,nx,ny,nz,gap,normal_force,tangential_force,tx,ty,tz,state").split(",")
STEPS_HEADER = ("step,stage,time,normal_force,stabilization_force,pull_b1_fx,pull_b1_fy,pull_b1_fz,pull_b2_fx,"
                "pull_b2_fy,pull_b2_fz,pull_b3_fx,pull_b3_fy,pull_b3_fz").split(",")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FIGURES = ["fig19_intermediate_geometries.png", "fig20_released_knots.png", "fig21_released_reactions.png",
           "view3d_stage_000_tie.png", "view3d_mu_0.30.png", "view3d_mu_0.20.png"]

FIBRE_RADIUS = 0.0564
RHO = FIBRE_RADIUS * 2 / math.sqrt(3)          # fibre centreline to yarn centreline [mm]
FIBRES = ["yarn.r1.f1", "yarn.r2.f1", "yarn.r3.f1"]
ANGLES = [0.0, 2 * math.pi / 3, 4 * math.pi / 3]
A, CUT = 0.5, 0.3                               # trefoil scale [mm], half the opening [rad]
T_A, T_B = math.pi / 3 + CUT, math.pi / 3 + 2 * math.pi - CUT
TAIL, TAIL_STEP = 2.5, 0.05                     # tail length and node spacing [mm]


def trefoil(t):
    t = np.asarray(t, float)
    return A * np.column_stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)])


def unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


U_A, U_B = unit(trefoil([T_A])[0]), unit(trefoil([T_B])[0])


def knotted_centreline():
    """(points, s, s_0, s_1): tail A, the trefoil arc, tail B; s the polyline's arc length."""
    k = np.arange(round(TAIL / TAIL_STEP) + 1) * TAIL_STEP            # 0 .. 2.5
    arc = trefoil(np.linspace(T_A, T_B, 241))
    tail_a = arc[0] + (TAIL - k)[:, None] * U_A                      # s = k
    tail_b = arc[-1] + k[1:, None] * U_B
    points = np.concatenate([tail_a, arc[1:], tail_b])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    return points, s, s[len(k) - 1], s[len(k) - 1 + len(arc) - 1]


def normal_frame(points):
    """(e1, e2) normal to the polyline's tangents (central differences), e1 carried along by projection."""
    t = np.empty_like(points)
    t[1:-1], t[0], t[-1] = points[2:] - points[:-2], points[1] - points[0], points[-1] - points[-2]
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    e1 = np.empty_like(points)
    e1[0] = unit(np.cross(t[0], [0.0, 0.0, 1.0]))
    for j in range(1, len(points)):
        e1[j] = unit(e1[j - 1] - e1[j - 1].dot(t[j]) * t[j])
    return e1, np.cross(t, e1)


def fibres_around(points):
    """{name: points} of the three fibres at RHO around the centreline `points`."""
    e1, e2 = normal_frame(points)
    return {name: points + RHO * (math.cos(a) * e1 + math.sin(a) * e2) for name, a in zip(FIBRES, ANGLES)}


def straight_yarn(s):
    """The fibres of a straight yarn along x from (-3, 0, 0): parallel lines 2 R_f apart."""
    return {name: np.column_stack([s - 3.0, np.full_like(s, RHO * math.cos(a)), np.full_like(s, RHO * math.sin(a))])
            for name, a in zip(FIBRES, ANGLES)}


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


def node_rows(fibres, s):
    """Rows of final_nodes.csv, each beam's nodes in reverse order of s."""
    return [{"beam": name, "node": k, "s": s[k], "x": p[k, 0], "y": p[k, 1], "z": p[k, 2], "g1x": 1.0, "g2y": 1.0}
            for name, p in fibres.items() for k in reversed(range(len(s)))]


def at(points, s, s_value):
    return np.array([np.interp(s_value, s, points[:, d]) for d in range(3)])


def contact_rows(fibres, s, elements):
    """Rows of contact_final.csv from (zone, beam_i, beam_j, s_i, s_j, R_N, T, gap), zeta by order in zone."""
    rows = []
    for k, (zone, i, j, s_i, s_j, normal, tangential, gap) in enumerate(elements):
        x_i, x_j = at(fibres[i], s, s_i), at(fibres[j], s, s_j)
        n = unit(x_j - x_i)
        rows.append({"zone": zone, "beam_i": i, "beam_j": j, "zeta": 0.01 * k, "abscissa_i": s_i,
                     "abscissa_j": s_j, "x_i": x_i[0], "y_i": x_i[1], "z_i": x_i[2], "x_j": x_j[0],
                     "y_j": x_j[1], "z_j": x_j[2], "nx": n[0], "ny": n[1], "nz": n[2], "gap": gap,
                     "normal_force": normal, "tangential_force": tangential,
                     "state": "open" if normal <= 0 else "slip" if tangential > 0 else "stick"})
    return rows


R1, R2, R3 = FIBRES


def tightened_elements(s_0, s_1):
    """(knot contacts, side-by-side contacts) as element tuples; the knot's in contact cover s_0 .. s_0 + 0.2,
    s_0 + 1.0 .. 2.0, s_0 + 3.0 .. 3.1, s_0 + 6.0 .. 6.1 and s_1 - 0.2 .. s_1."""
    knot = [(3, R1, R3, s_0 + 0.1 * k, s_1 - 0.1 * k, 0.02 * (k + 1), 0.005, -0.001 * k) for k in range(3)]
    knot.append((3, R1, R3, s_0 - 0.5, s_1 + 0.5, 0.0, 0.0, 0.01))          # open: outside the extent
    knot += [(4, R2, R2, s_0 + 3.0 + 0.1 * k, s_0 + 6.0 + 0.1 * k, 0.05, 0.01, 0.0) for k in range(2)]
    knot += [(5, R1, R2, s_0 + 1.0 + 0.1 * k, s_0 + 1.9 + 0.1 * k, 0.03, 0.0, 0.0) for k in range(2)]
    side = [(0, R1, R2, 0.2 + 0.1 * k, 0.21 + 0.1 * k, 0.01, 0.002, 0.0) for k in range(5)]   # tail A
    side += [(1, R2, R3, s_0 + 8.0 + 0.1 * k, s_0 + 8.01 + 0.1 * k, 0.04, 0.0, 0.0) for k in range(3)]
    side += [(2, R1, R3, s_1 + 0.5 + 0.1 * k, s_1 + 1.0 + 0.1 * k, 0.015, 0.001, 0.0) for k in range(2)]
    side.append((2, R1, R3, s_1 + 0.8, s_1 + 1.3, 0.0, 0.0, 0.02))          # open
    return knot, side


class KnotThreeByOneReportTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory()
        cls.tmp = Path(cls._tmp.name)
        cls.run_dir = cls.tmp / "run"
        cls.build_run(cls.run_dir)
        cls.result = subprocess.run([sys.executable, str(SCRIPT), str(cls.run_dir)], cwd=cls.tmp,
                                    capture_output=True, text=True, timeout=300)
        cls.rows = {}
        if cls.result.returncode == 0:
            with open(cls.run_dir / "report" / "knot_3x1_report.csv", newline="") as f:
                cls.rows = {row["state"]: row for row in csv.DictReader(f)}

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    @classmethod
    def build_run(cls, run_dir):
        points, s, s_0, s_1 = knotted_centreline()
        cls.s, cls.s_0, cls.s_1 = s, s_0, s_1
        fibres = fibres_around(points)
        cls.tightened_fibres = fibres
        knot, side = tightened_elements(s_0, s_1)
        cls.knot, cls.side = knot, side
        anchor = {"beam": "anchor", "node": 0, "s": 0.0, "x": 9.0, "y": 9.0, "z": 9.0}
        nodes = node_rows(fibres, s) + [anchor, {**anchor, "node": 1, "s": 1.0, "x": 10.0}]
        contact = contact_rows(fibres, s, knot + side)
        for folder in (run_dir, run_dir / "stages"):
            prefix = "" if folder == run_dir else "000_tie_"
            write_table(folder / (f"{prefix}nodes.csv" if prefix else "final_nodes.csv"), NODE_HEADER, nodes)
            write_table(folder / (f"{prefix}contact.csv" if prefix else "contact_final.csv"), CONTACT_HEADER,
                        contact)
        write_table(run_dir / "steps.csv", STEPS_HEADER, [
            {"step": 1, "stage": "pull", "normal_force": 9.0, "stabilization_force": 0.5},
            {"step": 2, "stage": "settle", "normal_force": 0.61, "stabilization_force": 0.002,
             "pull_b1_fx": 0.1, "pull_b1_fy": 0.05, "pull_b2_fx": 0.2, "pull_b2_fy": -0.05, "pull_b3_fx": 0.2}])
        (run_dir / "summary.json").write_text(json.dumps({"friction": 0.3, "branches": [
            {"name": "mu_0.30", "friction": 0.3, "folder": "branches/mu_0.30"},
            {"name": "mu_0.20", "folder": "branches/mu_0.20"}]}))

        slid = dict(fibres)
        slid[R2] = np.column_stack([s - 8.0, np.full_like(s, -8.0), np.zeros_like(s)])   # r2 slid out
        cls.slid_fibres = slid
        branch = run_dir / "branches" / "mu_0.30"
        write_table(branch / "final_nodes.csv", NODE_HEADER, node_rows(slid, s))
        write_table(branch / "contact_final.csv", CONTACT_HEADER,
                    contact_rows(slid, s, [(0, R1, R3, s_0 + 0.1 * k, s_1 - 0.1 * k, 0.01, 0.0, 0.0)
                                           for k in range(3)]))
        write_table(branch / "steps.csv", STEPS_HEADER, [{"step": 3, "stage": "rest", "normal_force": 0.03}])

        s_straight = np.linspace(0.0, 6.0, 201)
        cls.s_straight = s_straight
        straight = straight_yarn(s_straight)
        branch = run_dir / "branches" / "mu_0.20"
        write_table(branch / "final_nodes.csv", NODE_HEADER, node_rows(straight, s_straight))
        write_table(branch / "contact_final.csv", CONTACT_HEADER, contact_rows(straight, s_straight, [
            (zone, i, j, 1.0 + 0.1 * k, 1.0 + 0.1 * k + 0.02, 0.02, 0.004, 0.0)
            for zone, (i, j) in enumerate([(R1, R2), (R2, R3), (R1, R3)]) for k in range(4)]))
        write_table(branch / "steps.csv", STEPS_HEADER, [{"step": 3, "stage": "rest", "normal_force": 0.24}])

    def setUp(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)

    def value(self, state, column):
        return float(self.rows[state][column])

    def assertWritten(self, state, column, expected, delta=1e-12):
        """The CSV holds 6 significant digits: within half a unit of the sixth (5e-6 |expected|) and `delta`."""
        self.assertAlmostEqual(self.value(state, column), expected, delta=5e-6 * abs(expected) + delta,
                               msg=f"{state}: {column}")

    # knot types --------------------------------------------------------------------------------------
    def test_knot_types(self):
        expected = {"tightened": ["trefoil"] * 4,                       # mean, r1, r2, r3
                    "mu_0.30": [None, "trefoil", "unknot", "trefoil"],   # the mean is not known in closed form
                    "mu_0.20": ["unknot"] * 4}
        for state, types in expected.items():
            for column, knot in zip(["knot_mean", "knot_r1.f1", "knot_r2.f1", "knot_r3.f1"], types):
                if knot is not None:
                    with self.subTest(state=state, column=column):
                        self.assertEqual(self.rows[state][column], knot)
        self.assertNotIn("knot_anchor", self.rows["tightened"])        # not a fibre of the yarn

    # states, friction and steps ----------------------------------------------------------------------
    def test_states_friction_and_steps(self):
        self.assertEqual(list(self.rows), ["tightened", "mu_0.30", "mu_0.20"])   # highest friction first
        self.assertAlmostEqual(self.value("tightened", "friction"), 0.3)
        self.assertAlmostEqual(self.value("mu_0.30", "friction"), 0.3)
        self.assertAlmostEqual(self.value("mu_0.20", "friction"), 0.2)           # from the name
        self.assertWritten("tightened", "tightening_force_N", 0.5)  # |(0.5, 0, 0)|
        self.assertWritten("tightened", "stabilization_force_N", 0.002)
        self.assertWritten("tightened", "steps_normal_force_N", 0.61)
        self.assertWritten("mu_0.20", "steps_normal_force_N", 0.24)

    # end B -------------------------------------------------------------------------------------------
    def test_end_b_x(self):
        for state, fibres in (("tightened", self.tightened_fibres), ("mu_0.30", self.slid_fibres)):
            for name in FIBRES:
                with self.subTest(state=state, fibre=name):
                    self.assertWritten(state, f"end_b_x_{name[5:]}_mm", fibres[name][-1, 0])
        self.assertWritten("mu_0.30", "end_b_x_r2.f1_mm", self.s[-1] - 8.0)
        for name in FIBRES:
            self.assertWritten("mu_0.20", f"end_b_x_{name[5:]}_mm", 3.0)

    # reactions ---------------------------------------------------------------------------------------
    def test_reactions_of_the_tightened_knot(self):
        knot, side = self.knot, self.side
        every = knot + side
        normal = [e[5] for e in every]
        row = "tightened"
        self.assertEqual(int(self.rows[row]["zones"]), 6)
        self.assertEqual(int(self.rows[row]["contact_elements"]), len(every))
        self.assertEqual(int(self.rows[row]["elements_in_contact"]), sum(f > 0 for f in normal))
        self.assertEqual(int(self.rows[row]["zones_in_contact"]), 6)
        self.assertEqual(int(self.rows[row]["knot_zones_in_contact"]), 3)
        self.assertEqual(int(self.rows[row]["knot_elements_in_contact"]), 3 + 2 + 2)
        # R_N: knot 0.02 + 0.04 + 0.06 + 2 x 0.05 + 2 x 0.03 = 0.28; side by side 5 x 0.01 + 3 x 0.04 +
        # 2 x 0.015 = 0.2. |T|: knot 3 x 0.005 + 2 x 0.01 = 0.035, side 5 x 0.002 + 2 x 0.001 = 0.012.
        self.assertWritten(row, "knot_normal_N", 0.28)
        self.assertWritten(row, "total_normal_N", 0.48)
        self.assertWritten(row, "max_normal_N", 0.06)
        self.assertWritten(row, "total_tangential_N", 0.047)
        self.assertWritten(row, "max_penetration_mm", 0.002)
        with open(self.run_dir / "report" / "reactions_tightened.csv", newline="") as f:
            reactions = list(csv.DictReader(f))
        self.assertEqual(len(reactions), len(every))
        self.assertEqual(sum(int(r["knot"]) for r in reactions), len(knot))
        self.assertAlmostEqual(sum(float(r["normal_N"]) for r in reactions if r["knot"] == "1"), 0.28, delta=1e-9)

    # the knot's extent, tails and loop: side-by-side contacts left out -------------------------------
    def test_knot_extent_tail_angle_and_loop(self):
        row = "tightened"
        self.assertWritten(row, "knot_s_a_mm", self.s_0)
        self.assertWritten(row, "knot_s_b_mm", self.s_1)
        # the chords lie on the tails; arccos is well conditioned away from 0 and 180 degrees
        self.assertWritten(row, "tail_angle_deg", math.degrees(math.acos(float(U_A.dot(U_B)))), delta=1e-9)
        h = 0.05
        self.assertWritten(row, "loop_length_mm", (self.s_1 - 0.2) - (self.s_0 + 6.1) - 2 * h, delta=1e-9)
        # The straight yarn has side-by-side contacts only: no knot.
        self.assertEqual(int(self.rows["mu_0.20"]["knot_elements_in_contact"]), 0)
        self.assertEqual(int(self.rows["mu_0.20"]["elements_in_contact"]), 12)
        for column in ("knot_s_a_mm", "knot_s_b_mm", "tail_angle_deg"):
            self.assertTrue(math.isnan(self.value("mu_0.20", column)), column)

    def test_knot_contact_classification(self):
        contact = {"beam_i": np.array([R1, R1, R1, R2, R1], dtype=object),
                   "beam_j": np.array([R1, R2, R2, R3, "anchor"], dtype=object),
                   "abscissa_i": np.array([1.0, 1.0, 1.0, 4.0, 1.0]),
                   "abscissa_j": np.array([1.1, 1.5, 1.9, 3.3, 3.0])}
        state = k3.YarnState("s", None, None, contact, {}, {name: None for name in FIBRES}, None)
        # self-contact; 0.5 apart: side by side; 0.9 and 0.7 apart: knot; a beam not of the yarn: not
        np.testing.assert_array_equal(k3.knot_contacts(state, 0.68), [True, False, True, True, False])

    # distances ---------------------------------------------------------------------------------------
    def test_distances_of_the_straight_yarn(self):
        self.assertWritten("mu_0.20", "fibre_distance_mm", 2 * FIBRE_RADIUS)
        for name in FIBRES:
            self.assertWritten("mu_0.20", f"self_distance_{name[5:]}_mm", 0.68)

    # the twist's winding -------------------------------------------------------------------------------
    def test_winding_of_plied_helices(self):
        """Three fibres on helices about an axis along (0.6, 0, 0.8), a third of a turn apart, winding by a
        known angle over 201 nodes: the winding about their centre is that angle, in its sense."""
        s = np.linspace(0.0, 6.0, 201)
        axis = np.array([0.6, 0.0, 0.8])
        e1 = np.array([0.0, 1.0, 0.0])
        e2 = np.cross(axis, e1)                      # (e1, e2, axis) right-handed
        for degrees in (1030.0, -1030.0, 90.0, 0.0):
            fibres = {}
            for k, name in enumerate(FIBRES):
                angle = np.radians(degrees) * s / 6.0 + 2 * np.pi * k / 3
                p = np.outer(s, axis) + RHO * (np.outer(np.cos(angle), e1) + np.outer(np.sin(angle), e2))
                fibres[name] = {"s": s, "x": p[:, 0], "y": p[:, 1], "z": p[:, 2]}
            winding = k3.winding_deg(fibres)
            for name in FIBRES:
                with self.subTest(degrees=degrees, fibre=name):
                    self.assertAlmostEqual(winding[name], degrees, delta=1e-9)
        fibres[FIBRES[0]] = {c: v[:-1] for c, v in fibres[FIBRES[0]].items()}   # one node fewer
        self.assertIsNone(k3.winding_deg(fibres))

    # outputs -----------------------------------------------------------------------------------------
    def test_figures_written(self):
        out = self.run_dir / "report"
        for figure in FIGURES:
            with self.subTest(figure=figure):
                data = (out / figure).read_bytes()
                self.assertGreater(len(data), 1000)
                self.assertEqual(data[:8], PNG_SIGNATURE)
        self.assertFalse((out / "view3d_final.png").exists())   # the final state is the stage end's
        self.assertEqual([p.name for p in out.iterdir() if p.name.startswith(".")], [])  # no temporary
        self.assertIn("| knot_mean | trefoil |", self.result.stdout)

    def test_unknown_yarn_fails_with_one_line(self):
        result = subprocess.run([sys.executable, str(SCRIPT), str(self.run_dir), "--yarn", "rope",
                                 "--out", str(self.tmp / "none")], capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 2)  # bad input: status 2
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertTrue(lines[0].startswith("knot_3x1_report: "), lines[0])
        self.assertIn("rope.rK.fJ", lines[0])


if __name__ == "__main__":
    unittest.main()
