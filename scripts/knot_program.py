#!/usr/bin/env python3
"""Writes the loading program of the monofilament overhand knot (examples/monofilament_knot.yaml).

Durville (2012), Sect. 7.2: a straight rod is tied into an overhand knot by moving its ends while two
clamping beams hold its loop, tightened by pulling one end, and released for three friction coefficients.

The rod ends are moved along paths given by a few waypoints (position and axis direction of the end
section). Between waypoints the position is interpolated linearly and the axis direction along the great
circle; the section is carried along the path by parallel transport (no twist is added about the axis).
nodus interpolates a motion's rotation vector component-wise between keyframes, so the path is written as
many close keyframes (8 per waypoint interval), each rotation vector chosen among its equivalents (the
angle plus a multiple of 360 degrees) as the one closest to the previous keyframe.

The scenario is built as data (knot_scenario(), also for use from Python), checked by nodus's reader through
the Python module (nodus.Scenario) and written with Scenario.to_yaml().

Usage: scripts/knot_program.py [--elements N] [--force F] [--pin-release] > SCENARIO.yaml
       scripts/knot_program.py --yarn [--elements N] [--force F] > SCENARIO.yaml   (the 3x1 knot, Sect. 7.3)
Requires python3-numpy (Debian) and the nodus module (PYTHONPATH=build/release/python, or found there).
"""

import argparse
import os
import sys

import numpy as np

try:
    import nodus
except ImportError:  # from the source tree: the module built in build/release
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "release", "python"))
    import nodus

SUBSTEPS = 8  # keyframes per waypoint interval


def rotation_between(a, b):
    """The smallest rotation taking the unit vector a onto the unit vector b."""
    v = np.cross(a, b)
    c = float(a @ b)
    if np.linalg.norm(v) < 1e-12:
        if c > 0:
            return np.eye(3)
        raise ValueError("waypoint axes turn by 180 degrees in one interval")
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1 + c)


def rotation_vector(r, previous):
    """log(r), among log(r) + 2 pi k n the one closest to `previous` (radians)."""
    angle = np.arccos(np.clip((np.trace(r) - 1) / 2, -1, 1))
    if angle < 1e-12:
        v = np.zeros(3)
    elif np.pi - angle < 1e-6:
        m = (r + np.eye(3)) / 2
        i = int(np.argmax(np.diag(m)))
        v = m[:, i] / np.sqrt(m[i, i]) * angle
    else:
        v = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / (2 * np.sin(angle)) * angle
    if previous is None or np.linalg.norm(v) < 1e-12:
        return v
    n = v / np.linalg.norm(v)
    return min((v + 2 * np.pi * k * n for k in range(-3, 4)), key=lambda c: np.linalg.norm(c - previous))


def slerp(a, b, u):
    angle = np.arccos(np.clip(a @ b, -1, 1))
    if angle < 1e-12:
        return a
    return (np.sin((1 - u) * angle) * a + np.sin(u * angle) * b) / np.sin(angle)


class End:
    """One rod end driven by a motion condition: its reference position and its path so far."""

    def __init__(self, name, position):
        self.name = name
        self.reference = np.asarray(position, float)
        self.position = self.reference.copy()
        self.axis = np.array([1.0, 0.0, 0.0])
        self.rotation = np.eye(3)
        self.vector = None

    def move(self, waypoints):
        """The keyframes of a motion target through `waypoints` = [(at, position, axis), ...] of one stage."""
        keyframes = []
        at0 = 0.0
        for at, position, axis in waypoints:
            position = np.asarray(position, float)
            axis = np.asarray(axis, float) / np.linalg.norm(axis)
            start, start_axis = self.position, self.axis
            for k in range(1, SUBSTEPS + 1):
                u = k / SUBSTEPS
                p = (1 - u) * start + u * position
                t = slerp(start_axis, axis, u)
                self.rotation = rotation_between(self.axis, t) @ self.rotation
                self.axis = t
                self.vector = rotation_vector(self.rotation, self.vector)
                keyframes.append({"at": num(at0 + u * (at - at0)), "translation": vec(p - self.reference),
                                  "rotation": vec(np.degrees(self.vector))})
            self.position = position
            at0 = at
        return {"keyframes": keyframes}


def num(x):
    """x rounded to 6 significant digits, as the program has always written its numbers."""
    return float(f"{x:.6g}")


def vec(v):
    return [num(x) for x in v]


FRICTIONS = (0.30, 0.25, 0.20)  # the loosening branches (Sect. 7.2.2)

