#!/usr/bin/env python3
"""Description: a friction sweep of the released monofilament overhand knot [Durville 2012, Sect. 7.2.2,
Figs. 15-17], coarse: the knot is tied and tightened once, then released from the pulled state for each
friction coefficient mu; the tail angle and the loop radius of each released knot are plotted against mu.

The loading program is scripts/knot_program.py's (the flagship examples/monofilament_knot.yaml), on a coarser
rod: 150 elements instead of 300, as tests/long/test_monofilament_knot.cpp runs it (the motions do not depend
on the mesh, but convergence does: at 100 and 120 elements the `thread` stage fails, at 200 the `loop` stage).
The script writes the program's YAML, reads it with nodus.Scenario.from_yaml, replaces its branches by one
release per mu (the first branch's stages, with contact.friction set to mu) through to_dict() and
Scenario(dict), and runs it with nodus.run: the main run forms and tightens the knot, then the branches
release it, `--jobs` at a time. To keep the run short, the main run ends with `pull` and the releases start
from there: on the 150-element rod the flagship's `settle` (the force held until the knot stops moving) had not
ended after 231 steps and 6642 Newton iterations, nearly as many as all the stages before it, when it was
stopped; `--settle` keeps it. The knot is then still moving when the force is released (the drag left is 7 %
of the pull), so the released knots are not the flagship's.

Knot metrics (docs/knot.md, scripts/knot_report.py): the knot occupies the arc lengths [s_a, s_b] touched by
contact elements with R_N > 0; the tail angle [deg] is the angle between the chords leaving it over 2 mm on
each side (180 deg: tails pulled straight apart); the loop is the longest part of [s_a, s_b] clear of contact,
its radius [mm] that of the circle fitted to its nodes.

Sample runs:
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/friction_sweep.py
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/friction_sweep.py out/sweep --mu 0.3 0.2

Writes OUT/knot.yaml (the program as generated), OUT/knot_sweep.yaml (with the sweep's branches), the run's
files in OUT/run/ (one folder per release in OUT/run/branches/), OUT/friction_sweep.csv (one row per state:
the main run's final state, then each release) and OUT/friction_sweep.png. Exits with status 1 if a run does
not converge or a state has no knot to measure. Run time: see docs/python.md.
"""

import argparse
import csv
import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

import nodus  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
ELEMENTS = 150           # along the rod (the flagship has 300)
FRICTIONS = (0.3, 0.25, 0.2)
COLUMNS = ["state", "friction", "steps", "tail_angle_deg", "loop_radius_mm", "loop_length_mm",
           "elements_in_contact", "total_normal_N", "total_tangential_N", "stabilization_force_N"]


