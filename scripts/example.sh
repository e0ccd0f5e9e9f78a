#!/usr/bin/env bash
# Quick start, first command: installs what is missing, builds nodus (Release) and runs the flagship example,
# the monofilament overhand knot of Durville (2012), Sect. 7.2: formed, tightened and released for three
# friction coefficients, then reported (CSV tables and PNG figures, scripts/knot_report.py).
# Usage: scripts/example.sh [SCENARIO.yaml [OUT_DIR]]
set -euo pipefail
cd "$(dirname "$0")/.."
scenario=${1:-examples/monofilament_knot.yaml}
out=${2:-results/$(basename "$scenario" .yaml)}
scripts/setup.sh
# Debian's python3, for which setup.sh installed numpy and matplotlib (the report below runs with it).
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DNODUS_BUILD_BENCHMARKS=OFF \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build/release --target nodus nodus_python  # the report's knot metrics come from the module
# The time left in the progress lines: from the timing of a run kept in examples/timing/ unless an earlier run
# into "$out" left its own (docs/output.md, "Progress lines").
timing=examples/timing/$(basename "$scenario" .yaml)
timing_from=()
if [ ! -f "$out/timing.csv" ] && [ -f "$timing/timing.csv" ]; then timing_from=(--timing-from "$timing"); fi
# OpenBLAS's kernels for this processor where Debian's OpenBLAS is older than the processor and took its
# generic ones (`nodus kernels`; docs/performance.md, "Threads on a 16-core machine"): where the 3x1 knot
# forms, its MUMPS factorisations run about a quarter faster. The flagship factorises with KLU (no BLAS).
if [ -z "${OPENBLAS_CORETYPE:-}" ]; then
  coretype=$(build/release/nodus kernels --coretype)
  if [ -n "$coretype" ]; then export OPENBLAS_CORETYPE=$coretype; fi
fi
build/release/nodus run "$scenario" --out "$out" "${timing_from[@]}"
if [ "$(basename "$scenario" .yaml)" = monofilament_knot ]; then
  # Debian's python3 (with python3-numpy and python3-matplotlib from scripts/setup.sh).
  PYTHONPATH=build/release/python /usr/bin/python3 scripts/knot_report.py "$out"
  echo "report: $out/report (knot_report.csv, reactions_*.csv, fig12/14/15/17 PNG files)"
elif [ "$(basename "$scenario" .yaml)" = knot_3x1 ]; then
  PYTHONPATH=build/release/python /usr/bin/python3 scripts/knot_3x1_report.py "$out"
  echo "report: $out/report (knot_3x1_report.csv, reactions_*.csv, fig19/20/21 and view3d_* PNG files)"
fi
echo "results: $out (summary.json, steps.csv, final_nodes.csv, stages/, branches/; open $out/result.pvd in ParaView)"