# The clamping beams (Sect. 7.2.1, Figs. 12b-f): two elastic beams of the rod's material and section, across
# the top of the loop (along y), one above it and one below, each held at both ends. `clamp` brings them onto
# the loop with their supports CLAMP_DEPTH closer than touching, so that each bends and presses on it with a
# few hundredths of a newton; during `thread` the supports follow LOOP_TOP, the path that the top of the loop
# takes when it is threaded without clamp; `unclamp` takes the beams out of contact and lifts them away.
LOOP_TOP_START = np.array([3.052, 1.95, 0.25])  # the top of the loop at the end of `loop` [mm]
LOOP_TOP = [  # (fraction of `thread`, displacement of the top of the loop since its start [mm])
    (0.1, [0.149, -0.109, -0.016]), (0.2, [0.303, -0.206, -0.031]), (0.3, [0.337, -0.244, -0.038]),
    (0.4, [0.380, -0.274, -0.058]), (0.5, [0.431, -0.301, -0.095]), (0.6, [0.478, -0.338, -0.129]),
    (0.7, [0.515, -0.385, -0.138]), (0.8, [0.587, -0.429, -0.145]), (0.9, [0.655, -0.483, -0.156]),
    (1.0, [0.669, -0.561, -0.147])]
CLAMP_LENGTH = 3.0  # mm, centred on the top of the loop
CLAMP_ELEMENTS = 12
CLAMP_DEPTH = 0.02  # mm: how much closer than touching the supports come
CLAMP_AWAY = 1.5  # mm: the beams' distance from the loop plane before `clamp` and after `unclamp`
CONTACT_DISTANCE = 0.2  # mm: rod radius + clamp radius


def clamp_motions(offsets, keyframes=False):
    """The motion targets of the four clamp supports. `offsets` maps 'top'/'bottom' to the translation (or,
    with `keyframes`, to a list of (at, translation)) of both supports of that beam."""
    motions = {}
    for side in ("top", "bottom"):
        for end in ("a", "b"):
            if keyframes:
                motions[f"clamp_{side}_{end}"] = {
                    "keyframes": [{"at": num(at), "translation": vec(t)} for at, t in offsets[side]]}
            else:
                motions[f"clamp_{side}_{end}"] = {"translation": vec(offsets[side])}
    return motions