def _load(name):
    """A module of scripts/ imported by path (scripts/ is not a package)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_knot_report = _load("knot_report")


def knot_metrics(folder, name, friction):
    """The knot_report.csv row (a dict: tail_angle_deg, loop_radius_mm, loop_length_mm, ...) of the final state
    of the run in `folder`: scripts/knot_report.py reads the run's CSV files and its analyse() calls
    nodus.knot_metrics (the C++ metrics of src/nodus/analysis/knot_metrics.hpp)."""
    row, _, _ = _knot_report.analyse(_knot_report.load_state(Path(folder), name, friction))
    return row


def sweep_scenario(program, frictions, settle):
    """`program` (a Scenario) with its branches replaced by one release per friction coefficient: each the
    first branch's stages, with contact.friction = mu. Without `settle`, the main run ends with `pull` and the
    releases start from there."""
    data = program.to_dict()
    release = dict(data["branches"][0])
    if not settle:
        data["stages"] = [stage for stage in data["stages"] if stage["name"] != "settle"]
        release["from"] = data["stages"][-1]["name"]
    # Lowest friction first: that knot slides furthest and its release takes longest (at 150 elements, mu = 0.2
    # took twice as long as 0.3 or 0.25), so that the others run beside it rather than after it.
    data["branches"] = [dict(release, name=f"mu_{mu:.2f}", contact={"friction": mu}) for mu in sorted(frictions)]
    return nodus.Scenario(data)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out/python/friction_sweep", help="output folder")
    parser.add_argument("--mu", type=float, nargs="+", default=FRICTIONS, help="friction coefficients")
    parser.add_argument("--elements", type=int, default=ELEMENTS, help="quadratic elements along the rod")
    parser.add_argument("--jobs", type=int, default=2, help="releases run side by side")
    parser.add_argument("--settle", action="store_true",
                        help="keep the `settle` stage before the releases (minutes more on the coarse rod)")
    parser.add_argument("--resume", action="store_true", help="continue an interrupted run in OUT/run")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    # The knot's program, as scripts/knot_program.py writes it (it needs numpy: run it with this Python).
    program = subprocess.run([sys.executable, str(ROOT / "scripts" / "knot_program.py"), "--elements",
                              str(args.elements)], check=True, capture_output=True, text=True).stdout
    (out / "knot.yaml").write_text(program, encoding="utf-8")
    scenario = sweep_scenario(nodus.Scenario.from_yaml(out / "knot.yaml"), args.mu, args.settle)
    # Written to a file so that the branches can run in processes of their own (--jobs); a Scenario built from
    # data would run them here, one after the other.
    scenario.to_yaml(out / "knot_sweep.yaml")
    outcome = nodus.run(out / "knot_sweep.yaml", out / "run", jobs=args.jobs, resume=args.resume, quiet=True)
    if not outcome.converged:
        print(f"friction_sweep: the run did not converge: {outcome}", file=sys.stderr)
        return 1

    rows = []
    # The main run's final state (the end of `pull`, or of `settle`), then each release's.
    states = [(scenario.stages[-1], out / "run", scenario.to_dict()["contact"]["friction"])]
    states += [(f"mu_{mu:.2f}", out / "run" / "branches" / f"mu_{mu:.2f}", mu) for mu in args.mu]
    for name, folder, mu in states:
        metrics = knot_metrics(folder, name, mu)
        with open(folder / "steps.csv", newline="") as f:
            steps = sum(1 for _ in csv.DictReader(f))
        rows.append(dict({k: metrics[k] for k in COLUMNS if k in metrics}, state=name, friction=mu, steps=steps))
    with open(out / "friction_sweep.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, COLUMNS)
        writer.writeheader()
        writer.writerows({k: f"{v:.6g}" if isinstance(v, float) else v for k, v in row.items()} for row in rows)

    pulled, released = rows[0], rows[1:]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, label in ((axes[0], "tail_angle_deg", "tail angle [deg]"),
                           (axes[1], "loop_radius_mm", "loop radius [mm]")):
        ax.plot([r["friction"] for r in released], [r[key] for r in released], "o-", label="released")
        ax.axhline(pulled[key], color="grey", ls="--", lw=0.8,
                   label=f"before the release (end of {pulled['state']}, mu = {pulled['friction']:g})")
        ax.set_xlabel("friction coefficient mu")
        ax.set_ylabel(label)
        ax.legend(fontsize=8)
    fig.suptitle(f"Released overhand knot, {args.elements} elements: knot geometry against friction")
    fig.tight_layout()
    fig.savefig(out / "friction_sweep.png", dpi=120)
    plt.close(fig)

    for r in rows:
        print(f"{r['state']:>8}: mu = {r['friction']:g}, {r['steps']} steps, tail angle {r['tail_angle_deg']:.2f} "
              f"deg, loop radius {r['loop_radius_mm']:.4f} mm, {r['elements_in_contact']} elements in contact")
    print(f"written to {out}")
    bad = [r["state"] for r in rows if math.isnan(r["tail_angle_deg"]) or math.isnan(r["loop_radius_mm"])]
    if bad:
        print(f"friction_sweep: no knot measured in {', '.join(bad)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
