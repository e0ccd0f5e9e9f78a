#pragma once
/// What the nonlinear solver needs from the physics: a residual and its tangent over the free unknowns.
/// The solver knows nothing else of the problem.

#include <cstdint>

#include <Eigen/Core>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::solver {

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  /// Number of free unknowns.
  virtual int size() const = 0;
  /// The current free unknowns.
  virtual Eigen::VectorXd unknowns() const = 0;
  virtual void set_unknowns(const Eigen::VectorXd& u) = 0;
  /// The unknowns reached from `u` by the Newton increment `du`: u + du, or a better update of the problem's
  /// own that equals it to first order in du (a finite rotation of the beams' section directors).
  virtual Eigen::VectorXd step(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const { return u + du; }
  /// Residual (out-of-balance force) at the current unknowns, and the tangent d residual / d u if asked.
  virtual void evaluate(Eigen::VectorXd& residual, bool with_tangent) = 0;
  /// The tangent of the last evaluate(..., true). Its pattern stays the same between calls unless
  /// pattern_changed() says otherwise.
  virtual const SparseMatrix& tangent() const = 0;
  /// A number that changes whenever the tangent's pattern changes, so that a solver re-analyses it then (0:
  /// not tracked; the caller tells the solver, NewtonSolver::reanalyze).
  virtual std::uint64_t pattern_version() const { return 0; }
  /// Residual norm at which the state is in equilibrium (absolute, in the residual's units), from the last
  /// evaluation.
  virtual double residual_tolerance() const = 0;
  /// Size of an increment of the unknowns, dimensionless (each unknown divided by its own scale), to be
  /// compared with increment_tolerance().
  virtual double scaled_increment(const Eigen::VectorXd& du) const = 0;
  /// Scaled increment below which the state has stopped moving.
  virtual double increment_tolerance() const = 0;
};

}  // namespace nodus::solver
