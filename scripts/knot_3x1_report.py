#!/usr/bin/env python3
"""Report on a run of the 3x1 multifilament overhand knot of nodus (Durville 2012, Sect. 7.3, Figs. 19-21;
examples/knot_3x1.yaml, docs/knot_3x1.md), the yarn's counterpart of scripts/knot_report.py. Units: mm, N.

Usage: scripts/knot_3x1_report.py DIR [--yarn NAME] [--separation MM] [--out FOLDER]
       (Debian python3-numpy and python3-matplotlib, and the nodus module: PYTHONPATH=build/release/python,
       or found there)

The numbers come from nodus's Python module (knot_metrics, knot_invariant, min_self_distance,
min_distance_between; C++ in src/nodus/analysis/), the reading, writing and drawing from
scripts/knot_report.py and scripts/knot_views.py, imported.

Inputs (DIR is a run's output folder):
  DIR/final_nodes.csv, DIR/contact_final.csv       the tightened knot: the main run's final state, the end
                                                    of stage `settle` (required)
  DIR/steps.csv                                     last row: stabilization_force, normal_force, pull_bK_f*
  DIR/summary.json                                  optional: `friction`, `branches` (names, folders, friction)
  DIR/branches/NAME/{final_nodes,contact_final,steps}.csv   each release branch's final state: a released
                                                    knot (friction from summary.json, else from NAME, mu_0.30)
  DIR/stages/NNN_STAGE_{nodes,contact}.csv          stage-end states, for the 3D views

Definitions, for each state (the tightened knot, then each branch's final state, highest friction first):
  fibres          the beams YARN.rK.fJ (YARN from --yarn, default `yarn`), in the table's order, each's nodes
                  sorted by s; every other beam is left out of the numbers.
  mean centreline node k is the mean of node k of every fibre, as `nodus knot --yarn` takes it
                  (analysis::mean_curve; the fibres of a yarn have equal numbers of nodes and share their
                  reference arc lengths s, whose mean it takes), an open curve.
  knot_*          the knot type of a fibre's centreline and of the mean centreline, each closed far away
                  (nodus.knot_invariant, the Alexander polynomial: trefoil, unknot, another polynomial, or
                  unknown where every projection has a near-crossing), as knot_report.py's `knot`.
  in contact      contact elements with normal_force > 0; zones_in_contact the zones that have one.
  knot contacts   the contact elements between parts of the knot: an element of one fibre with itself, or
                  one between two fibres whose abscissas lie more than D = --separation (default 0.68 mm,
                  the example's delta_separ) apart, |abscissa_i - abscissa_j| > D. Two fibres of the yarn
                  lie side by side along its whole length and touch there all along (zones of hundreds of
                  elements pairing nearly equal abscissas): those contacts hold the yarn together and are
                  not the knot's (knot_views.knot_rows). A fibre's contact with itself is always the knot's:
                  the detection pairs a beam only with parts of itself at least delta_separ away.
  reactions       max_normal_N the largest R_N of an element, total_normal_N the sum of R_N,
                  total_tangential_N the sum of |T| (the column tangential_force), over every element;
                  knot_normal_N the sum of R_N over the knot contacts. steps_normal_force_N and
                  stabilization_force_N (the drag left) are the last row of steps.csv; tightening_force_N
                  the length of the sum over the fibres of the pull loads pull_bK_f (NaN without them).
  intermediate_length_mm   as knot_report.py (nodus.knot_metrics): the sum over zones of the span along the
                  intermediate geometry of the elements in contact, over every element;
                  knot_intermediate_length_mm over the knot contacts only.
  knot_s_a_mm, knot_s_b_mm   the knot's extent along the yarn: the smallest and largest abscissa_i,
                  abscissa_j of the knot contacts in contact (NaN without one).
  tail_angle_deg, loop_radius_mm, loop_length_mm   as knot_report.py defines them for the rod
                  (nodus.knot_metrics), on the mean centreline, with the knot contacts as the contact
                  elements: the extent [s_a, s_b] above, the tails' chords 2 mm long from s_a and s_b, the loop
                  the longest part of [s_a, s_b] not covered by a knot contact in contact.
  max_penetration_mm   max(-gap) over every element.
  fibre_distance_mm    the smallest distance between the centrelines (node polylines) of two fibres
                  (nodus.min_distance_between), fibre_distance_pair the two fibres.
  self_distance_F_mm   the smallest distance between two points of fibre F more than D apart along it
                  (nodus.min_self_distance, as `nodus knot --separation D`).
  end_b_x_F_mm    x of the node of fibre F with the largest s (end B).

Outputs, in DIR/report/ (or --out; each written to a temporary name, then renamed):
  knot_3x1_report.csv                  one row per state: the numbers above (printed as a markdown table,
                                       transposed: a row per number, a column per state)
  reactions_tightened.csv, reactions_NAME.csv   per element, as knot_report.py's, with beam_i, beam_j and
                                       knot (1 for a knot contact)
  fig19_intermediate_geometries.png    the tightened knot in 3D: the fibres as tubes, each in its colour, and
                                       the intermediate geometries of the elements in contact (the polylines
                                       of the midpoints (x_i + x_j) / 2 of each zone's runs of consecutive
                                       elements in contact; a lone element as a dot): dark red between parts
                                       of the knot, black between fibres side by side
  fig20_released_knots.png             the same, one panel per branch's final state
  fig21_released_reactions.png         the reactions along the intermediate geometries after release
                                       (knot_report.py's plot_reactions, Fig. 17), one panel per branch,
                                       highest friction first; the zones of fibres side by side shaded grey
  view3d_*.png                         3D views of every stage end and of each branch's final state
                                       (scripts/knot_views.py, the fibres as the knotted strands)
A figure whose inputs are missing is skipped with a note.
"""

