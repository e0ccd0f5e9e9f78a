// Newton's quadratic rate near a solution, read from the residual history of a real beam problem: a
// cantilever (L = 50 mm, R = 0.5 mm, 10 elements) under a dead end force F L^2 / EI = 3 (tip rotation ~ 70
// degrees), solved to load time 0.8 and then taken to 1.0 by plain Newton (no line search: full steps),
// iterated into round-off.
//
// What quadratic convergence means for the residual: after a full step du_k = -K_k^{-1} R_k,
//   R_{k+1} = R(u_k + du_k) = 1/2 D2R(u_k)[du_k, du_k] + O(|du_k|^3),
// the linear term cancelling exactly when K_k is the exact derivative of R. Hence
//   C_k = |R_{k+1}| / |R_k|^2 <= 1/2 M_k |K_k^{-1}|^2,   M_k = |D2R[du_k, du_k]| / |du_k|^2,
// a bound that depends only on the neighbourhood of the solution (M and K^{-1} are continuous there), so C_k
// stays bounded as R_k -> 0; with a tangent in error by E the residual keeps a first-order part E du_k and
// C_k grows like 1/|R_k|. The test reads the history and checks (1) the Taylor relation: |R_{k+1}| equals
// 1/2 |D2R[du_k, du_k]|, computed independently by central second differences of the residual along du_k;
// (2) C_k <= 1/2 M_k |K_k^{-1}|^2, with |K^{-1}| from the dense SVD of the tangent and M_k from (1), and that
// this bound is the same (within a factor 2) over the last iterations; (3) the digits double in the last step
// before round-off.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/SVD>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::verification {
namespace {

/// Forwards to a problem and records the residual norm and the unknowns at every evaluation. Its residual
/// tolerance is 0, so Newton iterates until max_iterations, into round-off.
class Recorder final : public solver::NonlinearProblem {
 public:
  explicit Recorder(solver::NonlinearProblem& p) : p_(p) {}
  int size() const override { return p_.size(); }
  Eigen::VectorXd unknowns() const override { return p_.unknowns(); }
  void set_unknowns(const Eigen::VectorXd& u) override { p_.set_unknowns(u); }
  void evaluate(Eigen::VectorXd& r, bool with_tangent) override {
    p_.evaluate(r, with_tangent);
    // Newton may evaluate an iterate twice (without the tangent, then with it, when it line-searches): keep
    // each iterate once.
    if (states.empty() || p_.unknowns() != states.back()) {
      norms.push_back(r.norm());
      states.push_back(p_.unknowns());
    }
  }
  const solver::SparseMatrix& tangent() const override { return p_.tangent(); }
  double residual_tolerance() const override { return 0.0; }
  double scaled_increment(const Eigen::VectorXd& du) const override { return p_.scaled_increment(du); }
  double increment_tolerance() const override { return p_.increment_tolerance(); }

  std::vector<double> norms;
  std::vector<Eigen::VectorXd> states;

