#!/usr/bin/env python3
"""Tightens the monofilament knot at a series of pull forces and tabulates the tightened states (docs/knot.md).

For each force F the loading program of examples/monofilament_knot.yaml (scripts/knot_program.py) is run with
F instead of 0.5 N on end B, with only the mu = 0.3 release as a branch (or none, --no-release). Two settings
differ from the example's: `pull` and `settle` take Newton's line search (knot_scenario(tighten_line_search=
True): without it 2 N and more crawl once the knot slips), and the contact elements' sections are paired by
`bisector` (contact.section_pairing; with the paper's `plane`, --section-pairing plane, the knot pulled at 2 N
overlaps itself where one strand wraps round the other). Its states are measured as by scripts/knot_report.py
(the metrics of nodus.knot_metrics). The table gives, for each force and state: the length of the intermediate
geometry in contact, the largest and summed normal reactions, the loop radius, the elements in contact, the
spacing of the contact elements along the intermediate geometry (a reaction per element scales with it; the
paper uses 58 elements, Fig. 14), and the clearance of the axes (steps.csv min_clearance: their distance less
the sections' reach, over pairs more than delta_separ apart) in the state and the smallest over the steps that
led to it: the contact elements' own penetrations do not show an overlap that falls between them.

Usage: scripts/knot_force_series.py OUT [--forces 0.5,1,2,4] [--elements 300] [--no-release]
                                        [--nodus build/release/nodus] [--jobs N] [--section-pairing P]
  OUT/force_F/knot.yaml    the scenario of force F; OUT/force_F/ its run (a finished run is not run again,
                           an interrupted one is resumed)
  OUT/force_series.csv     one row per force and state; also printed as a markdown table
Requires python3-numpy and python3-matplotlib (Debian) and the nodus module (PYTHONPATH=build/release/python).
"""

import argparse
import csv
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import knot_program  # noqa: E402  (also imports nodus)
import knot_report  # noqa: E402

COLUMNS = ["force_N", "state", "friction", "steps", "wall_s", "stabilization_force_N", "elements_in_contact",
           "contact_elements", "intermediate_length_mm", "element_spacing_mm", "max_normal_N", "total_normal_N",
           "max_tangential_N", "loop_radius_mm", "tail_angle_deg", "clearance_mm", "min_clearance_mm"]


def element_spacing(reactions):
    """Median distance along the intermediate geometry between successive contact elements of a zone [mm]."""
    zone, abscissa = np.asarray(reactions["zone"]), np.asarray(reactions["abscissa_mm"], float)
    gaps = [np.diff(abscissa[zone == z]) for z in np.unique(zone)]
    gaps = np.concatenate(gaps) if gaps else np.array([])
    return float(np.median(gaps)) if gaps.size else float("nan")


def run_force(out, force, elements, release, nodus_binary, jobs, pairing="bisector"):
    folder = out / f"force_{force:g}"
    folder.mkdir(parents=True, exist_ok=True)
    scenario = knot_program.knot_scenario(elements, force, tighten_line_search=True, section_pairing=pairing)
    scenario["branches"] = [b for b in scenario["branches"] if b["name"] == "mu_0.30"] if release else []
    if not scenario["branches"]:
        del scenario["branches"]
    path = folder / "knot.yaml"
    text = knot_program.nodus.Scenario(scenario).to_yaml()
    if path.is_file() and path.read_text() != text and (folder / "run").exists():
        raise ValueError(f"{folder / 'run'} holds a run of another scenario than {path} would now say "
                         f"(another --elements or --section-pairing?): give another OUT")
    if not path.is_file() or path.read_text() != text:
        path.write_text(text)
    summary = folder / "run" / "summary.json"
    if not summary.is_file():
        command = [nodus_binary, "run", str(path), "--out", str(folder / "run"), "--jobs", str(jobs), "--quiet"]
        if (folder / "run" / "checkpoints").is_dir():
            command.append("--resume")
        print(f"force {force:g} N: {' '.join(command)}", flush=True)
        subprocess.run(command, check=False)
    return folder / "run"


