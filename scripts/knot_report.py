#!/usr/bin/env python3
"""Report on an overhand-knot run of nodus (Durville 2012, Sect. 7.2, Figs. 12, 14, 15, 17). Units: mm, N.

Usage: scripts/knot_report.py DIR       (requires python3-numpy and python3-matplotlib, Debian, and the nodus
                                        module: PYTHONPATH=build/release/python, or found there)

The numbers come from nodus's Python module (nodus.knot_metrics, C++ in src/nodus/analysis/knot_metrics.hpp);
this script reads the run's files, writes the tables and draws the figures.

Inputs (DIR is a run's output folder):
  DIR/final_nodes.csv, DIR/contact_final.csv       the tightened state (required)
  DIR/steps.csv                                     last row: pull force |pull_b_f|, stabilization_force
  DIR/summary.json                                  optional: `branches` (names, folders, friction)
  DIR/branches/NAME/{final_nodes,contact_final,steps}.csv   each release branch (friction from
                                                    summary.json, else parsed from NAME, e.g. mu_0.30)
  DIR/stages/NNN_STAGE_nodes.csv                    stage-end states, for Fig. 12 (skipped if absent)

Definitions, for each state (the tightened one = the main run's final state, then each branch's final):
  knot            the knot type of the rod's centreline closed far away (nodus.knot_invariant, the
                  Alexander polynomial): trefoil, or unknot for a released knot that came undone
                  (unknown where every projection has a near-crossing).
  in contact      elements with normal_force > 0; s_a, s_b the smallest and largest rod arc length s among
                  their abscissa_i, abscissa_j: the knot occupies [s_a, s_b].
  abscissa        along the intermediate geometry: within a zone (elements in zeta order) the length of the
                  polyline of midpoints (x_i + x_j) / 2 from the zone's first element; zones in number order,
                  each starting where the previous one ends.
  intermediate length   sum over zones of the abscissa span from the first to the last element in contact.
  tail angle      angle between the unit chords c(s_a) -> c(s_a - 2) and c(s_b) -> c(s_b + 2) of the
                  centreline c (linear between nodes, clamped to the rod ends); 180 deg: tails pulled apart.
  loop            the longest sub-interval of [s_a, s_b] farther than h from every abscissa_i, abscissa_j of
                  an element in contact, h = half the median spacing of successive abscissa_i in a zone
                  (spacing at least 0.05 mm); loop_length_mm its length in s, loop_radius_mm the radius of
                  the circle fitted to its nodes (plane by SVD, then Kasa fit; nan below 5 nodes).
  max penetration max(-gap) over all elements.

Outputs, in DIR/report/ (each written to a temporary name, then renamed):
  knot_report.csv                      one row per state: the numbers above (also printed as a table)
  fold_check.csv                       the fold check of the main run and of each branch at every stage end
                                       (steps.csv: min_orientation, the smallest det[g1, g2, r'] over every
                                       Gauss point and element centre, and min_chord, the smallest element
                                       chord over h), with a last row per run over all its steps; an element
                                       is folded where det <= 0 (printed as a summary line)
  reactions_tightened.csv, reactions_NAME.csv   per element: zone, zeta, abscissa, s_i, s_j, midpoint,
                                       normal and tangential reaction, state
  fig14_tightened_reactions.png        reactions along the intermediate geometry, tightened state
  fig17_released_reactions.png         the same, one panel per branch (highest friction first)
  fig12_stages.png                     the rod seen from +z at the end of each stage (and the final state
                                       if it differs from the last stage end), coloured by z, with the
                                       other beams in contact with it (the clamping beams) in grey
  fig15_released_knots.png             each branch's knot seen from +z, nodes with s in [s_a-3, s_b+3]
  view3d_*.png                         3D views of every stage end and of each branch's released knot:
                                       tubes, intermediate geometry, normal reactions (Figs. 12, 13, 15,
                                       16), drawn by scripts/knot_views.py (see there)
"""

import csv
import json
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import matplotlib

try:
    import nodus  # the knot metrics are nodus's own (src/nodus/analysis/knot_metrics.hpp)
