#!/usr/bin/env bash
# Quick start, first command: installs what is missing, builds nodus (Release) and runs the flagship example.
# Usage: scripts/example.sh [SCENARIO.yaml [OUT_DIR]]
set -euo pipefail
cd "$(dirname "$0")/.."
scenario=${1:-examples/cantilever_roll_up.yaml}
out=${2:-results/$(basename "$scenario" .yaml)}
scripts/setup.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DNODUS_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build/release --target nodus
build/release/nodus run "$scenario" --out "$out"
echo "results: $out (summary.json, steps.csv, final_nodes.csv; open $out/result.pvd in ParaView)"
