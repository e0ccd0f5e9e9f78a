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

Pulled by a force, the knot gives way at about 3.6 N (docs/knot.md, "The tightening force"). --driven F pulls
it to F by displacement instead: from the knot tightened at --driven-from (2 N), end B is held where it is while
its force is taken off (`hold`, the support's reaction takes the pull over), then moved along +x at 0.1 mm/s
(`drive`) and held still (`keep`, as `settle`). A first run (`probe`) drives end B by up to 1.5 mm and gives
the displacement at which its reaction first reaches F; the second moves end B by that much, so that the
tightened knot is held at about F (its reaction is what the table gives), then releases the support's
reaction to 0 for mu = 0.3 (release, rest) as the force-driven releases do.

Usage: scripts/knot_force_series.py OUT [--forces 0.5,1,2,4] [--elements 300] [--no-release]
                                        [--nodus build/release/nodus] [--jobs N] [--section-pairing P]
                                        [--driven 4.1] [--driven-from 2]
  (--forces "" --driven 4.1: the driven pull alone)
  OUT/force_F/knot.yaml    the scenario of force F; OUT/force_F/ its run (a finished run is not run again,
                           an interrupted one is resumed)
  OUT/driven_F/probe.yaml, run.yaml and their runs probe/, run/: the displacement-driven pull to F
  OUT/force_series.csv     one row per force and state; also printed as a markdown table
Requires python3-numpy and python3-matplotlib (Debian) and the nodus module (PYTHONPATH=build/release/python).
"""

import argparse
import csv
import math
import os
import signal
import subprocess
import sys
import time
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
    path, run = folder / "knot.yaml", folder / "run"
    write_scenario(path, run, scenario)
    if not (run / "summary.json").is_file():
        subprocess.run(nodus_command(nodus_binary, path, run, jobs), check=False)
    return run


DRIVE_RATE = 0.1  # mm of end B's travel per s of load time
DRIVE_STEP = 0.01  # mm of travel a step
PROBE_TRAVEL = 1.5  # mm


def driven_scenario(elements, base_force, pairing, travel, release):
    """The knot tightened at base_force, then a branch that holds end B and drives it by `travel` mm along +x
    (hold, drive, keep) and, with release, a second one that goes on to release the support for mu = 0.3."""
    scenario = knot_program.knot_scenario(elements, base_force, tighten_line_search=True, section_pairing=pairing)
    hold = {"name": "hold", "steps": 10, "stabilization": 0.01, "line_search": True, "activate": ["end_b"],
            "loads": {"pull_b": {"force": [0, 0, 0]}}}
    steps = max(1, round(travel / DRIVE_STEP))
    drive = {"name": "drive", "steps": steps, "duration": knot_program.num(travel / DRIVE_RATE),
             "stabilization": 0.01, "line_search": True,
             "motions": {"end_b": {"translation": [knot_program.num(travel), 0, 0]}}}
    keep = {"name": "keep", "steps": 16, "duration": 8, "stabilization": 0.01, "line_search": True}
    branches = [{"name": "driven", "from": "settle", "stages": [hold, drive, keep]}]
    if release:
        branches.append({"name": "driven_mu_0.30", "from": "settle", "contact": {"friction": 0.3}, "stages": [
            hold, drive, keep,
            {"name": "release", "steps": 20, "stabilization": 0.01, "line_search": True, "release": ["end_b"]},
            {"name": "rest", "steps": 20, "duration": 40, "stabilization": 0.01, "stabilization_end": 0,
             "line_search": True}]})
    scenario["branches"] = branches
    return scenario


def write_scenario(path, out, scenario):
    """Writes `scenario` to `path`, refused (ValueError, nothing written) where `out` holds a run of another."""
    path.parent.mkdir(parents=True, exist_ok=True)
    text = knot_program.nodus.Scenario(scenario).to_yaml()
    if path.is_file() and path.read_text() != text and out.exists():
        raise ValueError(f"{out} holds a run of another scenario than {path} would now say "
                         f"(another --elements or --section-pairing?): give another OUT")
    if not path.is_file() or path.read_text() != text:
        path.write_text(text)


def nodus_command(nodus_binary, path, out, jobs):
    command = [nodus_binary, "run", str(path), "--out", str(out), "--jobs", str(jobs), "--quiet"]
    if (out / "checkpoints").is_dir():
        command.append("--resume")
    print(f"{out.parent.name}/{out.name}: {' '.join(command)}", flush=True)
    return command


def travel_to(steps_csv, force):
    """End B's travel [mm] in `drive` when its support's reaction first reaches `force` [N], from a probe's
    steps.csv (NaN if it has not, or there is no such file)."""
    if not steps_csv.is_file():
        return float("nan")
    with open(steps_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    def number(row, key):  # the file is read while nodus writes it: a last line may be partial
        try:
            return float(row.get(key) or "nan")
        except ValueError:
            return float("nan")

    held = [r for r in rows if r.get("stage") == "hold"]
    if not held:
        return float("nan")
    start = number(held[-1], "time")
    for r in rows:
        if r.get("stage") == "drive" and number(r, "end_b_fx") >= force:
            return DRIVE_RATE * (number(r, "time") - start)
    return float("nan")


def run_driven(out, force, base_force, elements, release, nodus_binary, jobs, pairing):
    """The run of the knot driven to `force` (None if the probe's reaction never reaches it)."""
    folder = out / f"driven_{force:g}"
    path, probe = folder / "probe.yaml", folder / "probe"
    write_scenario(path, probe, driven_scenario(elements, base_force, pairing, PROBE_TRAVEL, False))
    steps = probe / "branches" / "driven" / "steps.csv"
    travel = travel_to(steps, force)
    if not np.isfinite(travel) and not (probe / "summary.json").is_file():
        # The probe is stopped once its reaction has reached the force: the knot held further may slip (at
        # about 4.2 N, docs/knot.md), and only the travel to the force is wanted.
        # Its own process group (with --jobs above 1 the branch runs in a child of `nodus run`), stopped as a
        # whole, also when this script is interrupted.
        process = subprocess.Popen(nodus_command(nodus_binary, path, probe, jobs), start_new_session=True)
        try:
            while process.poll() is None:
                time.sleep(2.0)
                if np.isfinite(travel_to(steps, force)):
                    break
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGTERM)
                try:
                    process.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)
                    process.wait()
        travel = travel_to(steps, force)
        if not np.isfinite(travel) and not (probe / "summary.json").is_file():
            print(f"driven {force:g} N: the probe stopped before its reaction reached {force:g} N (exit status "
                  f"{process.returncode}); run again to resume it", file=sys.stderr)
            return None
    if not np.isfinite(travel):
        print(f"driven {force:g} N: the probe's reaction never reached {force:g} N", file=sys.stderr)
        return None
    travel = round(travel, 4)
    print(f"driven {force:g} N: end B driven by {travel:g} mm", flush=True)
    path, run = folder / "run.yaml", folder / "run"
    write_scenario(path, run, driven_scenario(elements, base_force, pairing, travel, release))
    if not (run / "summary.json").is_file():
        subprocess.run(nodus_command(nodus_binary, path, run, jobs), check=False)
    return run