def knot_scenario(elements=300, force=0.5, pin_release=False, tighten_line_search=False, section_pairing="plane",
                  lift=0.0):
    """The knot's scenario as data (the keys of a scenario file, docs/scenario.md).

    tighten_line_search: `pull` and `settle` take Newton's line search, as the releases do. Without it a pull of
    2 N or more crawls once the knot slips (Newton's iterates swing by 0.1-0.3 mm as contact elements flip their
    slip direction, and the steps fall to 1e-5 of the load time); the force series takes it for every force
    (docs/knot.md). The flagship keeps the full Newton step: it is cheaper there and its tables are measured so.
    section_pairing: contact.section_pairing, "plane" (the paper's, the flagship's) or "bisector" (which follows
    a strand wrapping round another in a knot pulled at 2 N; docs/contact.md).
    lift: end B's height [mm] at its first waypoint of `loop` (0.3 s), instead of 0 (it rises to 0.1 mm by
    0.6 s anyway). The straight rod, compressed by its ends, buckles in the first step; in the plane of the ends'
    motion the whole program decides the rod's side, out of it nothing does but round-off, so two linear
    solvers (or MPI runs) can take the loop out of the plane to opposite sides. 0.05 mm decides it: on 60
    elements KLU, UMFPACK, MUMPS and PETSc on 1 to 3 ranks then take the same steps (tests/mpi,
    docs/parallel.md). The flagship keeps 0: its figures were measured so, and on 300 elements KLU and MUMPS
    take the same path through `loop` without it."""
    a = End("end_a", [-10, 0, 0])
    b = End("end_b", [10, 0, 0])
    p = 3.9  # the ends of the loop sit at (-p, -p) and (p, -p)
    diagonal = np.array([1.0, 1.0, 0.0]) / np.sqrt(2)
    feed = 3.0  # end A pushes this much rod towards the knot while end B threads the loop
    loop = {"end_a": a.move([(1.0, [-p, -p, 0], [1, 1, 0])]),
            "end_b": b.move([(0.3, [p + 2, 1, lift], [0, 1, 0]), (0.6, [0, 3.5, 0.1], [-1, 0, 0]),
                             (0.8, [-1.5, 1, 0.25], [0, -1, 0]), (1.0, [p, -p, 0.35], [1, -1, 0])])}
    thread = {"end_a": a.move([(1.0, np.array([-p, -p, 0]) + feed * diagonal, [1, 1, 0])]),
              "end_b": b.move([(0.15, [4.7, -4.5, -0.3], [0.3, -0.3, -1]), (0.3, [4.2, -3.6, -0.8], [-0.6, 1, -0.2]),
                               (0.5, [3.2, -1.3, -0.8], [-0.2, 1, 0.3]), (0.65, [3.1, -1.0, 0.6], [0.3, 0.2, 1]),
                               (0.8, [4.5, -1.0, 0.8], [1, 0, 0]), (1.0, [6, -1, 0.5], [1, 0, 0])])}
    # The clamp: each beam starts CLAMP_AWAY above or below the top of the loop, and is brought to touching
    # less CLAMP_DEPTH.
    side = {"top": 1.0, "bottom": -1.0}
    closed = {k: np.array([0, 0, -z * (CLAMP_AWAY - CONTACT_DISTANCE + CLAMP_DEPTH)]) for k, z in side.items()}
    clamp = clamp_motions(closed)
    follow = clamp_motions({k: [(at, closed[k] + np.array(d)) for at, d in LOOP_TOP] for k in side}, True)
    unclamp = clamp_motions({k: closed[k] + np.array(LOOP_TOP[-1][1]) + [0, 0, z * CLAMP_AWAY]
                             for k, z in side.items()})
    clamp_start = {k: LOOP_TOP_START + [0, -CLAMP_LENGTH / 2, z * CLAMP_AWAY] for k, z in side.items()}

    # Each end's position and orientation are two conditions, so that either can be let go on its own: end B
    # is let go entirely for the pull; with pin_release, end A keeps its position but turns freely once the
    # force is released.
    for motions in (loop, thread):
        motions["end_a_turn"] = motions["end_a"]
        motions["end_b_turn"] = motions["end_b"]
    loop = {k: loop[k] for k in ("end_a", "end_a_turn", "end_b", "end_b_turn")}
    thread = {k: thread[k] for k in ("end_a", "end_a_turn", "end_b", "end_b_turn")}
    thread.update(follow)

    # The releases: the force on end B decreases to 0 (release), then the drag decays to exactly 0 (rest), so
    # that each released knot ends in an equilibrium held by friction alone, or comes undone. Both stages take
    # Newton's line search: without it the sliding knot costs 7 times the factorisations, in steps cut back
    # to 1/2000 of the nominal one (docs/knot.md). pin_release: end A turns freely about its fixed position
    # once the force is released.
    def branch(mu):
        release = {"name": "release", "steps": 20, "stabilization": 0.01, "line_search": True}
        if pin_release:
            release["release"] = ["end_a_turn"]
        release["loads"] = {"pull_b": {"force": [0, 0, 0]}}
        rest = {"name": "rest", "steps": 20, "duration": 40, "stabilization": 0.01, "stabilization_end": 0,
                "line_search": True}
        return {"name": f"mu_{mu:.2f}", "from": "settle", "contact": {"friction": mu}, "stages": [release, rest]}

    tighten = {"line_search": True} if tighten_line_search else {}
    rod = {"material": "nylon", "radius": 0.1}
    clamp_beam = {"material": "nylon", "radius": 0.1, "length": num(CLAMP_LENGTH), "elements": CLAMP_ELEMENTS,
                  "direction": [0, 1, 0], "director1": [1, 0, 0]}
    return {
        "units": {"length": "mm", "force": "N", "stress": "MPa", "time": "s"},
        "materials": [{"name": "nylon", "young_modulus": 4000, "poisson_ratio": 0.3}],
        "beams": [
            {"name": "rod", **rod, "length": 20, "elements": elements, "start": [-10, 0, 0],
             "direction": [1, 0, 0], "director1": [0, 1, 0], "bending_factor": 0.3},
            {"name": "clamp_top", **clamp_beam, "start": vec(clamp_start["top"])},
            {"name": "clamp_bottom", **clamp_beam, "start": vec(clamp_start["bottom"])}],
        "conditions": [
            {"name": "end_a", "type": "motion", "beam": "rod", "at": "start", "dofs": ["position"]},
            {"name": "end_a_turn", "type": "motion", "beam": "rod", "at": "start", "dofs": ["directors"]},
            {"name": "end_b", "type": "motion", "beam": "rod", "at": "end", "dofs": ["position"]},
            {"name": "end_b_turn", "type": "motion", "beam": "rod", "at": "end", "dofs": ["directors"]},
            {"name": "pull_b", "type": "load", "beam": "rod", "at": "end", "active": False},
            {"name": "clamp_top_a", "type": "motion", "beam": "clamp_top", "at": "start"},
            {"name": "clamp_top_b", "type": "motion", "beam": "clamp_top", "at": "end"},
            {"name": "clamp_bottom_a", "type": "motion", "beam": "clamp_bottom", "at": "start"},
            {"name": "clamp_bottom_b", "type": "motion", "beam": "clamp_bottom", "at": "end"}],
        "stages": [
            {"name": "loop", "steps": 60, "stabilization": 0.01, "stabilization_end": 0, "motions": loop},
            {"name": "clamp", "steps": 10, "stabilization": 0.01, "motions": clamp},
            {"name": "thread", "steps": 100, "stabilization": 0.01, "motions": thread},
            {"name": "unclamp", "steps": 4, "stabilization": 0.01, "contact_off": ["clamp_top", "clamp_bottom"],
             "motions": unclamp},
            {"name": "pull", "steps": 40, "stabilization": 0.01, "release": ["end_b", "end_b_turn"],
             "activate": ["pull_b"], "loads": {"pull_b": {"force": [num(force), 0, 0]}}, **tighten},
            {"name": "settle", "steps": 16, "duration": 8, "stabilization": 0.01, **tighten}],
        "branches": [branch(mu) for mu in FRICTIONS],
        # The exact friction tangent (varying, not symmetric: hence an LU solver below, KLU, 1.75 times
        # faster per factorisation than UMFPACK on these 5,859 unknowns). Loop 3's passes before
        # the last stop at 1e-2 of the total normal force: 3,749 Newton iterations in the main run instead of
        # 4,387 (docs/performance.md). No line search: it saves 12 % more, but the 150-element knot test's
        # axes then come 0.188 mm close, below its limit of 2R - 4 p_max = 0.192 mm.
        "contact": {"friction": 0.3, "friction_tangent": "varying", "max_detections": 2, "particles": "facing",
                    "normal_pass_residual": 0.01,
                    **({"section_pairing": section_pairing} if section_pairing != "plane" else {}),
                    # The clamps guide the loop without dragging the rod as it slides through them (the paper
                    # does not give their friction): 13 % less time for the whole example, the tightened
                    # knot within 0.2 % (docs/performance.md, "Frictionless clamps").
                    "friction_pairs": [{"beams": ["clamp_top", "clamp_bottom"], "friction": 0}]},
        "solver": {"linear_solver": "klu", "line_search": False, "max_newton_iterations": 40,
                   "easy_iterations": 20},
        "output": {"vtk_every": 10, "checkpoint_every": 50},
    }


