#!/usr/bin/env python3
"""3D views of an overhand-knot run of nodus, like Durville 2012, Figs. 12, 13, 15 and 16. Units: mm, N.

Usage: scripts/knot_views.py RUN_DIR [--out DIR] [--elev DEG] [--azim DEG] [--sides N] [--radius MM] [--dpi N]
       (Debian python3-numpy and python3-matplotlib; nothing else, not the nodus module)

Also called by scripts/knot_report.py, which writes the same pictures into RUN_DIR/report/.

Inputs (RUN_DIR is a run's output folder, docs/output.md; whatever is absent is skipped):
  RUN_DIR/stages/NNN_STAGE_nodes.csv, NNN_STAGE_contact.csv   the state at the end of every stage
  RUN_DIR/final_nodes.csv, contact_final.csv     the main run's final state (drawn only if it is not the
                                                 last stage end, e.g. a run that stopped early)
  RUN_DIR/summary.json                           optional: `branches` (names, folders, friction)
  RUN_DIR/branches/NAME/final_nodes.csv, contact_final.csv   each branch's final state: a released knot

Outputs, in RUN_DIR/report/ (or --out), one PNG per state (each written to a temporary name, then renamed):
  view3d_stage_NNN_STAGE.png    the end of stage NNN; the last one of the main run is the tightened knot
  view3d_final.png              the main run's final state, when it is not the last stage end
  view3d_NAME.png               the final state of branch NAME (the released knot)
Each holds the whole rod (left) and, when the rod is in contact with itself, the knot (right): the rod's
nodes with s in [s_a - 1, s_b + 1] mm, s_a and s_b the smallest and largest abscissa_i, abscissa_j of the
self-contact elements with normal_force > 0.

The knotted strand may be several beams (render_run(..., strands=NAMES, separation=D), as
scripts/knot_3x1_report.py draws the fibres of a yarn): each is then drawn in a colour of its own (blue,
amber, green, ...), and the knot's contact elements are those between two of them, or of one with itself,
whose abscissas lie more than D apart (the fibres' side-by-side contacts are not the knot's); the knot panel
shows every strand's nodes with s in [s_a - 1, s_b + 1] mm.

What is drawn:
  tube      the surface r(s) + R (cos phi e1 + sin phi e2) through the nodes of each beam (straight between
            nodes, `--sides` facets around, closed at the ends). (e1, e2) is a parallel-transport frame
            along the node polyline (tangents t by central differences, e1 carried from node to node by the
            rotation that takes t_k to t_k+1), so that the facets do not twist however the sections turn.
            The section directors of the table (g1, g2; docs/output.md) are drawn as a darker stripe: the
            facet between nodes k and k + 1 in the direction of g1 at node k projected normal to t (of g2,
            less 90 degrees, where g1 is within 17 degrees of t, as in a folded element). R is --radius,
            else the median distance of the contact particles x_i, x_j from the centreline at their
            abscissa (the beams of Sect. 7.2 all have R = 0.1 mm), else 0.1 mm.
  shading   ambient, Lambert and Blinn-Phong terms with a light above and to the left of the viewer, then
            mixed towards the white background with depth (the farthest facet 45 % white), so that the
            strand in front reads as in front at a crossing. Facets facing away from the viewer are left
            out; the others are painted from the farthest to the nearest (matplotlib's Poly3DCollection sorts
            them by mean depth). The rod is blue; other beams (the clamping beams) grey.
  contact   each zone's intermediate geometry (the polyline of the midpoints (x_i + x_j) / 2 of its
            elements, in zeta order; docs/output.md) as a dark red line, drawn over the tubes (it lies where
            they touch, inside them): thin in the whole-rod panel (all zones, the clamping beams' included),
            thick in the knot panel (the rod's self-contact). In the knot panel each element with R_N > 0
            carries a bar along its normal n centred on its midpoint, of length proportional to R_N (the
            longest 2.5 R) and coloured by R_N (colour bar).
  view      orthographic, equal scaling on the three axes (the box has the proportions of the data),
            elevation --elev and azimuth --azim (matplotlib's convention: the viewer sits in the direction
            (cos elev cos azim, cos elev sin azim, sin elev)); the default, 60 and -80 degrees, looks down on
            the knot's plane (z up) from the side of -y, x to the right. The axes are hidden; a triad of the
            x, y, z directions under each panel, with its length in mm, gives orientation and scale. End A
            is marked by a triangle, end B by a square.
"""

import argparse
import csv
import json
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib import cm, colors  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from mpl_toolkits.mplot3d import proj3d  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