def smallest_clearance(steps_csv):
    """The smallest finite min_clearance of steps.csv [mm] (NaN if none)."""
    with open(steps_csv, newline="") as f:
        values = [float(row["min_clearance"]) for row in csv.DictReader(f) if row.get("min_clearance")]
    values = [v for v in values if np.isfinite(v)]
    return min(values) if values else float("nan")


def measure(force, run_dir, driven=False):
    """Rows of the states of a run; driven: its branches only (the main run is the knot tightened at the force
    it was driven from), the force being the reaction of end B's support at the end of `keep`."""
    summary = knot_report.read_summary(run_dir)
    states = [] if driven else [(run_dir, "tightened", summary)]
    for name, folder, _ in knot_report.find_branches(run_dir, summary):
        states.append((folder, name, knot_report.read_summary(folder)))
    if driven:
        steps = run_dir / "branches" / "driven" / "steps.csv"
        kept = []
        if steps.is_file():
            with open(steps, newline="") as f:
                kept = [r for r in csv.DictReader(f) if r["stage"] == "keep"]
        if kept:
            force = float(kept[-1]["end_b_fx"])
        states = [(folder, "tightened, end B held" if name == "driven" else name.replace("driven_", ""), own)
                  for folder, name, own in states]
    rows = []
    for folder, name, own in states:
        if not (folder / "contact_final.csv").is_file():
            continue
        state = knot_report.load_state(folder, name, own.get("friction"))
        row, reactions, _ = knot_report.analyse(state)
        rows.append({"force_N": force, "state": name + (" (driven)" if driven else ""),
                     "friction": own.get("friction"),
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
    parser.add_argument("--driven", default="", help="pull forces reached by driving end B [N], comma separated")
    parser.add_argument("--driven-from", type=float, default=2.0,
                        help="the pull force of the knot that --driven starts from [N]")
    parser.add_argument("--section-pairing", choices=("bisector", "plane"), default="bisector",
                        help="contact.section_pairing (docs/contact.md); plane: the paper's, which lets the knot "
                             "pulled at 2 N overlap itself")
    args = parser.parse_args(argv[1:])
    lists = {}
    for option, text in (("--forces", args.forces), ("--driven", args.driven)):
        try:
            lists[option] = [] if not text.strip() else [float(f) for f in text.split(",")]
        except ValueError:
            print(f"knot_force_series: {option}: expected numbers separated by commas, got {text}", file=sys.stderr)
            return 2
        if lists[option] and not all(math.isfinite(f) and f > 0 for f in lists[option]):
            print(f"knot_force_series: {option}: expected positive forces, got {text}", file=sys.stderr)
            return 2
    forces, driven = lists["--forces"], lists["--driven"]
    if not forces and not driven:
        print("knot_force_series: --forces: expected at least one force (or --driven)", file=sys.stderr)
        return 2
    if not (math.isfinite(args.driven_from) and args.driven_from > 0):
        print(f"knot_force_series: --driven-from: expected a positive force, got {args.driven_from:g}",
              file=sys.stderr)
        return 2
    if any(f <= args.driven_from for f in driven):
        print(f"knot_force_series: --driven: expected forces above --driven-from ({args.driven_from:g} N), got "
              f"{args.driven}", file=sys.stderr)
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
    for force in driven:
        try:
            run_dir = run_driven(args.out, force, args.driven_from, args.elements, not args.no_release, args.nodus,
                                 args.jobs, args.section_pairing)
        except ValueError as error:
            print(f"knot_force_series: {error}", file=sys.stderr)
            return 2
        if run_dir is not None:
            rows += measure(force, run_dir, driven=True)
    table = args.out / "force_series.csv"
    knot_report.write_csv(table, COLUMNS, rows)
    print(markdown(rows))
    print(f"written: {table}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