# The 3x1 yarn knot (Sect. 7.3, Table 2): the monofilament's program drawn to the yarn's scale. The yarn is 6 mm
# long, against the rod's 20: the loop's lengths are the monofilament's scaled by YARN_SCALE = 6 / 20, and the
# waypoints of `thread` (YARN_THREAD) were drawn for the yarn's loop.
YARN = {"rovings": 3, "fibres_per_roving": 1, "fibre_radius": 0.0564, "length": 6.0}
YARN_SCALE = 0.3
YARN_TWIST = 1030.0  # degrees (examples/yarn_3x1_twist.yaml: a surface helix angle of 20 degrees)
YARN_TWISTED_LENGTH = 5.88  # mm, the length of the twisted yarn (docs/yarns.md)
YARN_LOOP_RISE = 0.35
YARN_TAIL_A, YARN_LOOP, YARN_TAIL_B = 1.92, 3.27, 0.81  # mm, along the yarn from end A to the crossing, round the loop, to end B
YARN_LOOP_CROSSING = (-1.245, 0.13)  # where the loop crosses the yarn after `loop` (coarse runs) [mm]
YARN_LOOP_FAR = (-0.29, 1.0)  # the loop's point farthest from the crossing [mm]
YARN_CLAMP_RADIUS = 0.06
YARN_CLAMP_LENGTH = 0.9
YARN_CLAMP_DEPTH = 0.01
YARN_CLAMP_Z = 0.12  # height of the loop's far point [mm]
YARN_CLAMP_AWAY = 0.45
YARN_CLAMP_DISTANCE = 0.18  # the yarn's outer radius + the clamp's
YARN_THREAD_DURATION = 4.0  # s: 4 times slower than `loop`, so that the drag presses the yarn less
# The clamps hold the loop through end B's dive, the first YARN_DIVE of the threading (stage `thread`); they are
# taken away before end B comes up through the loop (stage `close`, the rest of the threading). Held further,
# they squeezed the yarn as end B lifted the loop (below -2 p_max from 37 % of the threading on) or stalled the
# threading (docs/knot_3x1.md, "Clamping beams").
YARN_DIVE = 0.3
# The path of the loop's far point (node 114 of the mean centreline, (-0.293, 1.011, 0.124) mm after `loop`)
# through the dive, in the example without clamps (run of 2026-11-29): (fraction of the dive, displacement
# [mm]). The clamps' supports follow it, as the monofilament's follow LOOP_TOP.
YARN_LOOP_FAR_PATH = [
    (0.167, [-0.048, -0.008, 0.004]), (0.333, [-0.081, -0.014, 0.010]), (0.5, [-0.122, -0.034, 0.023]),
    (0.6, [-0.132, -0.041, 0.027]), (0.767, [-0.144, -0.048, 0.029]), (0.933, [-0.158, -0.055, 0.033]),
    (1.0, [-0.164, -0.059, 0.035])]