import argparse
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # leaves no scripts/__pycache__ in the source tree
import knot_report as kr  # noqa: E402  (tables, branches, reactions: scripts/knot_report.py; imports nodus)
import knot_views as kv  # noqa: E402  (the 3D drawing: scripts/knot_views.py)

nodus = kr.nodus
plt = kr.plt

DEFAULT_YARN = "yarn"
DEFAULT_SEPARATION = 0.68      # mm, delta_separ of examples/knot_3x1.yaml: the knot contacts' least |s_i - s_j|
SIDE_RGB = (0.1, 0.1, 0.1)     # intermediate geometries of fibres side by side (the knot's: kv.LINE_RGB)
PANEL_WIDTH = 7.0              # inches, of a 3D panel of Figs. 19 and 20
TITLE_BAND = 0.8               # inches above each 3D panel for its title
REACTION_COLUMNS = kr.REACTION_COLUMNS + ["beam_i", "beam_j", "knot"]


@dataclass
class YarnState(kr.State):
    """A knot state of the yarn: `nodes` is its mean centreline (columns s, x, y, z; None when the fibres
    differ in their numbers of nodes), `fibres` {name: nodes sorted by s}, `folder` where its tables are."""
    fibres: dict = None
    folder: Path = None


def read_fibres(path, yarn):
    """{name: nodes sorted by s} of the fibres YARN.rK.fJ of a nodal table, in the table's order."""
    nodes = kr.read_table(path, kr.NODE_COLUMNS, ["beam"])
    names = [b for b in dict.fromkeys(nodes["beam"]) if str(b).startswith(yarn + ".")]
    if not names:
        raise kr.ReportError(f"{path}: expected the fibres {yarn}.rK.fJ of yarn {yarn}, got none")
    fibres = {}
    for name in names:
        fibre = kr.select(nodes, nodes["beam"] == name)
        if len(fibre["s"]) < 2:
            raise kr.ReportError(f"{path}: fibre {name}: fewer than two nodes")
        fibres[str(name)] = kr.select(fibre, np.argsort(fibre["s"], kind="stable"))
    return fibres


def mean_centreline(fibres):
    """Columns s, x, y, z of the mean of the fibres node by node (analysis::mean_curve), or None if they
    differ in their numbers of nodes."""
    if len({len(f["s"]) for f in fibres.values()}) != 1:
        return None
    return {c: np.mean([f[c] for f in fibres.values()], axis=0) for c in ("s", "x", "y", "z")}


