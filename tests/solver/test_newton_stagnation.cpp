// Newton gives up a solve that makes no progress (NewtonSettings::stagnation_iterations) or too little
// (NewtonSettings::progress_window) and leaves a converging one alone; backtracking on |R|
// (NewtonSettings::backtrack_from) turns a diverging Newton into a converging one.
//
// The problem: f(x) = x^3 - 2 x + 2 = 0. From x = 0 Newton cycles between 0 and 1 for ever (f(0) = 2,
// f'(0) = -2: x = 1; f(1) = 1, f'(1) = 1: x = 0), |f| alternating 1 and 2; from x = -2 it converges to the
// real root, x = -1.76929235 (a classic example of Newton's method; the cycle follows from the formulas).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::solver {
namespace {

/// One equation f(x) = 0 in one unknown, converged at |f| <= residual_tolerance and |dx| <=
/// increment_tolerance.
class Scalar : public NonlinearProblem {
 public:
  Scalar(double x0, double residual_tolerance, double increment_tolerance)
      : x_(Eigen::VectorXd::Constant(1, x0)),
        residual_tolerance_(residual_tolerance),
        increment_tolerance_(increment_tolerance) {
    k_.resize(1, 1);
    k_.insert(0, 0) = 1.0;
    k_.makeCompressed();
  }
  virtual double f(double x) const = 0;
  virtual double df(double x) const = 0;
  int size() const override { return 1; }
  Eigen::VectorXd unknowns() const override { return x_; }
  void set_unknowns(const Eigen::VectorXd& u) override { x_ = u; }
  void evaluate(Eigen::VectorXd& r, bool /*with_tangent*/) override {
    r = Eigen::VectorXd::Constant(1, f(x_[0]));
    k_.coeffRef(0, 0) = df(x_[0]);
  }
  const SparseMatrix& tangent() const override { return k_; }
  double residual_tolerance() const override { return residual_tolerance_; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return du.lpNorm<Eigen::Infinity>(); }
  double increment_tolerance() const override { return increment_tolerance_; }

 private:
  Eigen::VectorXd x_;
  SparseMatrix k_;
  double residual_tolerance_, increment_tolerance_;
};

class Cubic final : public Scalar {
 public:
  explicit Cubic(double x0) : Scalar(x0, 1e-12, 1e-10) {}
  double f(double x) const override { return x * x * x - 2.0 * x + 2.0; }
  double df(double x) const override { return 3.0 * x * x - 2.0; }
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

// f(x) = x^10 from x = 1: Newton's x <- x - f / f' = 0.9 x, so |f| falls by 0.9^10 = 0.3487 an iteration:
// 0.1216 over two iterations, 0.0424 over three; |f| <= 1e-6 from iteration 14 on (0.3487^14 = 4.0e-7,
// 0.3487^13 = 1.1e-6).
class Power final : public Scalar {
 public:
  Power() : Scalar(1.0, 1e-6, 1.0) {}  // |dx| = 0.1 x <= 0.1: the residual decides
  double f(double x) const override { return std::pow(x, 10); }
  double df(double x) const override { return 10.0 * std::pow(x, 9); }
};

NewtonReport solve_with_progress(NonlinearProblem& problem, int window, const FixedPointUpdate& update = {}) {
  const auto linear = make_linear_solver(LinearSolverKind::umfpack);
  NewtonSettings settings;
  settings.max_iterations = 25;
  settings.progress_window = window;
  settings.progress_ratio = 0.1;
  NewtonSolver newton(*linear, settings);
  return newton.solve(problem, update);
}

TEST(NewtonProgress, GivesUpASolveWhoseResidualFallsTooSlowly) {
  Power plain, three, two;
  const NewtonReport a = solve_with_progress(plain, 0);
  ASSERT_TRUE(a.converged) << a.failure;
  EXPECT_EQ(a.iterations, 14);
  // A tenfold fall asked for over three iterations: 0.0424 a window, the same solve.
  const NewtonReport b = solve_with_progress(three, 3);
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_EQ(b.iterations, 14);
  EXPECT_DOUBLE_EQ(three.unknowns()[0], plain.unknowns()[0]);
  // Over two: 0.1216, not enough; judged once two iterations precede the window, at iteration 4.
  const NewtonReport c = solve_with_progress(two, 2);
  EXPECT_FALSE(c.converged);
  EXPECT_EQ(c.iterations, 4);
  EXPECT_NE(c.failure.find("too little progress"), std::string::npos) << c.failure;
  EXPECT_NEAR(two.unknowns()[0], std::pow(0.9, 4), 1e-14);
}

TEST(NewtonProgress, GivesUpACyclingSolveAndStartsAgainAfterAFixedPointUpdate) {
  // |f| = 1, 2, 1, 2, ...: no fall at all; a window of 5 with two iterations before it: iteration 7.
  Cubic cycling(0.0);
  NewtonReport report = solve_with_progress(cycling, 5);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 7);
  EXPECT_NE(report.failure.find("smallest |R| 1.000e+00 in the last 5 iterations, 1.000e+00 before them"),
            std::string::npos)
      << report.failure;
  // A fixed-point update that changes the problem at iteration 6 starts the count again: 6 + 7.
  Cubic updated(0.0);
  report = solve_with_progress(updated, 5, [](const NewtonProgress& p) { return p.iteration == 6; });
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 13);
}

