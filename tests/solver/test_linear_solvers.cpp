// The sparse direct solvers agree with a dense reference on a positive definite and on an indefinite matrix
// (CHOLMOD falls back from LL^T to LDL^T; MUMPS pivots), the LU solvers also on an unsymmetric one, and
// Newton converges quadratically on a small nonlinear problem, also with its factor kept across iterations
// (GMRES on it) and with a fixed point solved inside it.

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::solver {
namespace {

SparseMatrix banded(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
    if (i + 5 < n) {
      t.emplace_back(i, i + 5, -0.5);
      t.emplace_back(i + 5, i, -0.5);
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

class LinearSolvers : public ::testing::TestWithParam<LinearSolverKind> {};

TEST_P(LinearSolvers, MatchDenseSolution) {
  for (double shift : {0.0, -4.3}) {  // positive definite, then indefinite
    const SparseMatrix a = banded(60, shift);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(60, -1.0, 2.0);
    const Eigen::VectorXd reference = Eigen::MatrixXd(a).fullPivLu().solve(b);
    auto solver = make_linear_solver(GetParam());
    solver->analyze(a);
    ASSERT_TRUE(solver->factorize(a)) << solver->name() << " shift " << shift;
    EXPECT_LT((solver->solve(b) - reference).norm(), 1e-10 * reference.norm())
        << solver->name() << " " << shift;
  }
}

TEST_P(LinearSolvers, RefactoriseNewValuesOnOneAnalysis) {
  // One analysis, then the values of a positive definite and of an indefinite matrix of the same pattern:
  // what a Newton run does between two contact detections.
  auto solver = make_linear_solver(GetParam());
  solver->analyze(banded(60, 0.0));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(60, 1.0, -3.0);
  for (double shift : {0.0, -4.3, 1.5}) {
    const SparseMatrix a = banded(60, shift);
    const Eigen::VectorXd reference = Eigen::MatrixXd(a).fullPivLu().solve(b);
    ASSERT_TRUE(solver->factorize(a)) << solver->name() << " shift " << shift;
    EXPECT_LT((solver->solve(b) - reference).norm(), 1e-10 * reference.norm())
        << solver->name() << " " << shift;
  }
}

// Every unknown coupled to every other, as in a model of one beam element (18 free unknowns): MUMPS's PORD
// ordering finds no separator there and ended the process ("no valid number of stages in multisector"), also
// through CHOLMOD's fallback for indefinite tangents.
TEST_P(LinearSolvers, SolveAMatrixWithoutZeros) {
  for (double shift : {0.0, -19.5}) {  // positive definite, then indefinite
    Eigen::MatrixXd dense = Eigen::MatrixXd::Constant(18, 18, -0.5);
    dense.diagonal().array() = 10.0 + shift;
    const SparseMatrix a = dense.sparseView();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(18, -1.0, 2.0);
    const Eigen::VectorXd reference = dense.fullPivLu().solve(b);
    auto solver = make_linear_solver(GetParam());
    solver->analyze(a);
    ASSERT_TRUE(solver->factorize(a)) << solver->name() << " shift " << shift;
    EXPECT_LT((solver->solve(b) - reference).norm(), 1e-10 * reference.norm())
        << solver->name() << " " << shift;
  }
}

INSTANTIATE_TEST_SUITE_P(All, LinearSolvers,
                         ::testing::Values(LinearSolverKind::cholmod, LinearSolverKind::cholmod_ldlt,
                                           LinearSolverKind::umfpack, LinearSolverKind::mumps_ldlt,
                                           LinearSolverKind::mumps_lu, LinearSolverKind::klu));

/// The LU solvers on a matrix that is not symmetric (the friction tangent with R_N varying is not), then on a
/// singular one, which they must report rather than solve.
class LuSolvers : public ::testing::TestWithParam<LinearSolverKind> {};

TEST_P(LuSolvers, SolveUnsymmetricAndReportSingular) {
  SparseMatrix a = banded(50, -2.0);
  for (int i = 0; i + 3 < 50; ++i) a.coeffRef(i, i + 3) += 0.7;  // an upper entry with no lower twin
  a.makeCompressed();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(50, -2.0, 1.0);
  const Eigen::VectorXd reference = Eigen::MatrixXd(a).fullPivLu().solve(b);
  auto solver = make_linear_solver(GetParam());
  solver->analyze(a);
  ASSERT_TRUE(solver->factorize(a)) << solver->name();
  EXPECT_LT((solver->solve(b) - reference).norm(), 1e-10 * reference.norm()) << solver->name();

  SparseMatrix singular = a;  // row 7 and its column emptied of values (the pattern stays)
  for (int k = 0; k < singular.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(singular, k); it; ++it)
      if (it.row() == 7 || it.col() == 7) it.valueRef() = 0.0;
  EXPECT_FALSE(solver->factorize(singular)) << solver->name();
}

INSTANTIATE_TEST_SUITE_P(All, LuSolvers,
                         ::testing::Values(LinearSolverKind::umfpack, LinearSolverKind::mumps_lu,
                                           LinearSolverKind::klu));

// KLU keeps the pivot sequence of its first factorisation after an analysis. Matrices of one pattern that
// need other pivots: in the first's order the first pivot of the second is 1e-14 (a solve with an error of
// 1e-3 without a new choice), that of the third 0. All are solved to round-off all the same.
TEST(Klu, ChoosesNewPivotsWhereTheKeptOnesNoLongerServe) {
  const auto matrix = [](double a00, double a10) {
    SparseMatrix a(3, 3);
    const std::vector<Eigen::Triplet<double>> t = {{0, 0, a00}, {1, 0, a10}, {0, 1, 1.0}, {1, 1, 1.0},
                                                   {2, 1, 1.0}, {1, 2, 2.0}, {2, 2, 3.0}};
    a.setFromTriplets(t.begin(), t.end());
    return a;
  };
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, -2.0, 0.5);
  auto solver = make_linear_solver(LinearSolverKind::klu);
  solver->analyze(matrix(5.0, 1e-3));  // the first pivot on the diagonal
  for (const SparseMatrix& a : {matrix(5.0, 1e-3), matrix(1e-14, 1.0), matrix(5.0, 1e-3), matrix(0.0, 1.0)}) {
    ASSERT_TRUE(solver->factorize(a));
    const Eigen::VectorXd x = solver->solve(b);
    const Eigen::VectorXd reference = Eigen::MatrixXd(a).fullPivLu().solve(b);
    EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm()) << Eigen::MatrixXd(a);
  }
}

/// R(u) = A u + u^3 - b (componentwise cube): a smooth problem with a known Jacobian.
class CubicProblem final : public NonlinearProblem {
 public:
  explicit CubicProblem(int n)
      : a_(banded(n, 0.0)), b_(Eigen::VectorXd::Constant(n, 3.0)), u_(Eigen::VectorXd::Zero(n)) {}
  int size() const override { return static_cast<int>(u_.size()); }
  Eigen::VectorXd unknowns() const override { return u_; }
  void set_unknowns(const Eigen::VectorXd& u) override { u_ = u; }
  void evaluate(Eigen::VectorXd& r, bool with_tangent) override {
    r = a_ * u_ + u_.array().cube().matrix() - b_;
    if (with_tangent) {
      k_ = a_;
      for (int i = 0; i < size(); ++i) k_.coeffRef(i, i) += 3 * u_[i] * u_[i];
    }
    history.push_back(r.norm());
  }
  const SparseMatrix& tangent() const override { return k_; }
  /// b = `load` in every component.
  void set_load(double load) { b_.setConstant(load); }
  double residual_tolerance() const override { return 1e-12; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return du.lpNorm<Eigen::Infinity>(); }
  double increment_tolerance() const override { return 1e-10; }
  std::vector<double> history;

 private:
  SparseMatrix a_, k_;
  Eigen::VectorXd b_, u_;
};

TEST(Newton, ConvergesQuadratically) {
  for (bool line_search : {false, true}) {
    CubicProblem p(40);
    auto linear = make_linear_solver(LinearSolverKind::cholmod);
    NewtonSettings settings;
    settings.line_search = line_search;
    NewtonSolver newton(*linear, settings);
    const NewtonReport report = newton.solve(p);
    ASSERT_TRUE(report.converged) << report.failure;
    EXPECT_LE(report.iterations, 8);
    EXPECT_LE(report.residual, 1e-12);
  }
}

TEST(Newton, ALooseResidualEndsTheSolveEarlier) {
  CubicProblem exact(40), loose(40);
  auto linear = make_linear_solver(LinearSolverKind::cholmod);
  const NewtonReport full = NewtonSolver(*linear, NewtonSettings{}).solve(exact);
  ASSERT_TRUE(full.converged) << full.failure;
  const NewtonReport report = NewtonSolver(*linear, NewtonSettings{}).solve(loose, {}, 1e-3);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LE(report.residual, 1e-3);
  EXPECT_GT(report.residual, 1e-12);  // short of the tolerance: the solve stopped at the loose residual
  EXPECT_LT(report.iterations, full.iterations);
}

TEST(Newton, KeptFactorWithGmresSolvesTheSameProblem) {
  CubicProblem exact(40), lagged(40);
  auto linear = make_linear_solver(LinearSolverKind::cholmod);
  const NewtonReport reference = NewtonSolver(*linear, NewtonSettings{}).solve(exact);
  ASSERT_TRUE(reference.converged) << reference.failure;
  NewtonSettings settings;
  settings.reuse_factor = true;
  settings.krylov_tolerance = 1e-8;
  NewtonSolver newton(*linear, settings);
  const NewtonReport report = newton.solve(lagged);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LE(report.residual, 1e-12);
  // GMRES on the first iteration's factor carried the later iterations: fewer factorisations than iterations.
  EXPECT_LT(newton.timings().factorizations, report.iterations);
  EXPECT_GT(newton.timings().krylov_iterations, 0);
  EXPECT_LT((lagged.unknowns() - exact.unknowns()).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(Newton, FixedPointInsideNewtonEndsWhereTheUpdateChangesNothing) {
  // R(u) = A u + u^3 - b(p), with b = 3 + p and p = mean(u) / 2 a fixed point updated between iterations.
  CubicProblem p(40);
  auto linear = make_linear_solver(LinearSolverKind::cholmod);
  NewtonSolver newton(*linear, NewtonSettings{});
  double load = 0.0;  // p
  int updates = 0;
  bool last_converged = false;
  const FixedPointUpdate update = [&](const NewtonProgress& progress) {
    last_converged = progress.converged;
    const double next = 0.5 * p.unknowns().mean();
    if (std::abs(next - load) <= 1e-13) return false;
    load = next;
    p.set_load(3.0 + load);
    ++updates;
    return true;
  };
  const NewtonReport report = newton.solve(p, update);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_GT(updates, 1);
  EXPECT_TRUE(last_converged);  // the solve ended on an update at a converged state
  // The end state solves the coupled problem: p is the fixed point, and R(u) = 0 with it.
  const Eigen::VectorXd u = p.unknowns();
  EXPECT_NEAR(load, 0.5 * u.mean(), 1e-13);
  const Eigen::VectorXd r =
      banded(40, 0.0) * u + u.array().cube().matrix() - Eigen::VectorXd::Constant(40, 3.0 + 0.5 * u.mean());
  EXPECT_LT(r.norm(), 1e-11);
}

}  // namespace
}  // namespace nodus::solver
