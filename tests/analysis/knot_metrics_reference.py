"""The knot metrics in numpy, as scripts/knot_report.py computed them before they moved into C++
(src/nodus/analysis/knot_metrics.hpp): an independent implementation of the same definitions, kept
as the reference of tests/analysis/test_knot_metrics.cpp (KnotMetricsPythonReference.SameNumbersOnASyntheticKnot), which
runs it on a synthetic run folder and compares every number with the C++. Not used by nodus itself.

Reads DIR/final_nodes.csv, DIR/contact_final.csv and DIR/steps.csv as knot_report.py does (load_state), and
computes one row of knot_report.csv and the reactions table (analyse). Requires python3-numpy.
"""

import csv
from dataclasses import dataclass

import numpy as np

TAIL_CHORD = 2.0          # mm, length along each tail of the chord giving its direction
MIN_SPACING = 0.05        # mm, least element spacing for the contact coverage of the loop
MIN_LOOP_NODES = 5        # nodes needed for the circle fit
DEFAULT_RADIUS = 0.1      # mm, rod radius of Sect. 7.2 when it cannot be measured from the contact table


@dataclass
class State:
    """One knot state read from a run folder."""
    name: str
    friction: object         # float, or None when unknown
    nodes: dict              # column -> array, the rod's nodes sorted by s
    contact: dict            # column -> array, elements sorted by (zone, zeta)
    last_step: dict          # column -> value of the last row of steps.csv ({} if there is none)


