#!/usr/bin/env python3
"""Pictures of a yarn run of nodus (Durville 2012, Figs. 22-23 and 29-30): the cross-section at mid-length
before and after, and a 3D view of the fibres. Units: mm.

Usage (Debian's python3 with python3-numpy and python3-matplotlib, and nodus's Python module for its reader of
VTK files: run with PYTHONPATH=build/release/python /usr/bin/python3):
  scripts/yarn_section.py DIR [--stage NAME] [--out PNG]
      DIR a run's output folder. Draws the section of the initial state and of the final state (or of the end
      of stage NAME, a stage name or its index NNN) side by side, coloured by roving, and a 3D view of the
      fibres in that state. Default output: DIR/report/yarn_section.png.
  scripts/yarn_section.py --layout DIR [DIR ...] --out PNG
      The initial section of each run, side by side (docs/yarns.md draws the 3x1, 3x9 and 3x25 layouts so,
      from runs of examples/yarn_3x*.yaml, whose one stage `lay` has no conditions).

Inputs, all from the run's own files (docs/output.md):
  DIR/final_nodes.csv or DIR/stages/NNN_STAGE_nodes.csv   the state drawn as "after": per node, the beam name
                                                           and the centre x, y, z, beams in scenario order
  DIR/vtk/step_000000.vtp                                  the initial state: its first points are the node
                                                           centres in the same order (global node numbering),
                                                           and its tube rings give each fibre's radius R
                                                           (distance of a ring point from its node's centre:
                                                           R |g1| with g1 unit in the initial state)

Definitions:
  yarn axis t      the mean unit chord (last node - first node) of the fibres in the initial state
  origin o         the mean initial centre of the fibres' first nodes; length L their mean initial chord length
  section plane    the fixed plane (x - o) . t = L / 2 (mid-length of the laid yarn), the same for both states
  section point    where a fibre's centreline, the polyline through its node centres, first crosses that plane
                   (linear between the two nodes on either side)
  section axes     e1 = the initial director g1 of the first fibre (the yarn's director1: the same for all
                   fibres of a yarn), made orthogonal to t; e2 = t x e1. Points are drawn at ((p-o).e1,(p-o).e2)
  circles          of radius R at each section point (a fibre crossing the plane obliquely cuts an ellipse; the
                   circle is the fibre's own section, as in the paper's figures)
  roving           from the beam name YARN.rK.fJ (colour by K); other beams in grey
  3D view          centrelines as thick lines, coloured by roving; the axes are in mm but not to one scale (the
                   yarn is far longer than it is wide): read the ticks
"""

import argparse
import csv
import os
import re
import sys
from pathlib import Path

import numpy as np
from nodus.vtk import read_vtp
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

FIBRE_NAME = re.compile(r"^(?P<yarn>.*)\.r(?P<roving>\d+)\.f(?P<fibre>\d+)$")


def read_nodes(path):
    """Beam names in order and, per beam, its node centres (array n x 3) from a node table."""
    beams, centres = [], {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            name = row["beam"]
            if name not in centres:
                beams.append(name)
                centres[name] = []
            centres[name].append((float(row["x"]), float(row["y"]), float(row["z"])))
    return beams, {name: np.array(c) for name, c in centres.items()}


def read_initial(run, beams, final):
    """Initial node centres per beam, the first fibre's initial g1 and each beam's radius, from the first VTK file."""
    vtp = run / "vtk" / "step_000000.vtp"
    if not vtp.exists():
        sys.exit(f"{vtp}: expected the initial VTK file of the run (docs/output.md), got none")
    picture = read_vtp(vtp)
    points, node, g1 = picture.points, picture.point_data["node"], picture.point_data["g1"]
    count = sum(len(final[b]) for b in beams)
    if count > len(points):
        sys.exit(f"{vtp}: expected at least {count} points (the nodes of the node table), got {len(points)}")
    ring = np.arange(count, len(points))
    distance = np.linalg.norm(points[ring] - points[node[ring]], axis=1)
    initial, radius, first = {}, {}, 0
    for b in beams:
        n = len(final[b])
        initial[b] = points[first:first + n]
        mine = (node[ring] >= first) & (node[ring] < first + n)
        radius[b] = float(np.mean(distance[mine])) if mine.any() else 0.0
        first += n
    return initial, g1[0], radius


def frame(initial, beams, g1):
    """The yarn axis t, origin o, length L and section axes e1, e2 (module docstring)."""
    chords = np.array([initial[b][-1] - initial[b][0] for b in beams])
    lengths = np.linalg.norm(chords, axis=1)
    t = np.mean(chords / lengths[:, None], axis=0)
    t /= np.linalg.norm(t)
    o = np.mean([initial[b][0] for b in beams], axis=0)
    e1 = g1 - np.dot(g1, t) * t
    e1 /= np.linalg.norm(e1)
    return t, o, float(np.mean(lengths)), e1, np.cross(t, e1)


def section_point(centres, t, o, level):
    """Where the polyline through `centres` first crosses the plane (x - o) . t = level; None if it does not."""
    h = (centres - o) @ t - level
    for i in range(len(h) - 1):
        if h[i] == 0.0:
            return centres[i]
        if h[i] * h[i + 1] < 0.0:
            a = h[i] / (h[i] - h[i + 1])
            return centres[i] + a * (centres[i + 1] - centres[i])
    return centres[-1] if h[-1] == 0.0 else None


def roving_of(name):
    match = FIBRE_NAME.match(name)
    return int(match["roving"]) if match else None


def colour(roving):
    return "0.6" if roving is None else plt.get_cmap("tab10")((roving - 1) % 10)


def draw_section(ax, beams, centres, radius, t, o, level, e1, e2, title):
    missing = 0
    extent = 0.0
    for b in beams:
        p = section_point(centres[b], t, o, level)
        if p is None:
            missing += 1
            continue
        u, v = float(np.dot(p - o, e1)), float(np.dot(p - o, e2))
        ax.add_patch(Circle((u, v), radius[b], facecolor=colour(roving_of(b)), edgecolor="k", linewidth=0.4))
        extent = max(extent, abs(u) + radius[b], abs(v) + radius[b])
    extent = 1.1 * extent if extent > 0 else 1.0
    ax.set_xlim(-extent, extent)
    ax.set_ylim(-extent, extent)
    ax.set_aspect("equal")
    ax.set_xlabel("e1 [mm]")
    ax.set_ylabel("e2 [mm]")
    ax.set_title(title + (f"\n({missing} fibres do not reach the plane)" if missing else ""), fontsize=9)


def draw_3d(ax, beams, centres, title):
    for b in beams:
        c = centres[b]
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=colour(roving_of(b)), linewidth=1.5)
    everything = np.vstack([centres[b] for b in beams])
    span = np.maximum(everything.max(axis=0) - everything.min(axis=0), 1e-12)
    ax.set_box_aspect(tuple(np.maximum(span / span.max(), 0.35)))
    for axis in "xyz":
        ax.locator_params(axis=axis, nbins=4)
    ax.tick_params(labelsize=7)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    ax.set_title(title + "\n(axes not to one scale)", fontsize=9)