# End B's axis at 0.3 turns only part of the way towards +y: turned fully (0, 1, -0.1) while end B dives, the
# yarn bent sharply at its rigid end, fibre r1's last element shortened to 0.85 h and its end section overlapped
# fibre r3's by 3.1 p_max (docs/knot_3x1.md, "End B's dive").
YARN_THREAD = [  # (fraction of `thread`, position of end B [mm], its axis)
    (0.15, [-1.0, -0.95, -0.25], [0, -0.3, -1]), (0.3, [-0.9, -0.6, -0.45], [0, 0.6, -0.8]),
    (0.5, [-0.68, 0.38, -0.45], [0, 1, 0.3]), (0.65, [-0.62, 0.42, 0.45], [0, 0, 1]),
    (0.8, [-0.2, -0.1, 0.45], [1, -0.5, 0]), (1.0, [0.4, -0.3, 0.3], [1, 0, 0])]


YARN_FRICTIONS = (0.30, 0.20)  # the loosening branches (Sect. 7.3.3)


def split_motion(motion, at):
    """The keyframes of one stage's motion target split at stage fraction `at` into those of two stages, each
    with its fractions of its own stage. A keyframe is added at `at` if there is none, interpolated linearly
    between two keyframes of the same rotation."""
    keyframes = motion["keyframes"]
    if not any(abs(k["at"] - at) < 1e-9 for k in keyframes):
        i = next(i for i, k in enumerate(keyframes) if k["at"] > at)
        before = keyframes[i - 1] if i > 0 else {"at": 0.0, "translation": [0, 0, 0], "rotation": [0, 0, 0]}
        after = keyframes[i]
        if before["rotation"] != after["rotation"]:
            raise ValueError("split_motion: a rotation would be interpolated")
        u = (at - before["at"]) / (after["at"] - before["at"])
        translation = (1 - u) * np.array(before["translation"]) + u * np.array(after["translation"])
        keyframes = keyframes[:i] + [{"at": at, "translation": vec(translation), "rotation": after["rotation"]}] + \
            keyframes[i:]
    first = [dict(k, at=num(k["at"] / at)) for k in keyframes if k["at"] <= at + 1e-9]
    second = [dict(k, at=num((k["at"] - at) / (1 - at))) for k in keyframes if k["at"] > at + 1e-9]
    return {"keyframes": first}, {"keyframes": second}