def smallest_clearance(steps_csv):
    """The smallest finite min_clearance of steps.csv [mm] (NaN if none)."""
    with open(steps_csv, newline="") as f:
        values = [float(row["min_clearance"]) for row in csv.DictReader(f) if row.get("min_clearance")]
    values = [v for v in values if np.isfinite(v)]
    return min(values) if values else float("nan")


def measure(force, run_dir):
    summary = knot_report.read_summary(run_dir)
    states = [(run_dir, "tightened", summary)]
    for name, folder, _ in knot_report.find_branches(run_dir, summary):
        states.append((folder, name, knot_report.read_summary(folder)))
    rows = []
    for folder, name, own in states:
        if not (folder / "contact_final.csv").is_file():
            continue
        state = knot_report.load_state(folder, name, own.get("friction"))
        row, reactions, _ = knot_report.analyse(state)
        rows.append({"force_N": force, "state": name, "friction": own.get("friction"),
                     "steps": own.get("steps"), "wall_s": own.get("wall_seconds"),
                     "stabilization_force_N": row["stabilization_force_N"],
                     "elements_in_contact": row["elements_in_contact"],
                     "contact_elements": row["contact_elements"],
                     "intermediate_length_mm": row["intermediate_length_mm"],
                     "element_spacing_mm": element_spacing(reactions), "max_normal_N": row["max_normal_N"],
                     "total_normal_N": row["total_normal_N"], "max_tangential_N": row["max_tangential_N"],
                     "loop_radius_mm": row["loop_radius_mm"], "tail_angle_deg": row["tail_angle_deg"],
                     "clearance_mm": state.last_step.get("min_clearance", np.nan),
                     "min_clearance_mm": smallest_clearance(folder / "steps.csv")})
        if not own.get("converged", False):
            rows[-1]["state"] += " (stopped: " + str(own.get("failure", "not finished")) + ")"
    return rows


def markdown(rows):
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for row in rows:
        cells = [knot_report.format_value(float(f"{v:.4g}") if isinstance(v, float) and np.isfinite(v) else v)
                 for v in (row[c] for c in COLUMNS)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--forces", default="0.5,1,2,4", help="pull forces on end B [N], comma separated")
    parser.add_argument("--elements", type=int, default=300)
    parser.add_argument("--no-release", action="store_true", help="tighten only (no mu = 0.3 branch)")
    parser.add_argument("--nodus", default=str(HERE.parent / "build" / "release" / "nodus"))
    parser.add_argument("--jobs", type=int, default=1, help="branches side by side (nodus run --jobs)")
    parser.add_argument("--section-pairing", choices=("bisector", "plane"), default="bisector",
                        help="contact.section_pairing (docs/contact.md); plane: the paper's, which lets the knot "
                             "pulled at 2 N overlap itself")
    args = parser.parse_args(argv[1:])
    try:
        forces = [float(f) for f in args.forces.split(",")]
    except ValueError:
        print(f"knot_force_series: --forces: expected numbers separated by commas, got {args.forces}",
              file=sys.stderr)
        return 2
    if not forces or min(forces) <= 0:
        print(f"knot_force_series: --forces: expected positive forces, got {args.forces}", file=sys.stderr)
        return 2
    rows = []
    for force in forces:
        try:
            run_dir = run_force(args.out, force, args.elements, not args.no_release, args.nodus, args.jobs,
                                args.section_pairing)
        except ValueError as error:
            print(f"knot_force_series: {error}", file=sys.stderr)
            return 2
        rows += measure(force, run_dir)
    table = args.out / "force_series.csv"
    knot_report.write_csv(table, COLUMNS, rows)
    print(markdown(rows))
    print(f"written: {table}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