except ImportError:  # from the source tree: the module built in build/release
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "release", "python"))
    import nodus

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib import cm, colors  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # leaves no scripts/__pycache__ in the source tree
import knot_views  # noqa: E402  (the 3D views, scripts/knot_views.py)

NODE_COLUMNS = ["s", "x", "y", "z"]  # numeric; also `beam`
CONTACT_COLUMNS = ["zone", "zeta", "abscissa_i", "abscissa_j", "x_i", "y_i", "z_i", "x_j", "y_j", "z_j",
                   "gap", "normal_force", "tangential_force"]  # numeric; also `state`
TAIL_CHORD = 2.0          # mm, length along each tail of the chord giving its direction
MIN_SPACING = 0.05        # mm, least element spacing for the contact coverage of the loop
MIN_LOOP_NODES = 5        # nodes needed for the circle fit
ZOOM_MARGIN = 3.0         # mm of rod either side of the knot shown in Fig. 15
DEFAULT_RADIUS = 0.1      # mm, rod radius of Sect. 7.2 when it cannot be measured from the contact table
FIGURE_WIDTH = 11.0       # inches, of the rod figures
ROW_TITLE, ROW_LABEL = 0.35, 0.6   # inches above (panel title) and below (x label) each row of panels
REPORT_COLUMNS = ["state", "friction", "knot", "tightening_force_N", "stabilization_force_N", "zones",
                  "contact_elements", "elements_in_contact", "intermediate_length_mm", "max_normal_N",
                  "total_normal_N", "max_tangential_N", "total_tangential_N", "tail_angle_deg",
                  "loop_radius_mm", "loop_length_mm", "max_penetration_mm"]
REACTION_COLUMNS = ["zone", "zeta", "abscissa_mm", "s_i", "s_j", "x", "y", "z", "normal_N", "tangential_N",
                    "state"]
CMAP = colors.LinearSegmentedColormap.from_list("knot", cm.viridis(np.linspace(0.0, 0.85, 256)))


class ReportError(Exception):
    """A missing or unreadable input; reported as one line `knot_report: PATH: what`."""


@dataclass
class State:
    """One knot state read from a run folder: the tightened state or a branch's final state."""
    name: str                # `tightened` or the branch name
    friction: object         # float, or None when unknown
    nodes: dict              # column -> array, the rod's nodes sorted by s
    contact: dict            # column -> array, elements sorted by (zone, zeta)
    last_step: dict          # column -> value of the last row of steps.csv ({} if there is none)

    @property
    def label(self):
        if self.name == "tightened":
            return "tightened"
        return f"mu = {self.friction:g}" if self.friction is not None else self.name


def read_table(path, numeric, text):
    """A CSV file as {column: array}, numeric columns as float arrays; checks that it has the columns
    `numeric` (with numbers) and `text` (knot_views.read_table, with this script's error)."""
    try:
        table = knot_views.read_table(path, [*numeric])
    except knot_views.ViewError as e:
        raise ReportError(str(e)) from None
    absent = [c for c in text if c not in table]
    if absent:
        raise ReportError(f"{path}: missing column(s) {', '.join(absent)}")
    return table


def select(table, mask_or_order):
    """The rows of a table picked by a boolean mask or an index array."""
    return {k: v[mask_or_order] for k, v in table.items()}


def read_nodes(path):
    """The nodes of the rod (the beam named `rod`, else the first beam), sorted by s."""
    nodes = read_table(path, NODE_COLUMNS, ["beam"])
    beams = list(dict.fromkeys(nodes["beam"]))
    if beams:
        nodes = select(nodes, nodes["beam"] == ("rod" if "rod" in beams else beams[0]))
    if len(nodes["s"]) < 2:
        raise ReportError(f"{path}: fewer than two nodes")
    return select(nodes, np.argsort(nodes["s"], kind="stable"))