def yarn_knot_scenario(elements=100, force=0.5, stabilization=0.3, clamp=True, stages=None):
    """The 3x1 yarn knot's scenario as data: the yarn twisted by the rigid bodies at its rovings' ends, then
    tied, tightened and released as the monofilament (knot_scenario()), its ends moved as rigid assemblies.
    `clamp`: two clamping beams hold the loop through end B's dive (YARN_DIVE); without, the loop is threaded
    as one stage `thread` and nothing holds it."""
    s = YARN_SCALE
    m = YARN["rovings"]
    half = YARN["length"] / 2
    start_x, end_x = -half, -half + YARN_TWISTED_LENGTH

    a = End("end_a", [start_x, 0, 0])
    b = End("end_b", [end_x, 0, 0])
    # loop: end B rolls the yarn up into a loop of radius rho that crosses the yarn A-B at XC, as the end of
    # a circular arc that turns by 270 degrees followed by the straight tail, rising by LOOP_RISE so that the
    # tail passes over the yarn. The loop is then the monofilament's after `loop` at YARN_SCALE: its loop
    # (10.9 mm from the crossing round to it) and its tails (6.4 mm to end A, 2.7 mm to end B).
    tail_a, loop_length, tail_b = YARN_TAIL_A, YARN_LOOP, YARN_TAIL_B
    rho = loop_length / (1.5 * np.pi + 2)
    xc = start_x + tail_a
    x0, arc, tail = xc + rho, 1.5 * np.pi * rho, rho + tail_b
    n = 24
    waypoints = []
    for i in range(1, n + 1):
        th = 1.5 * np.pi * i / n
        heading = np.array([np.cos(th), np.sin(th), 0.0])
        point = np.array([x0 + arc / th * np.sin(th), arc / th * (1 - np.cos(th)), 0.0]) + tail * heading
        point[2] = YARN_LOOP_RISE * min(1.0, 1.5 * i / n)
        waypoints.append((i / n, point, heading))
    loop = {"end_a": a.move([(1.0, [start_x, 0, 0], [1, 0, 0])]), "end_b": b.move(waypoints)}

    # thread: the monofilament's passes, drawn for the yarn's loop (its crossing near (-1.25, 0.13), its inside
    # about (-0.7, 0.55), 0.45 across; clearances in yarn radii, not scaled): end B dives, turns back under
    # the yarn and the loop, comes up through the loop, leaves over the loop's side beyond the crossing and
    # heads along x, while end A feeds yarn into the loop.
    thread = {"end_a": a.move([(1.0, [start_x + s * 3.0, 0, 0], [1, 0, 0])]),
              "end_b": b.move([(t, [P[0], P[1], P[2]], d) for t, P, d in YARN_THREAD])}

    ends = {"end_a": "start", "end_b": "end"}
    conditions, twist_motions = [], {}
    for k in range(1, m + 1):
        for end, where in ends.items():
            pivot = [start_x if where == "start" else end_x, 0, 0]
            conditions.append({"name": f"{end}{k}", "type": "motion", "bodies": [f"yarn.r{k}.{where}"],
                               "pivot": vec(pivot), "active": where == "start"})
        # The twist (examples/yarn_3x1_twist.yaml): the end bodies turn about the yarn axis, their own rotation
        # held, free along the axis under a small tension; one condition per body, so that each can be released.
        conditions += [
            {"name": f"turn{k}", "type": "motion", "bodies": [f"yarn.r{k}.end"], "dofs": ["y", "z"],
             "pivot": [num(end_x), 0, 0]},
            {"name": f"keep{k}", "type": "clamp", "bodies": [f"yarn.r{k}.end"], "dofs": ["rotation"]},
            {"name": f"tension{k}", "type": "load", "bodies": [f"yarn.r{k}.end"], "force": [0.05, 0, 0]},
            {"name": f"pull_b{k}", "type": "load", "bodies": [f"yarn.r{k}.end"], "active": False}]
        twist_motions[f"turn{k}"] = {"rotation": [YARN_TWIST, 0, 0]}
    # From the pull on, end B's bodies move together along x (a bind, docs/bodies.md): the force drives the
    # yarn's end, not each fibre alone, and no fibre can slide out of the knot on its own in the releases.
    conditions.append({"name": "bind_b", "type": "bind", "bodies": [f"yarn.r{k}.end" for k in range(1, m + 1)],
                       "dofs": ["x"], "active": False})

    def per_body(motions):
        return {f"{end}{k}": target for end, target in motions.items() for k in range(1, m + 1)}

    twist_ends = [f"{c}{k}" for c in ("turn", "keep", "tension") for k in range(1, m + 1)]
    # The clamp (as the monofilament's): two beams across the far end of the loop, one above it and one
    # below, brought onto it and held there while end B threads the loop, then taken away.
    far = np.array(YARN_LOOP_FAR)
    across = np.array([-far[1] + YARN_LOOP_CROSSING[1], far[0] - YARN_LOOP_CROSSING[0], 0.0])
    across /= np.linalg.norm(across)
    side = {"top": 1.0, "bottom": -1.0}
    closed = {k: np.array([0, 0, -z * (YARN_CLAMP_AWAY - YARN_CLAMP_DISTANCE + YARN_CLAMP_DEPTH)])
              for k, z in side.items()}
    clamp_start = {k: np.array([far[0], far[1], YARN_CLAMP_Z + z * YARN_CLAMP_AWAY]) - across * YARN_CLAMP_LENGTH / 2
                   for k, z in side.items()}
    clamp_beam = {"material": "polyamide", "radius": YARN_CLAMP_RADIUS, "length": YARN_CLAMP_LENGTH,
                  "elements": 12, "direction": vec(across), "director1": [0, 0, 1]}
    clamp_beams = [{"name": f"clamp_{k}", **clamp_beam, "start": vec(clamp_start[k])} for k in side]
    for k in side:
        for e, where in (("a", "start"), ("b", "end")):
            conditions.append({"name": f"clamp_{k}_{e}", "type": "motion", "beam": f"clamp_{k}", "at": where})
    follow = clamp_motions({k: [(at, closed[k] + np.array(d)) for at, d in YARN_LOOP_FAR_PATH] for k in side},
                           True)
    unclamp = clamp_motions({k: closed[k] + np.array(YARN_LOOP_FAR_PATH[-1][1]) + [0, 0, z * YARN_CLAMP_AWAY]
                             for k, z in side.items()})

    program = [
        # MUMPS throughout: with the AMD ordering and the one thread it takes below 10,000 unknowns, the twist
        # runs faster than on KLU, which it used to take for being 10 % faster than MUMPS with PORD
        # (docs/performance.md, "MUMPS for small tangents"). Facing particles on the twist, as
        # examples/yarn_3x1_twist.yaml: with the centres that the threading needs (docs/contact.md) the twist
        # took twice the steps (docs/knot_3x1.md).
        {"name": "twist", "steps": 140, "particles": "facing", "motions": twist_motions},
        {"name": "loop", "steps": 60, "stabilization": stabilization,
         "release": twist_ends, "activate": [f"end_b{k}" for k in range(1, m + 1)],
         "motions": per_body(loop)},
        {"name": "clamp", "steps": 10, "stabilization": stabilization, "motions": clamp_motions(closed)},
        {"name": "thread", "steps": 100, "duration": YARN_THREAD_DURATION, "stabilization": stabilization,
         "motions": per_body(thread)},
        {"name": "unclamp", "steps": 4, "stabilization": stabilization, "contact_off": ["clamp_top", "clamp_bottom"],
         "motions": unclamp},
        {"name": "close", "steps": 0, "duration": 0, "stabilization": stabilization},  # set below
        # End B is pulled along x through a guide: the bodies keep the position across x and the rotation
        # that the threading left them (the twist's conditions turn and keep, taken again), each pulled by F / 3,
        # and bound together along x.
        {"name": "pull", "steps": 40, "stabilization": stabilization,
         "release": [f"end_b{k}" for k in range(1, m + 1)],
         "activate": [f"{c}{k}" for c in ("pull_b", "turn", "keep") for k in range(1, m + 1)] + ["bind_b"],
         "loads": {f"pull_b{k}": {"force": [num(force / m), 0, 0]} for k in range(1, m + 1)}},
        {"name": "settle", "steps": 16, "duration": 8, "stabilization": stabilization}]

    def branch(mu):
        release = {"name": "release", "steps": 20, "stabilization": 0.01, "line_search": True,
                   "loads": {f"pull_b{k}": {"force": [0, 0, 0]} for k in range(1, m + 1)}}
        rest = {"name": "rest", "steps": 20, "duration": 40, "stabilization": 0.01, "stabilization_end": 0,
                "line_search": True}
        return {"name": f"mu_{mu:.2f}", "from": "settle", "contact": {"friction": mu}, "stages": [release, rest]}

    contact = {"friction": 0.3, "friction_tangent": "varying", "max_detections": 2, "particles": "centres",
               "normal_pass_residual": 0.01}
    if clamp:
        # `thread` is end B's dive, with the clamps following the loop's far point; `close` the rest of the
        # threading, the same waypoints, after `unclamp`.
        thread_stage = next(st for st in program if st["name"] == "thread")
        close = next(st for st in program if st["name"] == "close")
        dive_motions, close["motions"] = {}, {}
        for name, motion in thread_stage["motions"].items():
            dive_motions[name], close["motions"][name] = split_motion(motion, YARN_DIVE)
        thread_stage["motions"] = {**dive_motions, **follow}
        close["steps"] = thread_stage["steps"] - round(YARN_DIVE * thread_stage["steps"])
        close["duration"] = num((1 - YARN_DIVE) * YARN_THREAD_DURATION)
        thread_stage["steps"] = round(YARN_DIVE * thread_stage["steps"])
        thread_stage["duration"] = num(YARN_DIVE * YARN_THREAD_DURATION)
        # Frictionless against everything: the clamps keep the loop from rising and turning without dragging
        # it along their path (with mu = 0.3 they stalled the threading, docs/knot_3x1.md).
        contact["friction_pairs"] = [{"beams": ["clamp_top", "clamp_bottom"], "friction": 0}]
    else:
        program = [st for st in program if st["name"] not in ("clamp", "unclamp", "close")]
        clamp_beams = []
        conditions = [c for c in conditions if not c["name"].startswith("clamp_")]
    if stages:
        program = [st for st in program if st["name"] in stages]
    return {
        "units": {"length": "mm", "force": "N", "stress": "MPa", "time": "s"},
        "materials": [{"name": "polyamide", "young_modulus": 4000, "poisson_ratio": 0.3}],
        **({"beams": clamp_beams} if clamp_beams else {}),
        "yarns": [{"name": "yarn", **YARN, "elements": elements, "material": "polyamide",
                   "start": [num(start_x), 0, 0]}],
        "conditions": conditions,
        "stages": program,
        **({"branches": [branch(mu) for mu in YARN_FRICTIONS]} if not stages or "settle" in stages else {}),
        "contact": contact,
        # MUMPS: 1.7 times KLU's speed where the knot forms, and faster on the twist too (above); a
        # solve that has not converged in 30 iterations rarely does, and one whose residual has not fallen
        # tenfold in 10 iterations is given up (a fifth fewer factorisations in the main run;
        # docs/performance.md, "The 3x1 knot", "Failing sooner").
        "solver": {"linear_solver": "mumps", "line_search": False, "max_newton_iterations": 30,
                   "easy_iterations": 30, "progress_window": 10},
        "output": {"vtk_every": 10, "checkpoint_every": 50},
    }



