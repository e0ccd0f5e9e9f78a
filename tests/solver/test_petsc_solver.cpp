// The PETSc linear solver (solver.linear_solver: petsc) on one process, against Eigen's own factorisations:
// Cholesky-type (MUMPS's LDL^T) and LU, a refactorisation with new values, a new pattern, a singular matrix,
// GMRES on a kept factor.
// Runs on several ranks are checked by tests/mpi/ (whole runs against the serial backend).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/solver/petsc_solver.hpp"

namespace {

using nodus::solver::SparseMatrix;

/// A 1-D Laplacian of n unknowns plus random couplings between i and i + 7 (symmetric, or not), shifted so
/// that the matrix is regular; an indefinite one when `shift` is negative enough.
SparseMatrix test_matrix(int n, bool symmetric, double shift, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
    if (i + 7 < n) {
      const double a = u(random);
      t.emplace_back(i, i + 7, a);
      t.emplace_back(i + 7, i, symmetric ? a : u(random));
    }
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

Eigen::VectorXd reference_solution(const SparseMatrix& a, const Eigen::VectorXd& b) {
  Eigen::SparseLU<SparseMatrix> lu(a);
  return lu.solve(b);
}

class PetscSolver : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!nodus::parallel::available()) GTEST_SKIP() << "nodus built without PETSc";
  }
};

TEST_F(PetscSolver, SolvesSymmetricAndUnsymmetricSystemsAsEigenDoes) {
  for (const bool symmetric : {true, false}) {
    for (const double shift : {0.1, -0.3}) {  // definite, and indefinite (LDL^T with pivoting)
      const SparseMatrix a = test_matrix(300, symmetric, shift, 11);
      const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(300, -1.0, 2.0);
      auto solver = nodus::solver::make_petsc_solver(symmetric, "");
      solver->analyze(a);
      ASSERT_TRUE(solver->factorize(a));
      const Eigen::VectorXd x = solver->solve(b);
      const Eigen::VectorXd reference = reference_solution(a, b);
      EXPECT_LT((x - reference).norm(), 1e-10 * reference.norm())
          << "symmetric " << symmetric << " shift " << shift;
      EXPECT_LT((a * x - b).norm(), 1e-12 * b.norm());
    }
  }
}