def tools_in_contact(nodes_path):
    """The other beams with contact elements on the rod at the state of `nodes_path` (a stage-end table),
    from its `_contact.csv` companion: [nodes of each, sorted by s]. Empty when there is no companion."""
    contact_path = nodes_path.with_name(nodes_path.name.replace("_nodes.csv", "_contact.csv"))
    if not contact_path.is_file():
        return []
    pairs = read_table(contact_path, [], ["beam_i", "beam_j"])
    names = {b for i, j in zip(pairs["beam_i"], pairs["beam_j"]) if "rod" in (i, j) for b in (i, j)} - {"rod"}
    nodes = read_table(nodes_path, NODE_COLUMNS, ["beam"])
    tools = []
    for name in sorted(names):
        beam = select(nodes, nodes["beam"] == name)
        if len(beam["s"]) >= 2:
            tools.append(select(beam, np.argsort(beam["s"], kind="stable")))
    return tools


def read_contact(path):
    """The contact elements sorted by (zone, zeta)."""
    contact = read_table(path, CONTACT_COLUMNS, ["state"])
    return select(contact, np.lexsort((contact["zeta"], contact["zone"])))


def read_last_step(path):
    """The numeric values of the last row of steps.csv as {column: value}; {} with a note if it has none."""
    if not path.is_file():
        print(f"note: {path} missing: no pull or stabilisation force")
        return {}
    with open(path, newline="") as f:
        last = None
        for last in csv.DictReader(f):
            pass
    values = {}
    for column, text in (last or {}).items():
        try:
            values[column] = float(text)
        except (TypeError, ValueError):
            pass
    return values


def load_state(folder, name, friction):
    return State(name, friction, read_nodes(folder / "final_nodes.csv"),
                 read_contact(folder / "contact_final.csv"), read_last_step(folder / "steps.csv"))


def friction_from_name(name):
    match = re.search(r"\d+(?:\.\d*)?|\.\d+", name)
    return float(match.group()) if match else None


def find_branches(run_dir, summary):
    """[(name, folder, friction)] of the branches, highest friction first (else in the order found)."""
    found = []
    listed = summary.get("branches")
    if isinstance(listed, list) and listed:
        for entry in listed:
            entry = entry if isinstance(entry, dict) else {"name": str(entry)}
            name = entry.get("name", "")
            friction = entry.get("friction")
            friction = float(friction) if isinstance(friction, (int, float)) else friction_from_name(name)
            found.append((name, run_dir / entry.get("folder", f"branches/{name}"), friction))
    elif (run_dir / "branches").is_dir():
        for folder in sorted(p for p in (run_dir / "branches").iterdir() if p.is_dir()):
            found.append((folder.name, folder, friction_from_name(folder.name)))
    return sorted(found, key=lambda b: -b[2] if b[2] is not None else np.inf)


def read_summary(run_dir):
    path = run_dir / "summary.json"
    if not path.is_file():
        return {}
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        print(f"note: {path} unreadable ({e}); ignored")
        return {}
    return data if isinstance(data, dict) else {}


def main_friction(summary):
    """The main run's friction coefficient if summary.json gives it (`friction` or `contact.friction`)."""
    contact = summary.get("contact")
    value = summary.get("friction", contact.get("friction") if isinstance(contact, dict) else None)
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def nodes_polyline(nodes):
    """(points (n, 3), arc_length (n,)) of a nodal table sorted by s."""
    return np.column_stack([nodes[c] for c in ("x", "y", "z")]), nodes["s"]


def rod_radius(states):
    """The rod radius: median distance of the contact particles x_i from the centreline at abscissa_i."""
    return nodus.rod_radius([(nodes_polyline(state.nodes), state.contact) for state in states], DEFAULT_RADIUS)


def pull_force(last_step):
    components = [last_step.get(f"pull_b_f{c}") for c in "xyz"]
    return float(np.linalg.norm(components)) if None not in components else np.nan


def knot_type(points):
    """The knot type of the polyline `points` (n, 3) closed far away (nodus.knot_invariant): trefoil, unknot,
    else the Alexander polynomial; unknown where every projection has a near-crossing."""
    try:
        invariant = nodus.knot_invariant(points)
        return ("trefoil" if invariant["trefoil"] else "unknot" if invariant["unknot"]
                else invariant["polynomial"])
    except RuntimeError:  # no projection without a near-crossing: a curve that touches itself
        return "unknown"