HEADER = """\
# The monofilament overhand knot of Durville (2012), Sect. 7.2 and Table 1: a rod 20 mm long, radius 0.1 mm,
# E = 4000 MPa, nu = 0.3, bending stiffness x 0.3, tied from its straight state by moving its ends,
# tightened by pulling one end, then released for mu = 0.3, 0.25 and 0.2 (docs/knot.md).
# Generated by scripts/knot_program.py {arguments};
# edit that script, not this file.
#  loop:    end B is carried round and over the rod, making a loop with one crossing (end A turns by 45 deg);
#  clamp:   two clamping beams, held at their ends, are brought onto the top of the loop from above and below;
#  thread:  end B dives under the loop, comes up through it and leaves over its far side, while end A feeds
#           rod into the loop and the clamp follows the top of the loop;
#  unclamp: the clamping beams are taken out of contact and lifted away;
#  pull:    end B is let go (position and section) and a force of {force:g} N pulls it along +x; end A stays
#           clamped;
#  settle:  the force held until the knot stops moving: the tightened knot (Figs. 13, 14);
#  branches mu_*: from the tightened knot, the force decreases to 0 (release), then the drag decays to 0
#           (rest): the released knot ends at rest, held by friction alone, or undone (Figs. 15-17). Both
#           stages take Newton's line search.{pin_note}
# Every stage carries a viscous drag (stages[].stabilization, docs/model.md) that keeps the rod from snapping
# through; it vanishes as the rod comes to rest, and steps.csv reports what is left of it (stabilization_force).
# In loop it lets the straight rod, compressed by its ends, buckle, and decays to 0 by the end of the stage.
"""