DEFAULT_RADIUS = 0.1        # mm, the rod radius of Sect. 7.2, when it cannot be measured
KNOT_MARGIN = 1.0           # mm of rod either side of [s_a, s_b] in the knot panel
BAR_LENGTH = 2.5            # longest reaction bar, in rod radii
DEFAULT_ELEV, DEFAULT_AZIM = 60.0, -80.0   # degrees
DEFAULT_SIDES = 14          # facets around the tube
ROD_RGB = np.array([0.25, 0.47, 0.78])
STRAND_COLOURS = [("blue", ROD_RGB), ("amber", np.array([0.88, 0.58, 0.16])),
                  ("green", np.array([0.30, 0.64, 0.36])), ("purple", np.array([0.58, 0.40, 0.74])),
                  ("brown", np.array([0.60, 0.42, 0.30])), ("pink", np.array([0.86, 0.45, 0.66])),
                  ("olive", np.array([0.62, 0.62, 0.22])), ("cyan", np.array([0.25, 0.70, 0.76]))]
TOOL_RGB = np.array([0.62, 0.62, 0.62])
LINE_RGB = (0.55, 0.0, 0.0)  # the intermediate geometry, dark red as in Fig. 13
STRIPE_SHADE = 0.55         # the director stripe: the tube's colour times this
FOG = 0.45                  # share of white on the farthest facet
KNOT_ALPHA = 1.0            # opacity of the rod in the knot panel
REACTION_CMAP = "plasma"
DPI = 110                   # of the PNG files
FILL = 0.9                  # share of a panel's width or height that its drawing fills
TRIAD_BAND = 0.75           # inches under the panels for the triad of the axes
NODE_COLUMNS = ["s", "x", "y", "z"]
CONTACT_COLUMNS = ["zone", "zeta", "abscissa_i", "abscissa_j", "x_i", "y_i", "z_i", "x_j", "y_j", "z_j",
                   "nx", "ny", "nz"]


class ViewError(Exception):
    """A missing or unreadable input; reported as one line `knot_views: PATH: what`."""


@dataclass
class Beam:
    """One beam of a nodal table, nodes in order of s."""
    name: str
    s: np.ndarray           # (n,) reference arc length [mm]
    r: np.ndarray           # (n, 3) centreline [mm]
    g1: object = None       # (n, 3) first director, or None if the table has none
    g2: object = None


@dataclass
class StateFiles:
    """One state to draw: its tables, title and output name."""
    key: str                # the PNG is view3d_KEY.png
    title: str
    nodes: Path
    contact: object         # Path or None


# ------------------------------------------------------------------------------------------------ reading

def read_table(path, numeric):
    """A CSV file as {column: array}; the columns `numeric` must be there and numeric."""
    if not path.is_file():
        raise ViewError(f"{path}: missing")
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        header = reader.fieldnames or []
    absent = [c for c in numeric if c not in header]
    if absent:
        raise ViewError(f"{path}: missing column(s) {', '.join(absent)}")
    table = {}
    for column in header:
        values = [row[column] for row in rows]
        try:
            table[column] = np.array(values, dtype=float)
        except ValueError:
            if column in numeric:
                raise ViewError(f"{path}: column {column} not numeric") from None
            table[column] = np.array(values, dtype=object)
    return table


def read_beams(path):
    """The beams of a nodal table (final_nodes.csv or a stage-end table), in the table's order."""
    table = read_table(path, NODE_COLUMNS)
    names = table["beam"] if "beam" in table else np.array(["rod"] * len(table["s"]), dtype=object)
    has_directors = all(f"g{k}{c}" in table and table[f"g{k}{c}"].dtype == float for k in (1, 2) for c in "xyz")
    beams = []
    for name in dict.fromkeys(names):
        rows = np.flatnonzero(names == name)
        rows = rows[np.argsort(table["s"][rows], kind="stable")]
        if len(rows) < 2:
            continue
        pick = lambda prefix: np.column_stack([table[f"{prefix}{c}"][rows] for c in "xyz"])  # noqa: E731
        beams.append(Beam(str(name), table["s"][rows], np.column_stack([table[c][rows] for c in "xyz"]),
                          pick("g1") if has_directors else None, pick("g2") if has_directors else None))
    if not beams:
        raise ViewError(f"{path}: no beam with two nodes")
    return beams


def read_contact(path):
    """The contact table sorted by (zone, zeta), or None if there is no file. A table without force columns
    (contact.forces: false) gets normal_force 0."""
    if path is None or not path.is_file():
        return None
    table = read_table(path, CONTACT_COLUMNS)
    n = len(table["zone"])
    if "normal_force" not in table or table["normal_force"].dtype != float:
        table["normal_force"] = np.zeros(n)
    for column in ("beam_i", "beam_j"):
        table[column] = np.array(table[column] if column in table else ["rod"] * n, dtype=str)
    order = np.lexsort((table["zeta"], table["zone"]))
    return {k: v[order] for k, v in table.items()}


