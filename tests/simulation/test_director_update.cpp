// EquilibriumProblem::step, the update of the unknowns by a Newton increment. A straight free rod along x,
// given as increment the linearised twist about its own axis (positions unchanged, each director d_i = theta
// e_x x g_i): turned by the rotation update, the rod is rigidly twisted and carries no internal force; added,
// the increment stretches every section by theta^2 / 2 and leaves out-of-balance forces of that order.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::simulation {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kTheta = 0.3;  // rad

struct Rod {
  model::Model model{2, 0.0};
  loading::Conditions conditions;
  Rod() {
    model.add_beam({"rod", 4.0, 0.1, 4, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(),
                    beam::ElasticConstants{4000.0, 0.3}, 1.0});
  }
  /// The increment that twists every node's directors by kTheta about x (positions: 0); no unknown is
  /// prescribed, so the free unknowns are all of them.
  Eigen::VectorXd twist(const Eigen::VectorXd& x) const {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(model.num_dofs());
    for (int n = 0; n < model.num_nodes(); ++n)
      for (int i = 0; i < 2; ++i) {
        const int at = model.node_dof(n) + 3 + 3 * i;
        du.segment<3>(at) = kTheta * Vec3::UnitX().cross(Vec3(x.segment<3>(at)));
      }
    return du;
  }
};

/// |R| after the twist increment, and the largest director length error.
std::pair<double, double> twisted(Rod& rod, DirectorUpdate update) {
  EquilibriumProblem problem(rod.model, rod.conditions, Tolerances{}, update);
  problem.set_time(0.0);
  EXPECT_EQ(problem.size(), rod.model.num_dofs());
  problem.set_unknowns(problem.step(problem.unknowns(), rod.twist(problem.state())));
  Eigen::VectorXd r;
  problem.evaluate(r, false);
  double stretch = 0.0;
  for (int n = 0; n < rod.model.num_nodes(); ++n)
    for (int i = 0; i < 2; ++i)
      stretch = std::max(
          stretch, std::abs(problem.state().segment<3>(rod.model.node_dof(n) + 3 + 3 * i).norm() - 1.0));
  return {r.norm(), stretch};
}

TEST(DirectorUpdate, ATwistIncrementTurnsTheSectionsRigidly) {
  Rod turned, added;
  const auto [r_turned, stretch_turned] = twisted(turned, DirectorUpdate::rotation);
  const auto [r_added, stretch_added] = twisted(added, DirectorUpdate::additive);
  std::printf("twist %.1f rad: |R| %.3e N turned, %.3e N added\n", kTheta, r_turned, r_added);
  // Added: |g + theta e x g| = sqrt(1 + theta^2).
  EXPECT_NEAR(stretch_added, std::sqrt(1.0 + kTheta * kTheta) - 1.0, 1e-14);
  EXPECT_LT(stretch_turned, 1e-14);
  // EA = 125.7 N; the added sections' strain theta^2 / 2 = 0.045 loads the rod by newtons.
  EXPECT_GT(r_added, 1.0);
  EXPECT_LT(r_turned, 1e-10);
}

}  // namespace
}  // namespace nodus::simulation