def winding_deg(fibres):
    """{name: how far the fibre winds about the centre of the fibres (the mean of their nodes of equal index),
    seen along the chord of that centre from its first node to its last, followed node by node [degrees]}
    (analysis::winding_about_centre), or None if the fibres differ in their numbers of nodes. Fibres whose
    ends are held change it by whole turns only by passing through one another: after `twist` it is the end
    bodies' turn (docs/knot_3x1.md)."""
    if len({len(f["s"]) for f in fibres.values()}) != 1:
        return None
    points = {name: np.column_stack([f["x"], f["y"], f["z"]]) for name, f in fibres.items()}
    centre = np.mean(list(points.values()), axis=0)
    axis = centre[-1] - centre[0]
    axis /= np.linalg.norm(axis)
    e1 = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    result = {}
    for name, p in points.items():
        offset = p - centre
        angle = np.arctan2(offset @ e2, offset @ e1)
        turns = np.remainder(np.diff(angle) + np.pi, 2 * np.pi) - np.pi   # each step's turn, in [-pi, pi)
        result[name] = float(np.degrees(turns.sum()))
    return result


def load_state(folder, name, friction, yarn):
    fibres = read_fibres(folder / "final_nodes.csv", yarn)
    return YarnState(name, friction, mean_centreline(fibres), kr.read_contact(folder / "contact_final.csv"),
                     kr.read_last_step(folder / "steps.csv"), fibres, folder)


def short_name(fibre, yarn):
    """`r1.f1` of `yarn.r1.f1`."""
    return fibre[len(yarn) + 1:]


def knot_contacts(state, separation):
    """Mask of the state's knot contacts (see the module's docstring; knot_views.knot_rows)."""
    return kv.knot_rows(state.contact, list(state.fibres), separation)


def tightening_force(last_step):
    """|sum over K of (pull_bK_fx, pull_bK_fy, pull_bK_fz)| [N], NaN without such columns."""
    total, found = np.zeros(3), False
    for column, value in last_step.items():
        match = re.fullmatch(r"pull_b\d*_f([xyz])", column)
        if match:
            total["xyz".index(match.group(1))] += value
            found = True
    return float(np.linalg.norm(total)) if found else np.nan