TEST_F(PetscSolver, RefactorisesNewValuesAndAnalysesANewPattern) {
  auto solver = nodus::solver::make_petsc_solver(false, "");
  SparseMatrix a = test_matrix(120, false, 0.2, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(120);
  solver->analyze(a);
  ASSERT_TRUE(solver->factorize(a));
  const Eigen::VectorXd first = solver->solve(b);
  // The same pattern, other values: the analysis stands.
  for (int k = 0; k < a.nonZeros(); ++k) a.valuePtr()[k] *= 1.0 + 0.01 * (k % 5);
  ASSERT_TRUE(solver->factorize(a));
  const Eigen::VectorXd second = solver->solve(b);
  EXPECT_LT((a * second - b).norm(), 1e-12 * b.norm());
  EXPECT_GT((second - first).norm(), 1e-3 * first.norm());  // the new values were used
  // Another pattern (another size): analysed again.
  const SparseMatrix c = test_matrix(90, false, 0.2, 4);
  solver->analyze(c);
  ASSERT_TRUE(solver->factorize(c));
  const Eigen::VectorXd y = solver->solve(Eigen::VectorXd::Ones(90));
  EXPECT_LT((c * y - Eigen::VectorXd::Ones(90)).norm(), 1e-12 * std::sqrt(90.0));
}

// solver.reuse_factor through PETSc: GMRES preconditioned by the kept factor solves nearby matrices, of the
// same pattern or of another one, to the tolerance on the true residual; it gives up after its iterations on
// a matrix the factor no longer serves, and a factorisation then solves exactly again.
TEST_F(PetscSolver, SolvesOnTheKeptFactorUntilItNoLongerServes) {
  constexpr int kN = 200;
  constexpr double kTolerance = 1e-8;
  auto solver = nodus::solver::make_petsc_solver(false, "");
  const SparseMatrix a = test_matrix(kN, false, 0.2, 5);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(kN, 1.0, -1.0);
  solver->analyze(a);
  ASSERT_TRUE(solver->factorize(a));
  // New values, the same pattern.
  SparseMatrix near = a;
  for (int k = 0; k < near.nonZeros(); ++k) near.valuePtr()[k] *= 1.0 + 0.01 * (k % 5);
  Eigen::VectorXd x;
  nodus::solver::KrylovSolve r = solver->solve_on_factor(near, false, b, kTolerance, 20, x);
  EXPECT_TRUE(r.accepted);
  EXPECT_GT(r.iterations, 1);  // not the factor's own matrix
  EXPECT_LE(r.iterations, 20);
  EXPECT_LT((near * x - b).norm(), 1.01 * kTolerance * b.norm());
  // Another pattern of the same size: couplings between i and i + 3 added.
  SparseMatrix other = near;
  for (int i = 0; i + 3 < kN; ++i) other.coeffRef(i, i + 3) = 0.01;
  other.makeCompressed();
  ASSERT_GT(other.nonZeros(), near.nonZeros());
  r = solver->solve_on_factor(other, true, b, kTolerance, 20, x);
  EXPECT_TRUE(r.accepted);
  EXPECT_LT((other * x - b).norm(), 1.01 * kTolerance * b.norm());
  // Far from the factor's matrix: two iterations do not reach the tolerance.
  SparseMatrix far = a;
  for (int k = 0; k < far.nonZeros(); ++k) far.valuePtr()[k] *= 1.0 + 0.5 * (k % 7);
  r = solver->solve_on_factor(far, true, b, kTolerance, 2, x);
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.iterations, 2);
  // Refactorised (the pattern analysed again, as Newton does after a new one): exact again.
  solver->analyze(far);
  ASSERT_TRUE(solver->factorize(far));
  x = solver->solve(b);
  EXPECT_LT((far * x - b).norm(), 1e-12 * b.norm());
  EXPECT_LT((x - reference_solution(far, b)).norm(), 1e-10 * x.norm());
}

TEST_F(PetscSolver, ReportsASingularMatrixAsAFailedFactorisation) {
  // An unknown that nothing holds: a zero row and column.
  SparseMatrix a = test_matrix(50, true, 0.2, 5);
  for (int k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (it.row() == 20 || it.col() == 20) it.valueRef() = 0.0;
  for (const bool symmetric : {true, false}) {
    auto solver = nodus::solver::make_petsc_solver(symmetric, "");
    solver->analyze(a);
    const bool factorised = solver->factorize(a);
    const Eigen::VectorXd x = solver->solve(Eigen::VectorXd::Ones(50));
    EXPECT_TRUE(!factorised || !x.allFinite()) << "symmetric " << symmetric;
    // It recovers: the next regular matrix of the same pattern factorises.
    const SparseMatrix regular = test_matrix(50, true, 0.2, 5);
    ASSERT_TRUE(solver->factorize(regular));
    const Eigen::VectorXd y = solver->solve(Eigen::VectorXd::Ones(50));
    EXPECT_LT((regular * y - Eigen::VectorXd::Ones(50)).norm(), 1e-12 * std::sqrt(50.0));
  }
}

TEST_F(PetscSolver, TakesTheScenariosOptionsAndRefusesMalformedOnes) {
  auto solver = nodus::solver::make_petsc_solver(false, "-pc_factor_mat_solver_type superlu_dist");
  const SparseMatrix a = test_matrix(60, false, 0.2, 6);
  solver->analyze(a);
  ASSERT_TRUE(solver->factorize(a));
  const Eigen::VectorXd x = solver->solve(Eigen::VectorXd::Ones(60));
  EXPECT_LT((a * x - Eigen::VectorXd::Ones(60)).norm(), 1e-12 * std::sqrt(60.0));
  EXPECT_THROW(nodus::solver::make_petsc_solver(false, "superlu_dist"), std::invalid_argument);
}

}  // namespace
