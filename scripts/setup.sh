#!/usr/bin/env bash
# Installs nodus's build dependencies from Debian's packages (Debian 12), if any is missing.
set -euo pipefail
packages=(g++ cmake ninja-build pkg-config libeigen3-dev libsuitesparse-dev libmetis-dev libmumps-seq-dev libyaml-cpp-dev zlib1g-dev
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libopenblas0-openmp python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pytest petsc-dev openmpi-bin
  libhdf5-dev python3-h5py
  nodejs npm chromium)
# zlib1g-dev: the compressed arrays of the VTK files (output.vtk_format: binary).
# libmumps-seq-dev: MUMPS in one process (multifrontal LDL^T with pivoting, LU), solver.linear_solver: mumps.
# petsc-dev, openmpi-bin: runs on several MPI ranks (`mpirun -n N nodus run`, solver.linear_solver: petsc;
# docs/parallel.md); petsc-dev brings PETSc 3.18 with MUMPS, SuperLU_dist and hypre, and OpenMPI. A build
# with PETSc takes MUMPS's MPI library instead of the sequential one (cmake/FindMUMPS.cmake).
# nodejs, npm, chromium: `nodus view`'s page, bundled from web/ (npm ci below), tested in headless Chromium.
# libhdf5-dev, python3-h5py: result.h5, every output state of a run in one HDF5 file, and its Python reader
# (the serial HDF5 library; petsc-dev's OpenMPI one is not used by nodus).
# python3-dev, pybind11-dev: the Python module (python/); python3-pytest runs its tests.
# python3-numpy, python3-matplotlib: the module's arrays, the knot example's loading program and report
# (scripts/knot_*.py) and the Python examples.
# libopenblas0-openmp: CHOLMOD's supernodal factorisation runs on the system BLAS; Debian's default
# (netlib) is 4.6x slower on the contact tangent of a 27-fibre bundle (docs/performance.md). The OpenMP
# build shares its threads with nodus's OpenMP regions instead of a second pool competing for the cores.
missing=()
for p in "${packages[@]}"; do
  # A Node.js of one's own (NodeSource's, which provides npm and conflicts with Debian's) stands for Debian's.
  case "$p" in nodejs | npm) command -v "${p/nodejs/node}" >/dev/null && continue ;; esac
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The viewer's JavaScript packages (three.js, esbuild, playwright-core; web/package-lock.json), from the npm
# registry, into web/node_modules: the build bundles `nodus view`'s page from them (cmake/viewer.cmake). Again
# when the lock file is newer than what npm installed (other pinned versions). playwright-core, used by the
# browser test, never downloads a browser: the test drives Debian's chromium.
web="$(dirname "$0")/../web"
if [ ! -d "$web/node_modules" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in web/" >&2
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "setup: npm ci in web/ failed (no access to the npm registry?): nodus builds without the page of" \
      "nodus view, and its browser test is left out" >&2
fi