def analyse(state, yarn, separation):
    """(row of knot_3x1_report.csv as a dict, reactions table as a dict of columns) of a state."""
    contact, fibres = state.contact, state.fibres
    knot = knot_contacts(state, separation)
    centreline = state.nodes
    if centreline is None:
        first = next(iter(fibres))
        print(f"note: {state.name}: the fibres differ in their numbers of nodes: no mean centreline; the tail "
              f"angle and loop are those of {first}")
        centreline = fibres[first]
    polyline = kr.nodes_polyline(centreline)
    options = {"tail_chord": kr.TAIL_CHORD, "min_spacing": kr.MIN_SPACING, "min_loop_nodes": kr.MIN_LOOP_NODES}
    m = nodus.knot_metrics(polyline, contact, **options)
    m_knot = nodus.knot_metrics(polyline, kr.select(contact, knot), **options)
    pressing = contact["normal_force"] > 0
    row = {"state": state.name, "friction": state.friction,
           "knot_mean": kr.knot_type(polyline[0]) if state.nodes is not None else "n/a"}
    for name, fibre in fibres.items():
        row[f"knot_{short_name(name, yarn)}"] = kr.knot_type(kr.nodes_polyline(fibre)[0])
    row.update({
        "tightening_force_N": tightening_force(state.last_step),
        "stabilization_force_N": state.last_step.get("stabilization_force", np.nan),
        "steps_normal_force_N": state.last_step.get("normal_force", np.nan),
        "zones": m["zones"],
        "zones_in_contact": len(np.unique(contact["zone"][pressing])),
        "contact_elements": m["contact_elements"],
        "elements_in_contact": m["elements_in_contact"],
        "knot_zones_in_contact": len(np.unique(contact["zone"][pressing & knot])),
        "knot_elements_in_contact": m_knot["elements_in_contact"],
        "max_normal_N": m["max_normal"],
        "total_normal_N": m["total_normal"],
        "knot_normal_N": m_knot["total_normal"],
        "total_tangential_N": m["total_tangential"],
        "intermediate_length_mm": m["intermediate_length"],
        "knot_intermediate_length_mm": m_knot["intermediate_length"],
        "knot_s_a_mm": m_knot["s_a"],
        "knot_s_b_mm": m_knot["s_b"],
        "tail_angle_deg": m_knot["tail_angle"],
        "loop_radius_mm": m_knot["loop_radius"],
        "loop_length_mm": m_knot["loop_length"],
        "max_penetration_mm": m["max_penetration"],
    })
    names = list(fibres)
    pairs = [(a, b, nodus.min_distance_between(*kr.nodes_polyline(fibres[a]), *kr.nodes_polyline(fibres[b]))[0])
             for k, a in enumerate(names) for b in names[k + 1:]]
    closest = min(pairs, key=lambda p: p[2]) if pairs else None
    row["fibre_distance_mm"] = closest[2] if closest else np.nan
    row["fibre_distance_pair"] = (f"{short_name(closest[0], yarn)}/{short_name(closest[1], yarn)}"
                                  if closest else "")
    for name, fibre in fibres.items():
        row[f"self_distance_{short_name(name, yarn)}_mm"] = nodus.min_self_distance(
            *kr.nodes_polyline(fibre), separation)[0]
    for name, fibre in fibres.items():
        row[f"end_b_x_{short_name(name, yarn)}_mm"] = fibre["x"][-1]
    reactions = kr.reactions_of(m, contact)
    element = np.asarray(m["reactions"]["element"], int)
    reactions.update({"beam_i": contact["beam_i"][element], "beam_j": contact["beam_j"][element],
                      "knot": knot[element].astype(int)})
    return row, reactions


def report_columns(rows):
    """The columns of knot_3x1_report.csv: every row's keys, in the order first met."""
    return list(dict.fromkeys(c for row in rows for c in row))


def transposed_markdown(rows, columns):
    """A markdown table with a row per column of `rows` and a column per row (state)."""
    lines = ["| | " + " | ".join(str(row["state"]) for row in rows) + " |", "|---|" + "---|" * len(rows)]
    for column in columns[1:]:
        lines.append(f"| {column} | " + " | ".join(kr.table_cell(row.get(column)) for row in rows) + " |")
    return "\n".join(lines)


# ------------------------------------------------------------------------------------------------ 3D figures

def contact_runs(contact, knot):
    """[(polyline (k, 3) of midpoints, is the knot's)]: each zone's runs of consecutive elements (zeta order)
    in contact and of one kind (knot contact or side by side)."""
    mid = 0.5 * (np.column_stack([contact[f"{c}_i"] for c in "xyz"])
                 + np.column_stack([contact[f"{c}_j"] for c in "xyz"]))
    pressing = contact["normal_force"] > 0
    runs = []
    for zone in np.unique(contact["zone"]):
        rows = np.flatnonzero(contact["zone"] == zone)
        start = None
        for k in range(len(rows) + 1):
            same = (k < len(rows) and pressing[rows[k]]
                    and (start is None or knot[rows[k]] == knot[rows[start]]))
            if start is not None and not same:
                runs.append((mid[rows[start:k]], bool(knot[rows[start]])))
                start = None
            if start is None and k < len(rows) and pressing[rows[k]]:
                start = k
    return runs