def reactions_of(m, contact):
    """The reactions table (REACTION_COLUMNS, as a dict of columns) of nodus.knot_metrics's result `m` for the
    contact table `contact`."""
    r = m["reactions"]
    mid = r["midpoint"]
    return {"zone": r["zone"], "zeta": r["zeta"], "abscissa_mm": r["abscissa"], "s_i": r["s_i"],
            "s_j": r["s_j"], "x": mid[:, 0], "y": mid[:, 1], "z": mid[:, 2], "normal_N": r["normal"],
            "tangential_N": r["tangential"], "state": contact["state"][np.asarray(r["element"], int)]}


def analyse(state):
    """(row of knot_report.csv as a dict, reactions table as a dict of columns, (s_a, s_b)): the knot metrics
    of nodus (nodus.knot_metrics, src/nodus/analysis/knot_metrics.hpp) with the definitions above."""
    contact = state.contact
    m = nodus.knot_metrics(nodes_polyline(state.nodes), contact, tail_chord=TAIL_CHORD, min_spacing=MIN_SPACING,
                           min_loop_nodes=MIN_LOOP_NODES)
    knot = knot_type(nodes_polyline(state.nodes)[0])
    row = {
        "state": state.name,
        "friction": state.friction,
        # A released knot may come undone: the centreline closed far away is then the unknot.
        "knot": knot,
        "tightening_force_N": pull_force(state.last_step),
        "stabilization_force_N": state.last_step.get("stabilization_force", np.nan),
        "zones": m["zones"],
        "contact_elements": m["contact_elements"],
        "elements_in_contact": m["elements_in_contact"],
        "intermediate_length_mm": m["intermediate_length"],
        "max_normal_N": m["max_normal"],
        "total_normal_N": m["total_normal"],
        "max_tangential_N": m["max_tangential"],
        "total_tangential_N": m["total_tangential"],
        "tail_angle_deg": m["tail_angle"],
        "loop_radius_mm": m["loop_radius"],
        "loop_length_mm": m["loop_length"],
        "max_penetration_mm": m["max_penetration"],
    }
    return row, reactions_of(m, contact), (m["s_a"], m["s_b"])


def format_value(value):
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        return "nan" if np.isnan(value) else f"{value:.6g}"
    return str(value)


def write_atomically(path, write):
    """Calls write(temporary path), then renames the result to path."""
    temporary = path.with_name(f".{path.name}.tmp")
    try:
        write(temporary)
        os.replace(temporary, path)
    finally:
        if temporary.exists():
            temporary.unlink()
    return path


def write_csv(path, columns, rows):
    def write(temporary):
        with open(temporary, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(columns)
            out.writerows([format_value(row[c]) for c in columns] for row in rows)
    return write_atomically(path, write)


def save_figure(fig, path):
    written = write_atomically(path, lambda temporary: fig.savefig(temporary, format="png", dpi=150))
    plt.close(fig)
    return written


def table_cell(value):
    """A value as printed in the markdown table: finite floats to 4 significant digits."""
    return format_value(float(f"{value:.4g}") if isinstance(value, float) and np.isfinite(value) else value)


def markdown_table(rows, columns=REPORT_COLUMNS):
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for row in rows:
        lines.append("| " + " | ".join(table_cell(row[c]) for c in columns) + " |")
    return "\n".join(lines)


def plot_reactions(ax, reactions, title):
    """Normal and tangential reactions against the abscissa along the intermediate geometry (Fig. 14)."""
    ax.set_title(title)
    if not len(reactions["zone"]):
        ax.text(0.5, 0.5, "no contact element", transform=ax.transAxes, ha="center", va="center")
        return
    for k, zone in enumerate(np.unique(reactions["zone"])):
        index = reactions["zone"] == zone
        x = reactions["abscissa_mm"][index]
        ax.plot(x, reactions["normal_N"][index], "o-", color="tab:blue", ms=4,
                label="Norm. react." if k == 0 else None)
        ax.plot(x, reactions["tangential_N"][index], "s--", color="tab:red", ms=4,
                label="Tang. react." if k == 0 else None)
        if k > 0:
            ax.axvline(x[0], color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("curvilinear abscissa along the intermediate geometry (mm)")
    ax.set_ylabel("reaction (N)")
    ax.grid(alpha=0.3)
    ax.legend()


def points_per_mm(ax):
    ax.apply_aspect()
    (x0, _), (x1, _) = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])
    return abs(x1 - x0) * 72.0 / ax.figure.dpi


