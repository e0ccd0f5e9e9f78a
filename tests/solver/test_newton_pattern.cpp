// Newton analyses the tangent's pattern again exactly when the problem says that it changed
// (NonlinearProblem::pattern_version), or when told to (reanalyze), and only then: a detection that finds the
// same couplings keeps the analysis (EquilibriumProblem::rebuild_pattern).
//
// The problem: a linear 3x3 system K u = f whose pattern has the corner entries (0, 2) and (2, 0), as
// explicit zeros, or not, so that the two patterns differ while the solution stays the same. Newton solves it
// in one iteration; each solve is checked against the exact solution.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::solver {
namespace {

/// K u = f, K tridiagonal (2 on the diagonal, -1 beside it), with the entries (0, 2) and (2, 0) in the
/// pattern (as explicit zeros) or not.
class Linear final : public NonlinearProblem {
 public:
  Linear() { build(false); }

  /// Changes the pattern (and its version) to the one with or without the corner entries.
  void set_corners(bool corners) {
    build(corners);
    ++version_;
  }
  /// Changes the version alone, as a problem that rebuilt the same pattern but does not compare.
  void bump_version() { ++version_; }

  int size() const override { return 3; }
  Eigen::VectorXd unknowns() const override { return u_; }
  void set_unknowns(const Eigen::VectorXd& u) override { u_ = u; }
  void evaluate(Eigen::VectorXd& r, bool /*with_tangent*/) override { r = k_ * u_ - f_; }
  const SparseMatrix& tangent() const override { return k_; }
  std::uint64_t pattern_version() const override { return version_; }
  double residual_tolerance() const override { return 1e-12; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return du.lpNorm<Eigen::Infinity>(); }
  double increment_tolerance() const override { return 1e-12; }

  Eigen::VectorXd exact() const { return Eigen::Vector3d(1.5, 2.0, 1.5); }  // K^-1 f for f = (1, 1, 1)

 private:
  void build(bool corners) {
    k_ = SparseMatrix(3, 3);
    for (int i = 0; i < 3; ++i) {
      k_.insert(i, i) = 2.0;
      if (i > 0) k_.insert(i, i - 1) = -1.0;
      if (i < 2) k_.insert(i, i + 1) = -1.0;
    }
    if (corners) {
      k_.insert(0, 2) = 0.0;
      k_.insert(2, 0) = 0.0;
    }
    k_.makeCompressed();
  }

  SparseMatrix k_;
  Eigen::VectorXd u_ = Eigen::VectorXd::Zero(3);
  Eigen::VectorXd f_ = Eigen::VectorXd::Ones(3);
  std::uint64_t version_ = 1;
};

/// A real solver that counts its analyses.
class CountingSolver final : public LinearSolver {
 public:
  explicit CountingSolver(LinearSolverKind kind = LinearSolverKind::umfpack)
      : inner_(make_linear_solver(kind)) {}
  void analyze(const SparseMatrix& a) override {
    ++analyses;
    inner_->analyze(a);
  }
  bool factorize(const SparseMatrix& a) override { return inner_->factorize(a); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override { return inner_->solve(b); }
  std::string name() const override { return "counting " + inner_->name(); }
  std::string package() const override { return inner_->package(); }
  bool analysis_reads_values() const override { return inner_->analysis_reads_values(); }

  int analyses = 0;

 private:
  std::unique_ptr<LinearSolver> inner_;
};

void solve_from_zero(NewtonSolver& newton, Linear& problem) {
  problem.set_unknowns(Eigen::VectorXd::Zero(3));
  const NewtonReport report = newton.solve(problem);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LT((problem.unknowns() - problem.exact()).norm(), 1e-12);
}

TEST(NewtonPattern, AnalysesAgainExactlyWhenThePatternVersionChanges) {
  Linear problem;
  CountingSolver linear;
  NewtonSolver newton(linear, NewtonSettings{});

  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 1);
  solve_from_zero(newton, problem);  // same pattern: the analysis serves
  EXPECT_EQ(linear.analyses, 1);

  problem.set_corners(true);  // more entries: an analysis of the old pattern would not fit the matrix
  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 2);

  problem.set_corners(false);  // back (a failed step attempt restored): analysed again, not taken as known
  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 3);

  problem.bump_version();  // a new version is analysed even if the pattern happens to be the same
  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 4);

  newton.reanalyze();  // and so is a pattern the caller says changed
  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 5);
  solve_from_zero(newton, problem);
  EXPECT_EQ(linear.analyses, 5);
}

TEST(NewtonPattern, ARestartAnalysesAgainWhereTheAnalysisReadsTheValues) {
  // A load step attempt starts as a resumed run's first step does: UMFPACK's analysis is given the values
  // (umfpack_symbolic), so it is done again; CHOLMOD's and MUMPS's read the pattern alone
  // (MUMPS is handed zeros), so an analysis of the same pattern still serves.
  EXPECT_TRUE(make_linear_solver(LinearSolverKind::umfpack)->analysis_reads_values());
  EXPECT_TRUE(make_linear_solver(LinearSolverKind::klu)->analysis_reads_values());
  for (LinearSolverKind kind : {LinearSolverKind::cholmod, LinearSolverKind::cholmod_ldlt,
                                LinearSolverKind::mumps_ldlt, LinearSolverKind::mumps_lu})
    EXPECT_FALSE(make_linear_solver(kind)->analysis_reads_values());

  // (MUMPS's PORD ordering fails on a 3x3 matrix: CHOLMOD stands for the solvers that read the pattern
  // alone.)
  for (LinearSolverKind kind : {LinearSolverKind::umfpack, LinearSolverKind::cholmod}) {
    Linear problem;
    CountingSolver linear(kind);
    NewtonSolver newton(linear, NewtonSettings{});
    solve_from_zero(newton, problem);
    newton.restart();
    solve_from_zero(newton, problem);
    EXPECT_EQ(linear.analyses, kind == LinearSolverKind::umfpack ? 2 : 1) << linear.name();
    problem.set_corners(true);  // a new pattern is analysed by every solver
    newton.restart();
    solve_from_zero(newton, problem);
    EXPECT_EQ(linear.analyses, kind == LinearSolverKind::umfpack ? 3 : 2) << linear.name();
  }
}

}  // namespace
}  // namespace nodus::solver
