#!/usr/bin/env python3
"""How the progress lines' estimate of the time left tracked the truth (docs/performance.md).

Usage: bench/remaining_time_accuracy.py LOG
LOG: the stderr of `nodus run SCENARIO --out DIR` with `output.progress_seconds: 0` (a line per step). For the
main run and each branch (lines labelled `branch NAME: `), the true time left at each line is the elapsed time
of that run's last line minus the line's own; the estimate is the line's `remaining ~X s`. Prints, per run,
the ratio estimate / truth over the lines after 20 %, 50 % and 80 % of the run's load time (worst of each),
and the last line where the ratio is outside [1/2, 2] while more than 20 % is done. Lines whose truth is
below 5 % of the run's wall time (or 1 s) are left out: there the printed estimate's rounding and the
last steps' cost decide the ratio.
"""
import re
import sys

LINE = re.compile(r"\] (?:branch (?P<branch>\S+): )?stage (?P<stage>\S+) \(\d+/\d+\), step (?P<step>\d+), "
                  r"load time (?P<t>\S+) / (?P<end>\S+), .* elapsed (?P<elapsed>\S+) s, remaining ~(?P<left>\S+) s")


def main(path):
    runs = {}
    for line in open(path, encoding="utf-8", errors="replace"):
        m = LINE.search(line)
        if m:
            left = float("nan") if m["left"] == "?" else float(m["left"])
            runs.setdefault(m["branch"] or "main", []).append(
                (float(m["t"]), float(m["end"]), float(m["elapsed"]), left, m["stage"], int(m["step"])))
    for name, lines in runs.items():
        t0 = lines[0][0] if name == "main" else None
        if t0 is None:  # a branch starts at its `from` stage's end: the load time before its first step
            t0 = lines[0][0] - (lines[1][0] - lines[0][0]) if len(lines) > 1 else lines[0][0]
        t0 = 0.0 if name == "main" else t0
        end, total = lines[-1][1], lines[-1][2]
        worst = {0.2: (1.0, 1.0), 0.5: (1.0, 1.0), 0.8: (1.0, 1.0)}
        outside = None
        for t, _, elapsed, left, stage, step in lines:
            truth = total - elapsed
            done = (t - t0) / (end - t0)
            if truth < max(1.0, 0.05 * total) or left != left:  # the run's last 5 %: see the docstring
                continue
            ratio = left / truth
            for f in worst:
                if done >= f:
                    lo, hi = worst[f]
                    worst[f] = (min(lo, ratio), max(hi, ratio))
            if done >= 0.2 and not 0.5 <= ratio <= 2.0:
                outside = (step, stage, round(done, 3), left, round(truth, 1))
        print(f"{name}: {len(lines)} lines, {total:.1f} s; estimate / truth after 20 % of load time "
              f"{worst[0.2][0]:.2f} .. {worst[0.2][1]:.2f}, after 50 % {worst[0.5][0]:.2f} .. {worst[0.5][1]:.2f}, "
              f"after 80 % {worst[0.8][0]:.2f} .. {worst[0.8][1]:.2f}; last outside [1/2, 2] after 20 %: {outside}")


if __name__ == "__main__":
    main(sys.argv[1])