def node_pieces(xy):
    """The centreline cut at the midpoints between nodes: piece j runs from the midpoint before node j
    through node j to the midpoint after it (from / to the rod ends), its colour ends pushed 5 % further
    along the rod so that neighbouring pieces overlap without seams."""
    mids = (xy[:-1] + xy[1:]) / 2
    pieces = []
    for j in range(len(xy)):
        start = mids[j - 1] if j > 0 else xy[0]
        end = mids[j] if j < len(mids) else xy[-1]
        outline = np.array([start, xy[j], end])
        colour = outline.copy()
        colour[0] += 0.05 * (start - xy[j])
        colour[2] += 0.05 * (end - xy[j])
        pieces.append((outline, colour))
    return pieces


def draw_rod(ax, nodes, norm, radius, limits, tools=()):
    """The rod seen from +z: pieces around each node, drawn from the lowest z to the highest with a white
    rim and a dark edge, so that upper strands hide lower ones; width the rod diameter at the plot scale.
    `tools` (other beams, e.g. the clamping beams) are drawn in translucent grey, under the rod when their
    mean z is below the rod's nodes within their reach, over it otherwise."""
    (x0, x1), (y0, y1) = limits
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    width = max(2 * radius * points_per_mm(ax), 1.5)
    xy = np.column_stack([nodes["x"], nodes["y"]])
    style = {"solid_capstyle": "butt", "solid_joinstyle": "round"}
    pieces = node_pieces(xy)

    def draw_tool(tool):
        ax.plot(tool["x"], tool["y"], color="0.35", alpha=0.55, lw=width, solid_capstyle="butt", zorder=3)

    above = []
    for tool in tools:
        # The rod's nodes under the tool (within a diameter of it, seen from +z) decide whether it is above.
        near = np.min(np.hypot(nodes["x"][:, None] - tool["x"][None, :],
                               nodes["y"][:, None] - tool["y"][None, :]), axis=1) < 2 * radius
        reference = np.median(nodes["z"][near]) if near.any() else np.median(nodes["z"])
        if np.mean(tool["z"]) > reference:
            above.append(tool)
        else:
            draw_tool(tool)
    for j in np.argsort(nodes["z"], kind="stable"):
        outline, colour = pieces[j]
        ax.plot(*outline.T, color="white", lw=width + 3, **style)
        ax.plot(*outline.T, color="0.15", lw=width + 1, **style)
        ax.plot(*colour.T, color=CMAP(norm(nodes["z"][j])), lw=width, **style)
    for tool in above:
        draw_tool(tool)
    ax.plot(*xy[0], "k^", ms=5, zorder=5)  # end A
    ax.plot(*xy[-1], "ks", ms=5, zorder=5)  # end B
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")


def view_limits(nodes, mask, margin):
    x, y = nodes["x"][mask], nodes["y"][mask]
    return (x.min() - margin, x.max() + margin), (y.min() - margin, y.max() + margin)