def draw_yarn_panel(ax, beams, fibres, contact, knot, radius, elev, azim):
    """The fibres as tubes in their colours (other beams grey) and the intermediate geometries of the elements
    in contact (contact_runs); returns the points to frame."""
    strands = kv.strands_of(beams, fibres)
    pieces, shown = kv.whole_pieces(beams, strands)
    kv.draw_tube_panel(ax, pieces, shown, radius, kv.DEFAULT_SIDES, elev, azim)
    for strand in strands:
        kv.draw_ends(ax, strand)
    for line, is_knot in contact_runs(contact, knot):
        colour, width = (kv.LINE_RGB, 2.2) if is_knot else (SIDE_RGB, 1.0)
        if len(line) == 1:
            ax.plot(*line.T, "o", color=colour, ms=3.5 if is_knot else 2.0, zorder=6, clip_on=False)
        else:
            ax.plot(*line.T, color=colour, lw=width, zorder=6, clip_on=False)
    return shown


def panel_title(state, beams, fibres, separation):
    colours = ", ".join(f"{b.name} {kv.strand_colour(k, len(fibres))[0]}"
                        for k, b in enumerate(kv.strands_of(beams, fibres)))
    return (f"{state.label}: {colours}\nintermediate geometries in contact: dark red between parts of the knot "
            f"(|s_i - s_j| > {separation:g} mm\nor one fibre), black between fibres side by side")