 private:
  solver::NonlinearProblem& p_;
};

TEST(NewtonRate, QuadraticNearTheSolutionOfALargeDeflectionCantilever) {
  const double length = 50.0, radius = 0.5, young = 4000.0;  // mm, mm, MPa
  const int elements = 10;
  model::Model model(2, 0.0);
  model.add_beam({"beam", length, radius, elements, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                  Eigen::Vector3d::UnitY(), beam::ElasticConstants{young, 0.3}, 1.0});
  const double ei = young * std::numbers::pi * std::pow(radius, 4) / 4.0;  // N mm^2
  const double force = 3.0 * ei / (length * length);                       // N
  loading::Conditions conditions;
  const int clamp = conditions.add_motion("clamp", 0, {true, true, true, true, true, true, true, true, true});
  const int tip =
      conditions.add_load("tip", 2 * elements, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0);
  conditions.activate(clamp, 0.0, model.reference());
  conditions.activate(tip, 0.0, model.reference());
  conditions.add_load_keyframe(tip, 1.0, Eigen::Vector3d(0.0, -force, 0.0), 0.0);
  simulation::EquilibriumProblem problem(model, conditions, simulation::Tolerances{});
  auto linear = solver::make_linear_solver(solver::LinearSolverKind::cholmod);
  {  // to load time 0.8, with the line search
    solver::NewtonSolver newton(*linear, solver::NewtonSettings{});
    solver::StepControl control;
    control.nominal_step = 0.1;
    const solver::AdvanceResult r =
        solver::advance(problem, newton, 0.0, 0.8, control, [](const solver::StepResult&) {});
    ASSERT_TRUE(r.completed) << r.failure;
  }
  // Then the last fifth of the load at once, full Newton steps, 12 iterations.
  problem.set_time(1.0);
  Recorder history(problem);
  solver::NewtonSettings settings;
  settings.line_search = false;
  settings.max_iterations = 12;
  solver::NewtonSolver newton(*linear, settings);
  newton.reanalyze();
  newton.solve(history);
  const std::vector<double>& r = history.norms;
  ASSERT_EQ(r.size(), 13u);
  // The round-off floor: where |R| stagnates, the last three iterates (4e-11 N: EquilibriumProblem's
  // estimate of its rounding floor is 4.4e-8 N, an upper bound).
  const double floor = std::max({r[10], r[11], r[12]});
  ASSERT_LT(floor, 1e-9);
  // The iterations before round-off: k >= 1 (the first step absorbs the load increment from the state at 0.8,
  // far from the new solution) while |R_{k+1}| is above 3 floors.
  std::vector<std::size_t> window;
  for (std::size_t k = 1; k + 1 < r.size() && r[k + 1] > 3.0 * floor; ++k) window.push_back(k);
  ASSERT_GE(window.size(), 5u);

  std::vector<double> bounds;  // 1/2 M_k |K_k^{-1}|^2 of the iterations near the solution
  for (const std::size_t k : window) {
    const Eigen::VectorXd& u = history.states[k];
    const Eigen::VectorXd du = history.states[k + 1] - u;
    // 1/2 D2R[du, du] by central second differences along v = s du, scaled so that |v| is 1e-3 L in the
    // largest position (D2R[du, du] = D2R[v, v] / s^2): truncation O(|v|^2) ~ 1e-6 relative, round-off
    // ~ eps |f_int| / |v|^2 ~ 1e-12 N.
    const double s = 1e-3 * length / du.lpNorm<Eigen::Infinity>();
    Eigen::VectorXd r_plus, r_minus, r_0;
    problem.set_unknowns(u + s * du);
    problem.evaluate(r_plus, false);
    problem.set_unknowns(u - s * du);
    problem.evaluate(r_minus, false);
    problem.set_unknowns(u);
    problem.evaluate(r_0, true);
    const double taylor = 0.5 * (r_plus - 2.0 * r_0 + r_minus).norm() / (s * s);
    // (1) The step leaves only the quadratic remainder. 10 %: the last step's |R_{k+1}| is within 10 floors
    // of the floor (1.5 % off); the others agree to 1e-3.
    EXPECT_NEAR(r[k + 1], taylor, 0.1 * r[k + 1]) << "iteration " << k;
    // (2) The bound.
    const Eigen::MatrixXd k_dense(problem.tangent());
    const double k_inverse = 1.0 / Eigen::JacobiSVD<Eigen::MatrixXd>(k_dense).singularValues().minCoeff();
    const double m = 2.0 * taylor / du.squaredNorm();
    const double bound = 0.5 * m * k_inverse * k_inverse;
    const double c = r[k + 1] / (r[k] * r[k]);
    std::printf("k %zu: |R_k| %.3e N, |R_k+1| %.3e N, 1/2 |D2R[du,du]| %.3e N, C_k %.3e /N, bound %.3e /N\n",
                k, r[k], r[k + 1], taylor, c, bound);
    EXPECT_LE(c, 1.1 * bound) << "iteration " << k;
    if (r[k] <= r[0]) bounds.push_back(bound);
  }
  // Near the solution (|R_k| back below the residual |R_0| of the load increment) the bound is a property of
  // the solution: about 3.3e6 /N (M ~ 12 N/mm^2 from the axial stiffness met by a rotation, |K^{-1}| ~ 740
  // mm/N the softest bending mode). The observed C_k stay below 30 /N: the bound assumes the residual lies
  // along the softest mode. They alternate between ~1e-2 and ~2e1 /N because successive residuals alternate
  // between mostly axial (stiff, small du) and mostly bending (soft, large du) content.
  ASSERT_GE(bounds.size(), 2u);
  EXPECT_LE(*std::max_element(bounds.begin(), bounds.end()),
            2.0 * *std::min_element(bounds.begin(), bounds.end()));
  // (3) Digits: counted against the residual |R_0| of the load increment (C |R_0| ~ 1, so that
  // -log10(C |R_{k+1}|) = -2 log10(C |R_k|)), the last step before round-off doubles them.
  const std::size_t last = window.back();
  const double digits = std::log10(r[0] / r[last]), next_digits = std::log10(r[0] / r[last + 1]);
  std::printf("last step: %.2f digits -> %.2f\n", digits, next_digits);
  EXPECT_GT(digits, 2.0);
  EXPECT_GT(next_digits, 1.8 * digits);
}

}  // namespace
}  // namespace nodus::verification