def rod_of(beams):
    """The beam named `rod`, else the first one."""
    return next((b for b in beams if b.name == "rod"), beams[0])


def strands_of(beams, names=None):
    """The beams of the knotted strand: those named in `names` (in the table's order), else (names None, or
    none of them in the table) [rod_of(beams)]."""
    strands = [b for b in beams if names is not None and b.name in names]
    return strands or [rod_of(beams)]


def strand_colour(k, count):
    """(name, rgb) of strand k of `count`: the rod's blue for a single strand, else the k-th of
    STRAND_COLOURS (cycled)."""
    return STRAND_COLOURS[0] if count == 1 else STRAND_COLOURS[k % len(STRAND_COLOURS)]


def centreline_at(beam, s):
    """Points of the centreline (linear between nodes) at arc lengths s."""
    return np.column_stack([np.interp(s, beam.s, beam.r[:, k]) for k in range(3)])


def measured_radius(beams, contact):
    """Median distance of the contact particles from the centreline at their abscissa, or None."""
    if contact is None or not len(contact["zone"]):
        return None
    by_name = {b.name: b for b in beams}
    distances = []
    for side in ("i", "j"):
        x = np.column_stack([contact[f"{c}_{side}"] for c in "xyz"])
        for name in set(contact[f"beam_{side}"]):
            if name not in by_name:
                continue
            rows = contact[f"beam_{side}"] == name
            axis = centreline_at(by_name[name], contact[f"abscissa_{side}"][rows])
            distances.extend(np.linalg.norm(x[rows] - axis, axis=1))
    return float(np.median(distances)) if distances else None


# ------------------------------------------------------------------------------------------------ states

def stage_files(run_dir):
    pattern = re.compile(r"^(\d{3,})_(.+)_nodes\.csv$")
    folder = run_dir / "stages"
    if not folder.is_dir():
        return []
    found = sorted((int(m.group(1)), m.group(1), m.group(2), p) for p in folder.iterdir()
                   if (m := pattern.match(p.name)))
    return [StateFiles(f"stage_{digits}_{stage}", f"end of stage {index}: {stage}", path,
                       path.with_name(f"{digits}_{stage}_contact.csv")) for index, digits, stage, path in found]


def friction_from_name(name):
    match = re.search(r"\d+(?:\.\d*)?|\.\d+", name)
    return float(match.group()) if match else None


def branch_files(run_dir):
    """The branches' final states, highest friction first: from summary.json's `branches`, else the
    folders of RUN_DIR/branches."""
    summary = {}
    if (run_dir / "summary.json").is_file():
        try:
            summary = json.loads((run_dir / "summary.json").read_text())
        except (OSError, ValueError):
            summary = {}
    listed = summary.get("branches") if isinstance(summary, dict) else None
    found = []
    if isinstance(listed, list) and listed:
        for entry in listed:
            entry = entry if isinstance(entry, dict) else {"name": str(entry)}
            name = str(entry.get("name", ""))
            friction = entry.get("friction")
            friction = float(friction) if isinstance(friction, (int, float)) else friction_from_name(name)
            found.append((name, run_dir / entry.get("folder", f"branches/{name}"), friction))
    elif (run_dir / "branches").is_dir():
        found = [(p.name, p, friction_from_name(p.name)) for p in sorted((run_dir / "branches").iterdir())
                 if p.is_dir()]
    found.sort(key=lambda b: -b[2] if b[2] is not None else np.inf)
    states = []
    for name, folder, friction in found:
        label = f"mu = {friction:g}" if friction is not None else name
        states.append(StateFiles(re.sub(r"[^A-Za-z0-9_.-]", "_", name), f"released knot, {label} ({name})",
                                 folder / "final_nodes.csv", folder / "contact_final.csv"))
    return states


def same_positions(path_a, path_b):
    try:
        a, b = read_table(path_a, NODE_COLUMNS), read_table(path_b, NODE_COLUMNS)
    except ViewError:
        return False
    return len(a["s"]) == len(b["s"]) and all(np.allclose(a[c], b[c], rtol=0, atol=1e-9) for c in "xyz")


def run_states(run_dir):
    """Every state of a run folder to draw, in order: stage ends, the final state if it differs from the
    last stage end, the branches. The last stage end of the main run is titled as the tightened knot when
    the run has branches (the knot program's `settle`)."""
    stages = stage_files(run_dir)
    states = list(stages)
    final = run_dir / "final_nodes.csv"
    if final.is_file() and not (stages and same_positions(stages[-1].nodes, final)):
        states.append(StateFiles("final", "final state", final, run_dir / "contact_final.csv"))
    branches = branch_files(run_dir)
    if branches and states:
        states[-1].title += " (the tightened knot)"
    return states + branches


# ------------------------------------------------------------------------------------------------ geometry