YARN_HEADER = """\
# The 3x1 multifilament overhand knot of Durville (2012), Sect. 7.3 and Table 2: three fibres of radius
# 0.0564 mm, 6 mm long, E = 4000 MPa, nu = 0.3, {elements} elements each, twisted into a yarn by rigid bodies
# at their ends, tied by moving the ends as rigid assemblies, tightened by pulling end B, then released for
# mu = 0.3 and 0.2 (docs/knot_3x1.md).
# Generated by scripts/knot_program.py {arguments};
# edit that script, not this file.
#  twist:   the end B bodies turn about the yarn's axis by {twist:g} deg under a small tension (as
#           examples/yarn_3x1_twist.yaml: KLU, MUMPS in the other stages; particles facing along the
#           normal, along the centres in the other stages);
#  loop:    end B is carried round and over the yarn, making a loop with one crossing;
#  clamp:   two clamping beams, held at their ends, are brought onto the loop's far side from above and
#           below (frictionless against the yarn: contact.friction_pairs);
#  thread:  end B dives under the loop while end A feeds yarn into it, the clamps following the loop;
#  unclamp: the clamping beams are taken out of contact and lifted away;
#  close:   end B comes up through the loop and leaves over its far side, end A still feeding;
#  pull:    end B is let go along x and a force of {force:g} N (a third on each fibre) pulls it; its bodies keep
#           their position across x and their rotation, and move together along x (bind_b); end A stays
#           clamped;
#  settle:  the force held until the knot stops moving: the tightened knot (Fig. 19);
#  branches mu_*: from the tightened knot, the force decreases to 0 (release), then the drag decays to 0
#           (rest): the released knots (Figs. 20, 21).
# Contact: particles facing along the line of the section centres (contact.particles: centres), but in
# twist (stages[].particles: facing).
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=None,
                        help="quadratic elements along the rod (default 300), or along each fibre with --yarn "
                             "(default 100)")
    parser.add_argument("--force", type=float, default=0.5, help="tightening force on end B [N]")
    parser.add_argument("--pin-release", action="store_true",
                        help="let end A turn about its fixed position in the releases")
    parser.add_argument("--yarn", action="store_true",
                        help="the 3x1 yarn knot (Sect. 7.3) instead; --elements then counts per fibre")
    parser.add_argument("--no-clamp", action="store_true",
                        help="with --yarn: no clamping beams, the loop threaded in one stage")
    args = parser.parse_args()
    if args.yarn:
        elements = args.elements or 100
        scenario = nodus.Scenario(yarn_knot_scenario(elements, args.force, clamp=not args.no_clamp))
        arguments = f"--yarn --elements {elements} --force {args.force:g}" + (" --no-clamp" if args.no_clamp else "")
        sys.stdout.write(YARN_HEADER.format(elements=elements, arguments=arguments, twist=YARN_TWIST,
                                            force=args.force) + scenario.to_yaml())
        return
    # Built and checked by nodus's own reader through the Python module, then written as a scenario file.
    args.elements = args.elements or 300
    scenario = nodus.Scenario(knot_scenario(args.elements, args.force, args.pin_release))
    pin_note = ("""
#           With --pin-release end A turns freely about its fixed position from the start of release."""
                if args.pin_release else "")
    arguments = f"--elements {args.elements} --force {args.force:g}" + (" --pin-release" if args.pin_release else "")
    sys.stdout.write(HEADER.format(arguments=arguments, force=args.force, pin_note=pin_note) + scenario.to_yaml())


if __name__ == "__main__":
    main()
