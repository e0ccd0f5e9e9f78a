#!/usr/bin/env python3
"""Compares a run with a reference run of the same scenario (the PETSc backend on N ranks against
the serial backend).

    compare_runs.py REFERENCE_DIR RUN_DIR [--nodes-tolerance 1e-8] [--end-only]

The same steps (steps.csv: stage, load time, Newton iterations, cutbacks, detections, normal iterations), the
same contact counts (zones and contact elements of every step; contact_final.csv's rows), and final nodes
(final_nodes.csv: positions in mm, directors) within the tolerance; the same for each branch folder. With
--end-only, only the last step (stage, load time, contact counts) and the final state are compared. Prints
the largest differences; exit status 0 when they agree, 1 when not, 2 on bad input.
"""
import argparse
import csv
import math
import sys
from pathlib import Path

SAME = ["step", "stage", "newton_iterations", "cutbacks", "zones", "contact_elements", "detections",
        "normal_iterations"]
NODE_COLUMNS = ["x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"]


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def compare_folder(ref, run, tolerance, label, end_only=False):
    problems = []
    ref_steps, run_steps = rows(ref / "steps.csv"), rows(run / "steps.csv")
    if end_only:
        # The path may differ (step attempts that diverge or not by round-off): the same end, and the steps
        # counted for the record.
        a, b = ref_steps[-1], run_steps[-1]
        for key in ["stage", "zones", "contact_elements"]:
            if a[key] != b[key]:
                problems.append(f"{label}: last step: {key} {b[key]} against {a[key]}")
        if not math.isclose(float(a["time"]), float(b["time"]), rel_tol=1e-12):
            problems.append(f"{label}: last step: time {b['time']} against {a['time']}")
        ref_steps, run_steps = [], run_steps
    elif len(ref_steps) != len(run_steps):
        problems.append(f"{label}: {len(run_steps)} steps against {len(ref_steps)}")
    for a, b in zip(ref_steps, run_steps):
        for key in SAME:
            if key in a and a[key] != b.get(key):
                problems.append(f"{label}: step {a['step']}: {key} {b.get(key)} against {a[key]}")
        if not math.isclose(float(a["time"]), float(b["time"]), rel_tol=1e-12, abs_tol=1e-15):
            problems.append(f"{label}: step {a['step']}: time {b['time']} against {a['time']}")
    ref_nodes, run_nodes = rows(ref / "final_nodes.csv"), rows(run / "final_nodes.csv")
    if len(ref_nodes) != len(run_nodes):
        problems.append(f"{label}: {len(run_nodes)} final nodes against {len(ref_nodes)}")
    largest = 0.0
    for a, b in zip(ref_nodes, run_nodes):
        if (a["beam"], a["node"]) != (b["beam"], b["node"]):
            problems.append(f"{label}: final node {b['beam']} {b['node']} against {a['beam']} {a['node']}")
            break
        for key in NODE_COLUMNS:
            largest = max(largest, abs(float(a[key]) - float(b[key])))
    if largest > tolerance:
        problems.append(f"{label}: final nodes differ by {largest:.3g} (> {tolerance:g})")
    contacts = [p for p in ("contact_final.csv",) if (ref / p).exists()]
    for name in contacts:
        n_ref, n_run = len(rows(ref / name)), len(rows(run / name))
        if n_ref != n_run:
            problems.append(f"{label}: {name}: {n_run} rows against {n_ref}")
    counts = f" (the reference {len(rows(ref / 'steps.csv'))})" if end_only else ""
    print(f"{label}: {len(run_steps)} steps{counts}, final nodes within {largest:.3g}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference", type=Path)
    parser.add_argument("run", type=Path)
    parser.add_argument("--nodes-tolerance", type=float, default=1e-8)
    parser.add_argument("--end-only", action="store_true",
                        help="compare the last step and the final state only (the path may differ)")
    args = parser.parse_args()
    for folder in (args.reference, args.run):
        if not (folder / "steps.csv").is_file() or not (folder / "final_nodes.csv").is_file():
            print(f"compare_runs.py: {folder}: expected a run's folder (steps.csv, final_nodes.csv)",
                  file=sys.stderr)
            return 2
    problems = compare_folder(args.reference, args.run, args.nodes_tolerance, "main run", args.end_only)
    branches = args.reference / "branches"
    if branches.is_dir():
        for ref_branch in sorted(p for p in branches.iterdir() if p.is_dir()):
            run_branch = args.run / "branches" / ref_branch.name
            if not (run_branch / "final_nodes.csv").is_file():
                problems.append(f"branch {ref_branch.name}: missing in {args.run}")
                continue
            problems += compare_folder(ref_branch, run_branch, args.nodes_tolerance, f"branch {ref_branch.name}",
                                       args.end_only)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
