// Newton gives up a solve that makes no progress (NewtonSettings::stagnation_iterations) and leaves a
// converging one alone.
//
// The problem: f(x) = x^3 - 2 x + 2 = 0. From x = 0 Newton cycles between 0 and 1 for ever (f(0) = 2,
// f'(0) = -2: x = 1; f(1) = 1, f'(1) = 1: x = 0), |f| alternating 1 and 2; from x = -2 it converges to the
// real root, x = -1.76929235 (a classic example of Newton's method; the cycle follows from the formulas).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::solver {
namespace {

class Cubic final : public NonlinearProblem {
 public:
  explicit Cubic(double x0) : x_(1) {
    x_[0] = x0;
    k_.resize(1, 1);
    k_.insert(0, 0) = 1.0;
    k_.makeCompressed();
  }
  int size() const override { return 1; }
  Eigen::VectorXd unknowns() const override { return x_; }
  void set_unknowns(const Eigen::VectorXd& u) override { x_ = u; }
  void evaluate(Eigen::VectorXd& r, bool /*with_tangent*/) override {
    const double x = x_[0];
    r.resize(1);
    r[0] = x * x * x - 2.0 * x + 2.0;
    k_.coeffRef(0, 0) = 3.0 * x * x - 2.0;
  }
  const SparseMatrix& tangent() const override { return k_; }
  double residual_tolerance() const override { return 1e-12; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return du.lpNorm<Eigen::Infinity>(); }
  double increment_tolerance() const override { return 1e-10; }

 private:
  Eigen::VectorXd x_;
  SparseMatrix k_;
};

NewtonReport solve_cubic(double x0, int stagnation, Cubic& problem) {
  const auto linear = make_linear_solver(LinearSolverKind::umfpack);
  NewtonSettings settings;
  settings.max_iterations = 25;
  settings.stagnation_iterations = stagnation;
  NewtonSolver newton(*linear, settings);
  problem = Cubic(x0);
  return newton.solve(problem);
}

TEST(NewtonStagnation, GivesUpACyclingSolveOnceItStopsImproving) {
  Cubic problem(0.0);
  // Without the rule: the whole 25 iterations, still on the cycle.
  NewtonReport report = solve_cubic(0.0, 0, problem);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 25);
  EXPECT_NE(report.failure.find("no convergence in 25 iterations"), std::string::npos) << report.failure;
  // With 5: the smallest |f| (1, at x = 1) comes at iteration 1 and is never beaten, so the solve stops at
  // iteration 1 + 5.
  report = solve_cubic(0.0, 5, problem);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 6);
  EXPECT_NE(report.failure.find("no progress in 5 iterations"), std::string::npos) << report.failure;
  EXPECT_NE(report.failure.find("smallest 1.000e+00 at iteration 1"), std::string::npos) << report.failure;
}

TEST(NewtonStagnation, LeavesAConvergingSolveAlone) {
  Cubic without(-2.0), with(-2.0);
  const NewtonReport a = solve_cubic(-2.0, 0, without);
  const NewtonReport b = solve_cubic(-2.0, 1, with);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_NEAR(with.unknowns()[0], -1.76929235423863, 1e-12);
}

}  // namespace
}  // namespace nodus::solver