def unit_rows(v):
    return v / np.maximum(np.linalg.norm(v, axis=1, keepdims=True), 1e-300)


def tangents(r):
    """Unit tangents at the nodes: central differences inside, one-sided at the ends."""
    t = np.empty_like(r)
    t[1:-1] = r[2:] - r[:-2]
    t[0], t[-1] = r[1] - r[0], r[-1] - r[-2]
    return unit_rows(t)


def transport_frame(t):
    """A parallel-transport (rotation-minimising) frame along unit tangents t: e1 carried from node to node
    by the rotation about t_k x t_k+1 that takes t_k to t_k+1 (Rodrigues); returns (e1, e2 = t x e1)."""
    e1 = np.empty_like(t)
    seed = np.eye(3)[np.argmin(np.abs(t[0]))]
    e1[0] = seed - seed.dot(t[0]) * t[0]
    e1[0] /= np.linalg.norm(e1[0])
    for k in range(len(t) - 1):
        axis = np.cross(t[k], t[k + 1])
        sin, cos = np.linalg.norm(axis), float(np.clip(t[k].dot(t[k + 1]), -1.0, 1.0))
        e = e1[k]
        if sin > 1e-12:
            a = axis / sin
            e = e * cos + np.cross(a, e) * sin + a * a.dot(e) * (1.0 - cos)
        e = e - e.dot(t[k + 1]) * t[k + 1]
        e1[k + 1] = e / np.linalg.norm(e)
    return e1, np.cross(t, e1)


def director_angle(beam, t, e1, e2):
    """Angle [rad] about t of the section director g1 in the frame (e1, e2), at each node: from g1
    projected normal to t, or, where g1 is within 17 degrees of t, from g2 so projected, less 90 degrees;
    NaN where neither is usable. None without directors."""
    if beam.g1 is None:
        return None
    angles = np.full(len(t), np.nan)
    for g, shift in ((beam.g2, -np.pi / 2), (beam.g1, 0.0)):   # g1 last: it wins where both are usable
        p = g - np.sum(g * t, axis=1, keepdims=True) * t
        usable = np.linalg.norm(p, axis=1) > 0.3 * np.maximum(np.linalg.norm(g, axis=1), 1e-12)
        angle = np.arctan2(np.sum(p * e2, axis=1), np.sum(p * e1, axis=1)) + shift
        angles[usable] = angle[usable]
    return angles


def tube_facets(r, t, e1, e2, radius, sides, stripe=None):
    """(polygons [(4 or sides, 3)], outward normals (m, 3), on the stripe (m,) bool): the quadrilaterals
    between successive rings of the tube r + radius (cos phi e1 + sin phi e2), phi = 2 pi j / sides, then
    the two end discs. `stripe` (angles [rad] about t at the nodes in the frame (e1, e2), or None) marks,
    between rings k and k + 1, the quadrilateral whose sector holds stripe[k]."""
    phi = 2 * np.pi * np.arange(sides) / sides
    radial = np.cos(phi)[None, :, None] * e1[:, None, :] + np.sin(phi)[None, :, None] * e2[:, None, :]
    rings = r[:, None, :] + radius * radial                          # (n, sides, 3)
    nxt = np.roll(np.arange(sides), -1)
    quads = np.stack([rings[:-1], rings[:-1][:, nxt], rings[1:][:, nxt], rings[1:]], axis=2).reshape(-1, 4, 3)
    mid_radial = radial + radial[:, nxt, :]
    normals = unit_rows((mid_radial[:-1] + mid_radial[1:]).reshape(-1, 3))
    marked = np.zeros((len(r) - 1, sides), bool)
    if stripe is not None:
        ok = np.flatnonzero(np.isfinite(stripe[:-1]))
        sector = np.floor(np.mod(stripe[ok], 2 * np.pi) / (2 * np.pi / sides)).astype(int) % sides
        marked[ok, sector] = True
    polygons = [*quads, rings[0][::-1], rings[-1]]
    return (polygons, np.concatenate([normals, [-t[0], t[-1]]]),
            np.concatenate([marked.ravel(), [False, False]]))


def shade(normals, centres, rgb, view, light, depth_range, alpha):
    """RGBA of facets (rgb (m, 3) and alpha (m,) their own): ambient + Lambert + Blinn-Phong highlight,
    mixed towards white with depth (depth_range: the nearest and farthest depth along `view`)."""
    half = (light + view) / np.linalg.norm(light + view)
    diffuse = np.clip(normals @ light, 0.0, None)
    specular = np.clip(normals @ half, 0.0, None) ** 30
    intensity = 0.35 + 0.65 * diffuse
    colour = np.clip(rgb * intensity[:, None] + 0.35 * specular[:, None], 0.0, 1.0)
    near, far = depth_range
    depth = np.clip((near - centres @ view) / max(near - far, 1e-12), 0.0, 1.0)   # 0 nearest, 1 farthest
    colour = colour * (1 - FOG * depth[:, None]) + FOG * depth[:, None]
    return np.column_stack([colour, alpha])