def rod_figure(panels, radius, path, title):
    """One panel per (title, nodes, mask of the nodes to frame[, other beams to draw]), each with its own
    colour scale of z.
    Panels in rows (one column when they are mostly wide and flat), each row as high as its flattest
    panel allows at equal aspect."""
    limits = [view_limits(nodes, mask, 4 * radius) for _, nodes, mask, *_ in panels]
    aspects = [(y1 - y0) / (x1 - x0) for (x0, x1), (y0, y1) in limits]
    n = len(panels)
    columns = 1 if np.median(aspects) < 0.4 else min(n, 3)
    cell = FIGURE_WIDTH / columns
    plot_width = cell - 1.7  # inches left for the y label and the colour bar
    row_starts = range(0, n, columns)
    heights = [float(np.clip(plot_width * max(aspects[k:k + columns]), 1.0, 5.0)) for k in row_starts]
    total = 0.5 + sum(h + ROW_TITLE + ROW_LABEL for h in heights)
    fig = plt.figure(figsize=(FIGURE_WIDTH, total))
    fig.suptitle(title, y=1 - 0.12 / total)
    top = total - 0.5
    for start, height in zip(row_starts, heights):
        bottom = top - ROW_TITLE - height
        for k in range(start, min(start + columns, n)):
            panel_title, nodes, mask, *tools = panels[k]
            left = (k - start) * cell + 0.75
            ax = fig.add_axes([left / FIGURE_WIDTH, bottom / total, plot_width / FIGURE_WIDTH,
                               height / total])
            ax.set_anchor("W")
            z = nodes["z"][mask]
            norm = colors.Normalize(z.min(), max(z.max(), z.min() + 1e-6))
            draw_rod(ax, nodes, norm, radius, limits[k], tools[0] if tools else ())
            ax.set_title(panel_title)
            box = ax.get_position()
            bar = fig.add_axes([box.x1 + 0.12 / FIGURE_WIDTH, box.y0, 0.12 / FIGURE_WIDTH, box.height])
            fig.colorbar(cm.ScalarMappable(norm=norm, cmap=CMAP), cax=bar, label="z (mm)")
        top = bottom - ROW_LABEL
    return save_figure(fig, path)


def stage_panels(run_dir, final_nodes):
    """Fig. 12 panels: the stage-end states in order, then the final state if it is not the last of them."""
    pattern = re.compile(r"^(\d{3,})_(.+)_nodes\.csv$")
    files = sorted((int(m.group(1)), m.group(2), p) for p in (run_dir / "stages").iterdir()
                   if (m := pattern.match(p.name)))
    panels = []
    for index, stage, path in files:
        try:
            nodes = read_nodes(path)
        except ReportError as e:
            print(f"note: stage {stage} left out of fig12: {e}")
            continue
        panels.append((f"{index}: {stage}", nodes, np.ones(len(nodes["s"]), bool), tools_in_contact(path)))
    last = panels[-1][1] if panels else None
    same = last is not None and len(last["s"]) == len(final_nodes["s"]) and all(
        np.allclose(last[c], final_nodes[c], rtol=0, atol=1e-9) for c in ("x", "y", "z"))
    if not same:
        panels.append(("final state (tightened)", final_nodes, np.ones(len(final_nodes["s"]), bool)))
    return panels


def knot_mask(nodes, extent):
    s_a, s_b = extent
    if np.isnan(s_a):
        return np.ones(len(nodes["s"]), bool)
    return (nodes["s"] >= s_a - ZOOM_MARGIN) & (nodes["s"] <= s_b + ZOOM_MARGIN)


FOLD_COLUMNS = ["run", "stage", "step", "min_orientation", "min_chord"]


def fold_check(runs):
    """Rows of fold_check.csv for runs [(name, folder)]: each stage end of each run's steps.csv, then the run's
    smallest values over all its steps (stage "all steps"); [] with a note where steps.csv lacks the columns."""
    rows = []
    for name, folder in runs:
        path = folder / "steps.csv"
        if not path.is_file():
            continue
        with open(path, newline="") as f:
            steps = list(csv.DictReader(f))
        if not steps or "min_orientation" not in steps[0]:
            print(f"note: {path}: no fold check (min_orientation, min_chord) in this run's steps.csv")
            continue
        values = [(int(r["step"]), r["stage"], float(r["min_orientation"]), float(r["min_chord"])) for r in steps]
        for k, (step, stage, orientation, chord) in enumerate(values):
            if k + 1 == len(values) or values[k + 1][1] != stage:
                rows.append({"run": name, "stage": stage, "step": step, "min_orientation": orientation,
                             "min_chord": chord})
        rows.append({"run": name, "stage": "all steps", "step": values[-1][0],
                     "min_orientation": min(v[2] for v in values), "min_chord": min(v[3] for v in values)})
    return rows