def render_yarn_states(states, path, title, radius, separation, elev=kv.DEFAULT_ELEV, azim=kv.DEFAULT_AZIM):
    """One 3D panel per state (two to a row), each zoomed to fill its panel (knot_views.frame_panel), with the
    triad of the axes under it; written to `path` (PNG)."""
    columns = min(len(states), 2)
    rows = -(-len(states) // columns)
    width = PANEL_WIDTH * columns
    fig = plt.figure(figsize=(width, 6.0))
    axes, shown, titles = [], [], []
    for k, state in enumerate(states):
        # The yarn alone, as the paper's figures show it: the clamping beams are lifted away by then (the stage
        # views, view3d_stage_*.png, show them).
        beams = [b for b in kv.read_beams(state.folder / "final_nodes.csv") if b.name in state.fibres]
        ax = fig.add_axes([(k % columns) / columns, 0.0, 1.0 / columns, 0.8], projection="3d")
        shown.append(draw_yarn_panel(ax, beams, list(state.fibres), state.contact,
                                     knot_contacts(state, separation), radius, elev, azim))
        axes.append(ax)
        titles.append(panel_title(state, beams, list(state.fibres), separation))
    fig.canvas.draw()
    ratios = [size[1] / size[0] for _, size in (kv.projected_box(ax, p) for ax, p in zip(axes, shown))]
    panel = float(np.clip(max(ratios) * PANEL_WIDTH / kv.FILL, 2.5, 7.0))
    cell = panel + TITLE_BAND + kv.TRIAD_BAND
    height = rows * cell + 0.4
    fig.set_size_inches(width, height)
    for k, (ax, text) in enumerate(zip(axes, titles)):
        bottom = (rows - 1 - k // columns) * cell + kv.TRIAD_BAND
        left = (k % columns) / columns
        ax.set_position([left, bottom / height, 1.0 / columns, panel / height])
        fig.text(left + 0.5 / columns, (bottom + panel) / height, text, fontsize=9, ha="center", va="bottom")
    fig.suptitle(title, y=1.0 - 0.08 / height, va="top")
    fig.canvas.draw()
    for ax, points in zip(axes, shown):
        rect, px_per_mm = kv.frame_panel(ax, points, elev, azim)
        kv.draw_triad(fig, rect, px_per_mm, elev, azim)
    return kr.save_figure(fig, path)


def plot_branch_reactions(ax, reactions, title):
    """knot_report.plot_reactions, over a grey band on each zone of fibres side by side."""
    labelled = False
    for zone in np.unique(reactions["zone"]):
        rows = reactions["zone"] == zone
        if not reactions["knot"][rows].any():
            x = reactions["abscissa_mm"][rows]
            ax.axvspan(x.min(), x.max(), color="0.88", lw=0,
                       label=None if labelled else "zones of fibres side by side")
            labelled = True
    kr.plot_reactions(ax, reactions, title)


# ------------------------------------------------------------------------------------------------ report

def report(run_dir, out_dir, yarn, separation):
    for required in ("final_nodes.csv", "contact_final.csv"):
        if not (run_dir / required).is_file():
            raise kr.ReportError(f"{run_dir / required}: missing")
    summary = kr.read_summary(run_dir)
    states = [load_state(run_dir, "tightened", kr.main_friction(summary), yarn)]
    for name, folder, friction in kr.find_branches(run_dir, summary):
        try:
            states.append(load_state(folder, name, friction, yarn))
        except kr.ReportError as e:
            print(f"note: branch {name} skipped: {e}")
    out_dir.mkdir(parents=True, exist_ok=True)
    fibres = list(states[0].fibres)
    radius = kv.measured_radius(kv.read_beams(run_dir / "final_nodes.csv"),
                                kv.read_contact(run_dir / "contact_final.csv")) or kv.DEFAULT_RADIUS
    rows, written, branch_reactions = [], [], []
    for state in states:
        row, reactions = analyse(state, yarn, separation)
        rows.append(row)
        n = len(reactions["zone"])
        written.append(kr.write_csv(out_dir / f"reactions_{state.name}.csv", REACTION_COLUMNS,
                                    [{c: reactions[c][k] for c in REACTION_COLUMNS} for k in range(n)]))
        if state.name != "tightened":
            branch_reactions.append((state.label, reactions))
    columns = report_columns(rows)
    written.insert(0, kr.write_csv(out_dir / "knot_3x1_report.csv", columns, rows))

    written.append(render_yarn_states(states[:1], out_dir / "fig19_intermediate_geometries.png",
                                      "Fig. 19: the tightened 3x1 knot and its intermediate geometries", radius,
                                      separation))
    if branch_reactions:
        written.append(render_yarn_states(states[1:], out_dir / "fig20_released_knots.png",
                                          "Fig. 20: the released 3x1 knots", radius, separation))
        fig, axes = plt.subplots(len(branch_reactions), 1, figsize=(9.0, 3.8 * len(branch_reactions)),
                                 squeeze=False, sharey=True)
        for ax, (label, reactions) in zip(axes[:, 0], branch_reactions):
            plot_branch_reactions(ax, reactions, f"Released 3x1 knot, {label}: reactions along the intermediate "
                                  "geometries")
        fig.tight_layout()
        written.append(kr.save_figure(fig, out_dir / "fig21_released_reactions.png"))
    else:
        print("note: no branches: fig20 and fig21 skipped")
    try:
        written += kv.render_run(run_dir, out_dir, radius=radius, strands=fibres, separation=separation)
    except kv.ViewError as e:
        print(f"note: no 3D views: {e}")

    for path in sorted((run_dir / "stages").glob("*_twist_nodes.csv")):
        winding = winding_deg(read_fibres(path, yarn))
        if winding:
            print(f"{path.name}: the fibres wind about the yarn's centre by " +
                  ", ".join(f"{short_name(name, yarn)} {w:.1f}" for name, w in winding.items()) + " degrees")
    print(transposed_markdown(rows, columns))
    print()
    print("written:")
    for path in written:
        print(f"  {path}")


def main(argv):
    parser = argparse.ArgumentParser(description="Report on a run of the 3x1 multifilament knot (Figs. 19-21).")
    parser.add_argument("run_dir", type=Path, help="the run's output folder")
    parser.add_argument("--yarn", default=DEFAULT_YARN, help=f"the yarn's name (default {DEFAULT_YARN}): its "
                        "fibres are the beams NAME.rK.fJ")
    parser.add_argument("--separation", type=float, default=DEFAULT_SEPARATION,
                        help=f"least |s_i - s_j| of a knot contact between two fibres, and of the points of a "
                             f"fibre's smallest self-distance [mm] (default {DEFAULT_SEPARATION:g})")
    parser.add_argument("--out", type=Path, help="where the outputs go (default RUN_DIR/report)")
    args = parser.parse_args(argv[1:])
    if not args.separation > 0:
        parser.error("--separation must be positive")
    try:
        report(args.run_dir, args.out or args.run_dir / "report", args.yarn, args.separation)
    except kr.ReportError as e:
        print(f"knot_3x1_report: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