def stage_table(run, stage):
    tables = sorted((run / "stages").glob("*_nodes.csv"))
    for path in tables:
        number, name = path.name[:-len("_nodes.csv")].split("_", 1)
        if stage in (name, number) or (stage.isdigit() and int(stage) == int(number)):
            return path, f"end of stage {name}"
    names = ", ".join(p.name for p in tables) or "none"
    sys.exit(f"{run}: --stage: expected a stage with a table in {run / 'stages'} ({names}), got {stage}")


def save(fig, out):
    out.parent.mkdir(parents=True, exist_ok=True)
    temporary = out.with_name(out.name + f".tmp{os.getpid()}.png")
    fig.savefig(temporary, dpi=110)
    os.replace(temporary, out)
    print(out)


def load(run):
    final_path = run / "final_nodes.csv"
    if not final_path.exists():
        sys.exit(f"{final_path}: expected the node table of a finished run (docs/output.md), got none")
    beams, final = read_nodes(final_path)
    initial, g1, radius = read_initial(run, beams, final)
    return beams, final, initial, g1, radius


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", type=Path, help="the run's output folder (several with --layout)")
    parser.add_argument("--stage", help="draw the end of this stage (name or index) instead of the final state")
    parser.add_argument("--layout", action="store_true", help="only the initial sections of the runs")
    parser.add_argument("--out", type=Path, help="the PNG to write")
    args = parser.parse_args()

    if args.layout:
        if args.out is None:
            parser.error("--layout needs --out")
        fig, axes = plt.subplots(1, len(args.runs), figsize=(3.2 * len(args.runs), 3.4), squeeze=False)
        for ax, run in zip(axes[0], args.runs):
            beams, _, initial, g1, radius = load(run)
            t, o, length, e1, e2 = frame(initial, beams, g1)
            rovings = {roving_of(b) for b in beams}
            per = len(beams) // max(len(rovings), 1)
            draw_section(ax, beams, initial, radius, t, o, length / 2, e1, e2,
                         f"{len(rovings)}x{per}, R = {radius[beams[0]]:.4g} mm")
        fig.tight_layout()
        save(fig, args.out)
        return

    if len(args.runs) != 1:
        parser.error("one run folder (several only with --layout)")
    run = args.runs[0]
    beams, final, initial, g1, radius = load(run)
    after, label = final, "final state"
    if args.stage is not None:
        path, label = stage_table(run, args.stage)
        names, after = read_nodes(path)
        if names != beams:
            sys.exit(f"{path}: expected the beams of final_nodes.csv, got others")
    t, o, length, e1, e2 = frame(initial, beams, g1)
    fig = plt.figure(figsize=(14, 4.4))
    grid = fig.add_gridspec(1, 3, width_ratios=(1, 1, 1.5))
    draw_section(fig.add_subplot(grid[0, 0]), beams, initial, radius, t, o, length / 2, e1, e2,
                 "initial state, section at mid-length")
    draw_section(fig.add_subplot(grid[0, 1]), beams, after, radius, t, o, length / 2, e1, e2,
                 f"{label}, section at mid-length")
    draw_3d(fig.add_subplot(grid[0, 2], projection="3d"), beams, after, f"{label}, fibres")
    fig.tight_layout()
    save(fig, args.out or run / "report" / "yarn_section.png")


if __name__ == "__main__":
    main()