def screen_axes(elev, azim):
    """(towards the viewer, screen right, screen up) as unit vectors in the global axes, for matplotlib's
    elevation and azimuth [deg]."""
    e, a = np.radians(elev), np.radians(azim)
    view = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    up = np.array([-np.sin(e) * np.cos(a), -np.sin(e) * np.sin(a), np.cos(e)])
    return view, right, up


def view_vectors(elev, azim):
    """(towards the viewer, towards the light): the light above and to the left of the viewer."""
    view, right, up = screen_axes(elev, azim)
    light = view + 0.6 * up - 0.5 * right
    return view, light / np.linalg.norm(light)


# ------------------------------------------------------------------------------------------------ drawing

@dataclass
class Piece:
    """A run of consecutive nodes of a beam to draw as one tube."""
    r: np.ndarray
    t: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    stripe: object          # angles of g1 about t in (e1, e2) [rad], or None
    rgb: np.ndarray
    alpha: float


def pieces_of(beam, keep, rgb, alpha):
    """The runs of consecutive nodes of `beam` with keep True (at least two nodes each), each with a
    parallel-transport frame started afresh and the angle of the director g1 in it."""
    runs, start = [], None
    for k, flag in enumerate(list(keep) + [False]):
        if flag and start is None:
            start = k
        elif not flag and start is not None:
            if k - start >= 2:
                part = Beam(beam.name, beam.s[start:k], beam.r[start:k],
                            None if beam.g1 is None else beam.g1[start:k],
                            None if beam.g2 is None else beam.g2[start:k])
                t = tangents(part.r)
                e1, e2 = transport_frame(t)
                runs.append(Piece(part.r, t, e1, e2, director_angle(part, t, e1, e2), rgb, alpha))
            start = None
    return runs


def set_equal_box(ax, points, pad):
    """Limits around the points (plus pad) and a box of the same proportions: equal scaling."""
    low, high = points.min(axis=0) - pad, points.max(axis=0) + pad
    span = high - low
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_zlim(low[2], high[2])
    ax.set_box_aspect(span)
    return low, high


def round_length_below(limit):
    """The largest 1, 2 or 5 times a power of ten not above limit (> 0)."""
    power = 10.0 ** np.floor(np.log10(limit))
    return power * max(m for m in (1, 2, 5) if m * power <= limit * (1 + 1e-12))


def draw_triad(fig, rect, px_per_mm, elev, azim):
    """The x, y, z directions as seen, a round length long (as long as fits in TRIAD_BAND, below the panel's
    rectangle `rect`, pixels), at the band's left, with that length written beside it."""
    _, right, up = screen_axes(elev, azim)
    directions = np.array([[axis @ right, axis @ up] for axis in np.eye(3)])    # on screen, per mm
    room = (TRIAD_BAND - 0.2) * fig.dpi                                       # pixels for the arrows
    length = round_length_below(room / (px_per_mm * max(np.max(np.abs(directions)), 1e-3)))
    size = fig.bbox.size
    origin = np.array([rect.x0 + 0.03 * rect.width + 0.5 * room,
                       rect.y0 - TRIAD_BAND * fig.dpi + 0.12 * fig.dpi + 0.5 * room])
    rightmost = origin[0]
    for direction, label, colour in zip(directions, "xyz", ("tab:red", "tab:green", "tab:blue")):
        tip = origin + length * px_per_mm * direction
        fig.add_artist(Line2D(*(np.column_stack([origin, tip]) / size[:, None]), color=colour, lw=1.5))
        label_at = origin + 1.25 * (tip - origin)
        fig.text(*(label_at / size), label, color=colour, fontsize=8, ha="center", va="center")
        rightmost = max(rightmost, label_at[0])
    fig.text((rightmost + 0.12 * fig.dpi) / size[0], origin[1] / size[1], f"axes {length:g} mm", fontsize=7,
             color="0.3", ha="left", va="center")