// f(x) = atan(x): Newton x <- x - (1 + x^2) atan(x) overshoots the root 0 from |x| > 1.3917 and diverges,
// |x| growing at every iteration (from 2: -3.5357, 13.951, -279.34, ...). |f| has its only minimum at the
// root, so a step halved until |f| falls converges there.
class Atan final : public Scalar {
 public:
  explicit Atan(double x0) : Scalar(x0, 1e-12, 1e-10) {}
  double f(double x) const override { return std::atan(x); }
  double df(double x) const override { return 1.0 / (1.0 + x * x); }
};

/// Solves `problem` with backtracking from iteration `from` (0: none); `norms` gets |R| after each iteration.
NewtonReport solve_with_backtracking(NonlinearProblem& problem, int from, std::vector<double>& norms) {
  const auto linear = make_linear_solver(LinearSolverKind::umfpack);
  NewtonSettings settings;
  settings.max_iterations = 25;
  settings.backtrack_from = from;
  NewtonSolver newton(*linear, settings);
  norms.clear();
  return newton.solve(problem, [&norms](const NewtonProgress& p) {
    norms.push_back(p.residual);
    return false;
  });
}

TEST(NewtonBacktracking, TurnsADivergingSolveIntoAConvergingOne) {
  std::vector<double> norms;
  Atan plain(2.0);
  EXPECT_FALSE(solve_with_backtracking(plain, 0, norms).converged);
  Atan from_first(2.0);
  NewtonReport report = solve_with_backtracking(from_first, 1, norms);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_NEAR(from_first.unknowns()[0], 0.0, 1e-12);
  for (std::size_t k = 1; k < norms.size(); ++k) EXPECT_LE(norms[k], norms[k - 1]) << "iteration " << k + 1;
  // From the third iteration on: the first two are Newton's full steps.
  Atan from_third(2.0);
  report = solve_with_backtracking(from_third, 3, norms);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_NEAR(from_third.unknowns()[0], 0.0, 1e-12);
  const double x1 = 2.0 - 5.0 * std::atan(2.0);
  const double x2 = x1 - (1.0 + x1 * x1) * std::atan(x1);
  ASSERT_GE(norms.size(), 3u);
  EXPECT_NEAR(norms[0], std::abs(std::atan(x1)), 1e-14);
  EXPECT_NEAR(norms[1], std::abs(std::atan(x2)), 1e-14);
  EXPECT_GT(norms[1], norms[0]);  // the full step raised |R|
  for (std::size_t k = 2; k < norms.size(); ++k) EXPECT_LE(norms[k], norms[k - 1]) << "iteration " << k + 1;
}

TEST(NewtonBacktracking, LeavesAConvergingSolveAlone) {
  // From -2 Newton's full steps reduce |f| at every iteration: no step is shortened.
  std::vector<double> norms;
  Cubic plain(-2.0), backtracked(-2.0);
  const NewtonReport a = solve_with_backtracking(plain, 0, norms);
  const NewtonReport b = solve_with_backtracking(backtracked, 1, norms);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(plain.unknowns()[0], backtracked.unknowns()[0]);
}

}  // namespace
}  // namespace nodus::solver
