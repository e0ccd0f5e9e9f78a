"""Compares two runs of nodus from their result.h5 files: the contact force step by step, and how far apart
the last states' centrelines are.

Sample run (a scenario with branches, e.g. tests/python/conftest.py's DRAG_WITH_BRANCHES, or two runs of one
scenario with different settings):

    nodus run scenario.yaml --out out/run
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/compare_runs.py \
        out/run/branches/same out/run/branches/mu_0.1
"""

import sys

import numpy as np

import nodus.results

a, b = (nodus.results.open(folder) for folder in sys.argv[1:3])
print(f"{'step':>6} {'time [s]':>10} {'normal force A [N]':>20} {'normal force B [N]':>20}")
for step in sorted(set(a.steps["step"]) & set(b.steps["step"])):
    i, j = np.flatnonzero(a.steps["step"] == step)[0], np.flatnonzero(b.steps["step"] == step)[0]
    print(f"{step:>6} {a.steps['time'][i]:>10.4g} {a.steps['normal_force'][i]:>20.6g} "
          f"{b.steps['normal_force'][j]:>20.6g}")
gap = np.linalg.norm(a.states[-1].centre - b.states[-1].centre, axis=1)
print(f"last states (steps {a.states[-1].step} and {b.states[-1].step}): centres apart by {gap.max():.4g} mm "
      f"at most, {gap.mean():.4g} mm on average")