def draw_tubes(ax, pieces, radius, sides, view, light):
    """All pieces as one Poly3DCollection of the facets that face the viewer, shaded and depth-sorted; the
    facets on the director stripe darker."""
    polygons, normals, marked, rgb, alpha = [], [], [], [], []
    for p in pieces:
        polys, n, m = tube_facets(p.r, p.t, p.e1, p.e2, radius, sides, p.stripe)
        polygons += polys
        normals.append(n)
        marked.append(m)
        rgb.append(np.tile(p.rgb, (len(polys), 1)))
        alpha.append(np.full(len(polys), p.alpha))
    normals, marked, rgb, alpha = map(np.concatenate, (normals, marked, rgb, alpha))
    rgb[marked] *= STRIPE_SHADE
    centres = np.array([v.mean(axis=0) for v in polygons])
    depth = centres @ view
    facing = np.flatnonzero(normals @ view > -0.05)
    colours = shade(normals[facing], centres[facing], rgb[facing], view, light, (depth.max(), depth.min()),
                    alpha[facing])
    # Opaque facets get an edge of their own colour, which closes the hairline seams between them; on
    # translucent ones it would draw a grid.
    edges = np.where(colours[:, 3:] < 1.0, 0.0, colours)
    collection = Poly3DCollection([polygons[k] for k in facing], facecolors=colours, edgecolors=edges,
                                  linewidths=0.25)
    collection.set_zorder(1)
    collection.set_clip_on(False)
    ax.add_collection3d(collection)


def intermediate_lines(contact):
    """[polyline (k, 3)] of the midpoints of each zone's elements, in zeta order."""
    mid = 0.5 * (np.column_stack([contact[f"{c}_i"] for c in "xyz"])
                 + np.column_stack([contact[f"{c}_j"] for c in "xyz"]))
    return [mid[contact["zone"] == zone] for zone in np.unique(contact["zone"])], mid


def knot_rows(contact, names, separation=0.0):
    """Mask of the knot's contact elements: between two beams of `names` (the strands) that are one beam
    (a self-contact) or whose abscissas lie more than `separation` [mm] apart (two fibres of a yarn side by
    side are not the knot's contact)."""
    names = np.asarray(list(names), dtype=str)
    strands = np.isin(contact["beam_i"], names) & np.isin(contact["beam_j"], names)
    apart = np.abs(contact["abscissa_i"] - contact["abscissa_j"]) > separation
    return strands & ((contact["beam_i"] == contact["beam_j"]) | apart)


def knot_extent(strands, contact, separation=0.0):
    """(s_a, s_b) of the knot's contact elements (knot_rows) with R_N > 0, or None."""
    if contact is None:
        return None
    rows = knot_rows(contact, [b.name for b in strands], separation) & (contact["normal_force"] > 0)
    if not rows.any():
        return None
    s = np.concatenate([contact["abscissa_i"][rows], contact["abscissa_j"][rows]])
    return float(s.min()), float(s.max())


def draw_tube_panel(ax, pieces, shown, radius, sides, elev, azim):
    """Sets up a 3D panel (orthographic, seen from `elev`, `azim`, no axes, an equal box around the points
    `shown` padded by 1.5 radius) and draws the tube `pieces` in it."""
    view, light = view_vectors(elev, azim)
    ax.view_init(elev=elev, azim=azim)
    ax.set_proj_type("ortho")
    ax.set_axis_off()
    ax.computed_zorder = False
    set_equal_box(ax, shown, radius * 1.5)
    draw_tubes(ax, pieces, radius, sides, view, light)


def draw_ends(ax, beam, knot=None):
    """End A (triangle) and end B (square) of `beam`, those within `knot` (s range) if given."""
    if knot is None or (beam.s[0] >= knot[0]):
        ax.plot(*beam.r[0][:, None], marker="^", color="k", ms=5, zorder=5, clip_on=False)   # end A
    if knot is None or (beam.s[-1] <= knot[1]):
        ax.plot(*beam.r[-1][:, None], marker="s", color="k", ms=5, zorder=5, clip_on=False)  # end B


def whole_pieces(beams, strands):
    """(tube pieces, points to frame) of every beam whole: the strands in their colours, the others grey."""
    names = [b.name for b in strands]
    pieces = []
    for beam in beams:
        rgb = strand_colour(names.index(beam.name), len(names))[1] if beam.name in names else TOOL_RGB
        pieces += pieces_of(beam, np.ones(len(beam.s), bool), rgb, 1.0)
    return pieces, np.concatenate([b.r for b in beams])


