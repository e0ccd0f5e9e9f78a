#!/usr/bin/env bash
# Installs nodus's build dependencies from Debian's packages (Debian 12), if any is missing.
set -euo pipefail
packages=(g++ cmake ninja-build pkg-config libeigen3-dev libsuitesparse-dev libmetis-dev libmumps-seq-dev libyaml-cpp-dev zlib1g-dev
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libopenblas0-openmp python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pytest petsc-dev openmpi-bin
  libhdf5-dev python3-h5py)
# zlib1g-dev: the compressed arrays of the VTK files (output.vtk_format: binary).
# libmumps-seq-dev: MUMPS in one process (multifrontal LDL^T with pivoting, LU), solver.linear_solver: mumps.
# petsc-dev, openmpi-bin: runs on several MPI ranks (`mpirun -n N nodus run`, solver.linear_solver: petsc;
# docs/parallel.md); petsc-dev brings PETSc 3.18 with MUMPS, SuperLU_dist and hypre, and OpenMPI. A build
# with PETSc takes MUMPS's MPI library instead of the sequential one (cmake/FindMUMPS.cmake).
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
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
