#pragma once
/// The linear solve on every MPI rank together, through PETSc's KSP and PC (solver.linear_solver: petsc).
/// Each rank hands PETSc its own contiguous range of rows of the tangent: PETSc's even split of the rows, or
/// the rows the rank assembled (`local_rows`, a distributed evaluation: docs/parallel.md). PETSc factorises
/// the distributed matrix with MUMPS (by default; SuperLU_dist or any other package through
/// `-pc_factor_mat_solver_type`), and every rank receives the whole solution, the same bits on each, so that
/// the ranks stay on one Newton path.
///
/// Options: KSPPREONLY with PCCHOLESKY (a symmetric tangent: MUMPS's LDL^T with pivoting) or PCLU, MUMPS with
/// its usual symmetric ordering (ICNTL(12) = 1), then the scenario's solver.petsc_options, then the command
/// line's `-ksp_*`, `-pc_*`, `-mat_*`, each winning over the ones before; they live in the solver's own
/// options database. With a kept factor (solver.reuse_factor, LinearSolver::solve_on_factor) the solves
/// between factorisations are PETSc's GMRES preconditioned by it, on the same distributed matrix; the KSP's
/// type is then nodus's (a `-ksp_type` applies until the first such solve). Built only with PETSc;
/// make_petsc_solver throws otherwise.

#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "nodus/solver/linear_solver.hpp"

namespace nodus::solver {

/// The rows [first, last) of the tangent this rank holds, read at every analysis; {-1, -1}: every rank
/// holds the whole tangent.
using LocalRows = std::function<std::pair<int, int>()>;

/// `symmetric`: the tangent is symmetric (Cholesky-type factorisation). `options`: solver.petsc_options.
/// `local_rows`: where the ranks' rows are (none: every rank holds the whole tangent). Starts MPI and PETSc
/// if they have not started (one process).
std::unique_ptr<LinearSolver> make_petsc_solver(bool symmetric, const std::string& options,
                                                LocalRows local_rows = {});

}  // namespace nodus::solver