def draw_panel(ax, beams, strands, contact, radius, sides, elev, azim, knot=None, separation=0.0):
    """One 3D panel: every beam (knot None; the strands in their colours, the others grey) or the strands'
    nodes with s in `knot` (s_a - m, s_b + m), with the intermediate geometry and (knot panel: of the
    knot's contact elements, knot_rows) the reaction bars. Returns (the ScalarMappable of the reaction
    colours or None, the points to frame)."""
    names = [b.name for b in strands]
    if knot is None:
        pieces, shown = whole_pieces(beams, strands)
    else:
        pieces, shown = [], []
        for k, strand in enumerate(strands):
            keep = (strand.s >= knot[0]) & (strand.s <= knot[1])
            pieces += pieces_of(strand, keep, strand_colour(k, len(strands))[1], KNOT_ALPHA)
            shown.append(strand.r[keep])
        shown = np.concatenate(shown)
    draw_tube_panel(ax, pieces, shown, radius, sides, elev, azim)
    for strand in strands:
        draw_ends(ax, strand, knot)
    mappable = None
    if contact is not None and len(contact["zone"]):
        rows = np.ones(len(contact["zone"]), bool)
        if knot is not None:
            rows = knot_rows(contact, names, separation)
        part = {k: v[rows] for k, v in contact.items()}
        lines, mid = intermediate_lines(part)
        for line in lines:
            ax.plot(*line.T, color=LINE_RGB, lw=2.0 if knot is not None else 1.0, zorder=6,
                    clip_on=False)
        if knot is not None:
            force = part["normal_force"]
            pressing = force > 0
            if pressing.any():
                normal = np.column_stack([part[f"n{c}"] for c in "xyz"])
                half = 0.5 * BAR_LENGTH * radius * (force / force.max())[:, None] * normal
                segments = np.stack([mid - half, mid + half], axis=1)[pressing]
                norm = colors.Normalize(0.0, force.max())
                cmap = plt.get_cmap(REACTION_CMAP)
                bars = Line3DCollection(segments, colors=cmap(norm(force[pressing])), linewidths=2.2)
                bars.set_zorder(7)
                bars.set_clip_on(False)
                ax.add_collection3d(bars)
                mappable = cm.ScalarMappable(norm=norm, cmap=cmap)
    return mappable, shown


def projected_box(ax, points):
    """(lower-left corner, size) in pixels of the projection of `points` in a drawn 3D panel."""
    x, y, _ = proj3d.proj_transform(*points.T, ax.get_proj())
    corners = ax.transData.transform(np.column_stack([x, y]))
    low = corners.min(axis=0)
    return low, np.maximum(corners.max(axis=0) - low, 1e-9)


def frame_panel(ax, points, elev, azim):
    """Zooms (from 1) and pans a drawn 3D panel so that the projection of `points` is centred in the panel's
    rectangle and fills FILL of its width or height. A 3D panel draws in the largest square inside its
    rectangle, centred, but does not clip to it (clip_on False): the rectangle is what counts. Returns
    (the rectangle in pixels, the scale in pixels per mm after the zoom)."""
    rect = ax.get_position(original=True).transformed(ax.figure.transFigure)
    low, size = projected_box(ax, points)
    offset = low + size / 2 - np.array([rect.x0 + rect.width / 2, rect.y0 + rect.height / 2])   # pixels
    _, right, up = screen_axes(elev, azim)
    centre = np.mean(points, axis=0)
    _, unit = projected_box(ax, np.array([centre, centre + right]))
    shift = (offset[0] * right + offset[1] * up) / unit[0]   # mm; moving the limits moves the view back
    ax.set_xlim(*(np.array(ax.get_xlim()) + shift[0]))
    ax.set_ylim(*(np.array(ax.get_ylim()) + shift[1]))
    ax.set_zlim(*(np.array(ax.get_zlim()) + shift[2]))
    zoom = FILL / max(size[0] / rect.width, size[1] / rect.height)
    ax.set_box_aspect(ax._box_aspect, zoom=zoom)      # from 1: the scale in pixels per mm grows by zoom
    return rect, unit[0] * zoom


def strands_title(beams, strands):
    """Title of the whole panel: `whole rod`, or the strands with their colours."""
    if len(strands) == 1:
        return "whole rod" + (", other beams grey" if len(beams) > 1 else "")
    names = ", ".join(f"{b.name} ({strand_colour(k, len(strands))[0]})" for k, b in enumerate(strands))
    return names + (", other beams grey" if len(beams) > len(strands) else "")