def read_table(path):
    """A CSV file as {column: array}: numbers as float arrays, text as object arrays."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    table = {}
    for column in rows[0] if rows else []:
        values = [row[column] for row in rows]
        try:
            table[column] = np.array(values, dtype=float)
        except ValueError:
            table[column] = np.array(values, dtype=object)
    return table


def load_state(folder, name, friction):
    """The nodes of the first beam sorted by s, the contact elements sorted by (zone, zeta), and the numbers of
    the last row of steps.csv (if there is one) of the run in `folder`."""
    nodes = read_table(folder / "final_nodes.csv")
    nodes = {k: v[nodes["beam"] == nodes["beam"][0]] for k, v in nodes.items()}
    nodes = {k: v[np.argsort(nodes["s"], kind="stable")] for k, v in nodes.items()}
    contact = read_table(folder / "contact_final.csv")
    contact = {k: v[np.lexsort((contact["zeta"], contact["zone"]))] for k, v in contact.items()}
    last_step = {}
    if (folder / "steps.csv").is_file():
        steps = read_table(folder / "steps.csv")
        last_step = {k: float(v[-1]) for k, v in steps.items() if v.dtype == float and len(v)}
    return State(name, friction, nodes, contact, last_step)


def centreline(nodes, s):
    """Centreline points at arc lengths s (linear between nodes, clamped to the rod ends)."""
    return np.stack([np.interp(s, nodes["s"], nodes[c]) for c in ("x", "y", "z")], axis=-1)


def midpoints(contact):
    return np.stack([(contact[f"{c}_i"] + contact[f"{c}_j"]) / 2 for c in ("x", "y", "z")], axis=-1)


def intermediate_abscissa(contact):
    """Abscissa of each element along the polyline of midpoints, zone after zone (elements sorted)."""
    mid = midpoints(contact)
    abscissa = np.zeros(len(mid))
    start = 0.0
    for zone in np.unique(contact["zone"]):
        index = np.flatnonzero(contact["zone"] == zone)
        steps = np.linalg.norm(np.diff(mid[index], axis=0), axis=1)
        abscissa[index] = start + np.concatenate([[0.0], np.cumsum(steps)])
        start = abscissa[index[-1]]
    return abscissa


def intermediate_length(contact, abscissa):
    """Sum over zones of the abscissa span of the elements in contact."""
    length = 0.0
    for zone in np.unique(contact["zone"]):
        touching = abscissa[(contact["zone"] == zone) & (contact["normal_force"] > 0)]
        if len(touching):
            length += touching.max() - touching.min()
    return length


def element_spacing(contact):
    """Median |difference| of successive abscissa_i within a zone, at least MIN_SPACING."""
    diffs = [np.abs(np.diff(contact["abscissa_i"][contact["zone"] == zone]))
             for zone in np.unique(contact["zone"])]
    diffs = np.concatenate(diffs) if diffs else np.array([])
    return max(float(np.median(diffs)), MIN_SPACING) if len(diffs) else MIN_SPACING


def tail_angle(nodes, s_a, s_b):
    """Angle (deg) between the tail directions leaving the knot [s_a, s_b]; nan if they are degenerate."""
    s_min, s_max = nodes["s"][0], nodes["s"][-1]
    exits = centreline(nodes, np.array([s_a, s_b]))
    outs = centreline(nodes, np.array([max(s_a - TAIL_CHORD, s_min), min(s_b + TAIL_CHORD, s_max)]))
    chords = outs - exits
    lengths = np.linalg.norm(chords, axis=1)
    if np.any(lengths < 1e-12):
        return np.nan
    cosine = np.dot(chords[0], chords[1]) / (lengths[0] * lengths[1])
    return float(np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0))))


def longest_uncovered(centres, half_width, lo, hi):
    """The longest sub-interval of [lo, hi] farther than half_width from every centre, or None."""
    best, position = None, lo
    for start, end in sorted((c - half_width, c + half_width) for c in centres):
        if start > position and (best is None or start - position > best[1] - best[0]):
            best = (position, min(start, hi))
        position = max(position, end)
        if position >= hi:
            break
    if position < hi and (best is None or hi - position > best[1] - best[0]):
        best = (position, hi)
    return best


def fit_circle(points):
    """Radius of the least-squares circle through 3-D points: plane by SVD, algebraic (Kasa) fit in it."""
    centred = points - points.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    u, v = centred @ vt[0], centred @ vt[1]
    a = np.column_stack([2 * u, 2 * v, np.ones_like(u)])
    (cu, cv, c), *_ = np.linalg.lstsq(a, u * u + v * v, rcond=None)
    return float(np.sqrt(c + cu * cu + cv * cv))


def loop_geometry(nodes, contact, s_a, s_b):
    """(radius, length) of the loop of the knot [s_a, s_b]; nan where there is none."""
    touching = contact["normal_force"] > 0
    centres = np.concatenate([contact["abscissa_i"][touching], contact["abscissa_j"][touching]])
    interval = longest_uncovered(centres, element_spacing(contact) / 2, s_a, s_b)
    if interval is None:
        return np.nan, np.nan
    inside = (nodes["s"] >= interval[0]) & (nodes["s"] <= interval[1])
    points = np.column_stack([nodes[c][inside] for c in ("x", "y", "z")])
    radius = fit_circle(points) if len(points) >= MIN_LOOP_NODES else np.nan
    return radius, interval[1] - interval[0]


def knot_extent(contact):
    """(s_a, s_b): the range of rod arc length touched by elements in contact; nan if none is."""
    touching = contact["normal_force"] > 0
    if not touching.any():
        return np.nan, np.nan
    s = np.concatenate([contact["abscissa_i"][touching], contact["abscissa_j"][touching]])
    return float(s.min()), float(s.max())


def rod_radius(states):
    """The rod radius: median distance of the contact particles x_i from the centreline at abscissa_i."""
    distances = []
    for state in states:
        contact = state.contact
        particles = np.column_stack([contact[f"{c}_i"] for c in ("x", "y", "z")])
        distances.append(np.linalg.norm(particles - centreline(state.nodes, contact["abscissa_i"]), axis=1))
    distances = np.concatenate(distances) if distances else np.array([])
    return float(np.median(distances)) if len(distances) else DEFAULT_RADIUS


def pull_force(last_step):
    components = [last_step.get(f"pull_b_f{c}") for c in "xyz"]
    return float(np.linalg.norm(components)) if None not in components else np.nan


def analyse(state):
    """(row of knot_report.csv as a dict, reactions table as a dict of columns, (s_a, s_b))."""
    contact = state.contact
    abscissa = intermediate_abscissa(contact)
    s_a, s_b = knot_extent(contact)
    touching = contact["normal_force"] > 0
    normal, tangential = contact["normal_force"], contact["tangential_force"]
    if np.isnan(s_a):
        angle, (radius, length) = np.nan, (np.nan, np.nan)
    else:
        angle = tail_angle(state.nodes, s_a, s_b)
        radius, length = loop_geometry(state.nodes, contact, s_a, s_b)
    row = {
        "state": state.name,
        "friction": state.friction,
        "tightening_force_N": pull_force(state.last_step),
        "stabilization_force_N": state.last_step.get("stabilization_force", np.nan),
        "zones": len(np.unique(contact["zone"])),
        "contact_elements": len(contact["zone"]),
        "elements_in_contact": int(touching.sum()),
        "intermediate_length_mm": intermediate_length(contact, abscissa),
        "max_normal_N": normal.max() if len(normal) else 0.0,
        "total_normal_N": normal.sum(),
        "max_tangential_N": tangential.max() if len(tangential) else 0.0,
        "total_tangential_N": tangential.sum(),
        "tail_angle_deg": angle,
        "loop_radius_mm": radius,
        "loop_length_mm": length,
        "max_penetration_mm": (-contact["gap"]).max() if len(contact["gap"]) else np.nan,
    }
    mid = midpoints(contact)
    reactions = {"zone": contact["zone"], "zeta": contact["zeta"], "abscissa_mm": abscissa,
                 "s_i": contact["abscissa_i"], "s_j": contact["abscissa_j"], "x": mid[:, 0], "y": mid[:, 1],
                 "z": mid[:, 2], "normal_N": normal, "tangential_N": tangential, "state": contact["state"]}
    return row, reactions, (s_a, s_b)
