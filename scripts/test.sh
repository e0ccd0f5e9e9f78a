#!/usr/bin/env bash
# Quick start, second command: installs what is missing, builds and runs the tests twice: Release, then Debug
# at -O1 with AddressSanitizer on everything and UndefinedBehaviorSanitizer on nodus's library and program
# (without the tests labelled `long`, the knot runs, which would take tens of minutes under the sanitizers;
# their code paths are covered by the shorter tests; and without PETSc: OpenMPI's own allocations would read
# as leaks, and the MPI runs are checked in the Release pass). Tests labelled `slow` (the Python
# friction-sweep example and the 3x1 knot as the example has it, minutes) are left out of both:
# `ctest --test-dir build/release -L slow` runs them; the Release pass runs a coarse variant of the 3x1 knot
# (about 4 minutes on one core, beside the other tests).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc)
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DNODUS_BUILD_TESTS=ON -DNODUS_BUILD_BENCHMARKS=OFF \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null  # Debian's, with the numpy and pytest of setup.sh
cmake --build build/release -j "$jobs"
ctest --test-dir build/release --output-on-failure --no-tests=error -j "$jobs" -LE slow
cmake -S . -B build/debug-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DNODUS_SANITIZE=ON -DNODUS_BUILD_TESTS=ON -DNODUS_BUILD_BENCHMARKS=OFF \
  -DNODUS_WITH_PETSC=OFF >/dev/null
cmake --build build/debug-sanitize -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/debug-sanitize --output-on-failure --no-tests=error -j "$jobs" -LE long