def report(run_dir):
    for required in ("final_nodes.csv", "contact_final.csv"):
        if not (run_dir / required).is_file():
            raise ReportError(f"{run_dir / required}: missing")
    summary = read_summary(run_dir)
    states = [load_state(run_dir, "tightened", main_friction(summary))]
    for name, folder, friction in find_branches(run_dir, summary):
        try:
            states.append(load_state(folder, name, friction))
        except ReportError as e:
            print(f"note: branch {name} skipped: {e}")
    out_dir = run_dir / "report"
    out_dir.mkdir(exist_ok=True)
    radius = rod_radius(states)
    rows, written, branch_reactions, branch_panels = [], [], [], []
    for state in states:
        row, reactions, extent = analyse(state)
        rows.append(row)
        n = len(reactions["zone"])
        written.append(write_csv(out_dir / f"reactions_{state.name}.csv", REACTION_COLUMNS,
                                 [{c: reactions[c][k] for c in REACTION_COLUMNS} for k in range(n)]))
        if state.name == "tightened":
            fig, ax = plt.subplots(figsize=(7.5, 4.5))
            force = row["tightening_force_N"]
            plot_reactions(ax, reactions, "Tightened knot: reactions, tightening force "
                           + (f"{force:.3g} N" if np.isfinite(force) else "unknown"))
            written.append(save_figure(fig, out_dir / "fig14_tightened_reactions.png"))
        else:
            branch_reactions.append((state.label, reactions))
            branch_panels.append((state.label, state.nodes, knot_mask(state.nodes, extent)))
    written.insert(0, write_csv(out_dir / "knot_report.csv", REPORT_COLUMNS, rows))
    folds = fold_check([("main", run_dir)] + [(name, folder) for name, folder, _ in find_branches(run_dir, summary)])
    if folds:
        written.insert(1, write_csv(out_dir / "fold_check.csv", FOLD_COLUMNS, folds))
        worst = min(folds, key=lambda r: r["min_orientation"])
        folded = [r for r in folds if r["min_orientation"] <= 0.0]
        print(f"fold check: smallest det[g1, g2, r'] {worst['min_orientation']:.6g} ({worst['run']}, "
              f"{worst['stage']}), smallest chord / h {min(r['min_chord'] for r in folds):.6g}: "
              + (f"FOLDED ELEMENTS in {len(folded)} rows of fold_check.csv" if folded else "no element folded"))

    if branch_reactions:
        fig, axes = plt.subplots(len(branch_reactions), 1, figsize=(7.5, 3.8 * len(branch_reactions)),
                                 squeeze=False, sharey=True)
        for ax, (label, reactions) in zip(axes[:, 0], branch_reactions):
            plot_reactions(ax, reactions, f"Released knot, {label}: reactions")
        fig.tight_layout()
        written.append(save_figure(fig, out_dir / "fig17_released_reactions.png"))
        written.append(rod_figure(branch_panels, radius, out_dir / "fig15_released_knots.png",
                                  "Released knots seen from +z"))
    else:
        print("note: no branches: fig15 and fig17 skipped")

    if (run_dir / "stages").is_dir():
        written.append(rod_figure(stage_panels(run_dir, states[0].nodes), radius,
                                  out_dir / "fig12_stages.png", "Forming and tightening, seen from +z"))
    else:
        print(f"note: {run_dir / 'stages'} missing: fig12 skipped")

    try:
        written += knot_views.render_run(run_dir, out_dir, radius=radius)
    except knot_views.ViewError as e:
        print(f"note: no 3D views: {e}")

    print(markdown_table(rows))
    print()
    print("written:")
    for path in written:
        print(f"  {path}")


def main(argv):
    if len(argv) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    run_dir = Path(argv[1])
    try:
        report(run_dir)
    except ReportError as e:
        print(f"knot_report: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
