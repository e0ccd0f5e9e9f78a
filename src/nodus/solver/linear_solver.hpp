#pragma once
/// Sparse direct solvers behind one interface. The pattern is analysed once (fill-reducing ordering) and each
/// Newton iteration only refactorises numerically.

#include <memory>
#include <string>

#include <Eigen/Core>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::solver {

/// What a solve on a kept factor (LinearSolver::solve_on_factor) did.
struct KrylovSolve {
  bool accepted = false;  ///< |a x - b| <= tolerance |b| was reached
  int iterations = 0;     ///< Krylov iterations taken
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Symbolic analysis of the pattern of `a`; must be called again when the pattern changes.
  virtual void analyze(const SparseMatrix& a) = 0;
  /// Numerical factorisation; returns false if the matrix is singular to working precision.
  virtual bool factorize(const SparseMatrix& a) = 0;
  /// Solves a x = b with the last factorisation.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  virtual std::string name() const = 0;
  /// The library that factorises, with its version ("MUMPS 5.5.1"), for the records of a run.
  virtual std::string package() const = 0;
  /// Solves a x = b by GMRES (restarted after `max_iterations`, so at most that many), preconditioned by the
  /// last factorisation, which may be of an earlier matrix and pattern of the same size. The result is
  /// accepted on the true residual. `new_pattern`: the pattern of `a` is not the one handed to this solver
  /// last (by analyze() or by this call). By default Eigen's GMRES with solve() as the preconditioner on the
  /// whole matrix; the PETSc solver runs PETSc's GMRES on the ranks' rows instead.
  virtual KrylovSolve solve_on_factor(const SparseMatrix& a, bool new_pattern, const Eigen::VectorXd& b,
                                      double tolerance, int max_iterations, Eigen::VectorXd& x);
  /// Whether analyze() reads the values as well as the pattern: then two analyses of one pattern may differ,
  /// and a run that must repeat itself exactly (resumed from a checkpoint) has to analyse at the same points.
  virtual bool analysis_reads_values() const { return true; }
};

enum class LinearSolverKind {
  cholmod,  ///< CHOLMOD supernodal LL^T (METIS ordering), falling back to MUMPS's LDL^T with pivoting when
            ///< the matrix is not positive definite (buckled states)
  cholmod_ldlt,  ///< CHOLMOD simplicial LDL^T only (no pivoting), for comparison
  umfpack,       ///< UMFPACK LU with partial pivoting
  mumps_ldlt,    ///< MUMPS multifrontal LDL^T with pivoting (symmetric, definite or not); reads one triangle
  mumps_lu,      ///< MUMPS multifrontal LU (any matrix)
  klu,  ///< KLU sparse LU with partial pivoting, the pivots kept across factorisations while they serve
};

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind);

}  // namespace nodus::solver