def render_state(state, out_path, radius=None, sides=DEFAULT_SIDES, elev=DEFAULT_ELEV, azim=DEFAULT_AZIM,
                 dpi=DPI, strands=None, separation=0.0):
    """Draws one state into out_path (PNG): the whole rod, and the knot when the rod touches itself.
    The panels' heights follow the proportions of what they show on screen, and each is zoomed so that it
    fills 90 % of its panel's width or height (matplotlib leaves room for the whole 3D box, corners
    included, which wastes most of a flat one), centred. `strands` (names, e.g. the fibres of a yarn) and
    `separation` [mm]: the knotted strand is those beams (strands_of), the knot's contact elements knot_rows."""
    beams = read_beams(state.nodes)
    contact = read_contact(state.contact)
    strands = strands_of(beams, strands)
    if radius is None:
        radius = measured_radius(beams, contact) or DEFAULT_RADIUS
    extent = knot_extent(strands, contact, separation)
    width = 8.0 if extent is None else 13.0
    # Panels as (left, width) in figure fractions; the colour bar to the right of the knot panel.
    columns = [(0.0, 1.0)] if extent is None else [(0.0, 0.36), (0.37, 0.55)]
    fig = plt.figure(figsize=(width, 6.0))
    fig.suptitle(state.title)
    axes = [fig.add_axes([left, 0.0, w, 0.8], projection="3d") for left, w in columns]
    shown = [draw_panel(axes[0], beams, strands, contact, radius, sides, elev, azim)[1]]
    titles = [strands_title(beams, strands)]
    bar = None
    if extent is not None:
        knot = (extent[0] - KNOT_MARGIN, extent[1] + KNOT_MARGIN)
        mappable, points = draw_panel(axes[1], beams, strands, contact, radius, sides, elev, azim, knot,
                                      separation)
        shown.append(points)
        what = ("intermediate geometry" if len(strands) == 1 else
                f"intermediate geometries of the contacts\nbetween parts of the knot (|s_i - s_j| > "
                f"{separation:g} mm or one fibre)")
        titles.append(f"the knot, s from {knot[0]:.2f} to {knot[1]:.2f} mm: {what} (dark "
                      f"red), normal reactions\nas bars along the contact normal (length and colour: R_N; "
                      f"longest {BAR_LENGTH:g} R)")
        if mappable is not None:
            bar = fig.add_axes([0.935, 0.2, 0.012, 0.5])
            fig.colorbar(mappable, cax=bar, label="normal reaction R_N (N)")
    fig.canvas.draw()
    ratios = [size[1] / size[0] for _, size in (projected_box(ax, p) for ax, p in zip(axes, shown))]
    title_band = 0.75 if extent is not None else 0.55       # inches: figure title and panel titles
    panel = float(np.clip(max(r * w * width for r, (_, w) in zip(ratios, columns)) / FILL, 2.5, 7.0))
    height = panel + title_band + TRIAD_BAND
    bottom = TRIAD_BAND / height
    fig.set_size_inches(width, height)
    for ax, (left, w), title in zip(axes, columns, titles):
        ax.set_position([left, bottom, w, panel / height])
        fig.text(left + w / 2, bottom + panel / height, title, fontsize=9, ha="center", va="bottom")
    if bar is not None:
        bar.set_position([0.935, bottom + 0.15 * panel / height, 0.012, 0.7 * panel / height])
    fig.suptitle(state.title, y=1.0 - 0.08 / height, va="top")
    fig.canvas.draw()
    for ax, points in zip(axes, shown):
        rect, px_per_mm = frame_panel(ax, points, elev, azim)
        draw_triad(fig, rect, px_per_mm, elev, azim)
    temporary = out_path.with_name(f".{out_path.name}.tmp")
    try:
        fig.savefig(temporary, format="png", dpi=dpi)
        os.replace(temporary, out_path)
    finally:
        plt.close(fig)
        if temporary.exists():
            temporary.unlink()
    return out_path


def render_run(run_dir, out_dir=None, **options):
    """Draws every state of a run folder (run_states) into out_dir (default RUN_DIR/report); returns the
    paths written. A state whose tables cannot be read is skipped with a note on stdout."""
    run_dir = Path(run_dir)
    out_dir = Path(out_dir) if out_dir is not None else run_dir / "report"
    states = run_states(run_dir)
    if not states:
        raise ViewError(f"{run_dir}: no stage-end table, final_nodes.csv or branch to draw")
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for state in states:
        try:
            written.append(render_state(state, out_dir / f"view3d_{state.key}.png", **options))
        except ViewError as e:
            print(f"note: {state.key} not drawn: {e}")
    return written


def main(argv):
    parser = argparse.ArgumentParser(description="3D views of a knot run's stage ends and released knots.")
    parser.add_argument("run_dir", type=Path, help="the run's output folder")
    parser.add_argument("--out", type=Path, help="where the PNG files go (default RUN_DIR/report)")
    parser.add_argument("--elev", type=float, default=DEFAULT_ELEV, help="elevation of the view [deg]")
    parser.add_argument("--azim", type=float, default=DEFAULT_AZIM, help="azimuth of the view [deg]")
    parser.add_argument("--sides", type=int, default=DEFAULT_SIDES, help="facets around the tube (>= 3)")
    parser.add_argument("--radius", type=float, help="tube radius [mm] (default: measured, else 0.1)")
    parser.add_argument("--dpi", type=float, default=DPI, help=f"resolution of the PNG files (default {DPI})")
    args = parser.parse_args(argv[1:])
    if args.sides < 3 or (args.radius is not None and not args.radius > 0) or not args.dpi > 0:
        parser.error("--sides must be at least 3, --radius and --dpi positive")
    try:
        written = render_run(args.run_dir, args.out, radius=args.radius, sides=args.sides, elev=args.elev,
                             azim=args.azim, dpi=args.dpi)
    except ViewError as e:
        print(f"knot_views: {e}", file=sys.stderr)
        return 2
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
