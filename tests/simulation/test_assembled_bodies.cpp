// The assembled tangent of EquilibriumProblem with rigid bodies against central finite differences of its
// residual, over every free unknown (the free body's six included), with the terms a twisted yarn has: beam
// internal forces, the averaged conditions with their tie (the committed state elsewhere, so that the tie
// acts), a dead force and a moment about a fixed axis on a free body, a body held in some of its unknowns,
// a bind of two bodies' x and z (coupling their blocks), and the viscous drag.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include <Eigen/Dense>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/averaged_conditions_term.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::simulation {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(AssembledBodies, TangentMatchesFiniteDifferencesThroughTheWholeProblem) {
  model::Model model(2, 0.0);
  const beam::ElasticConstants material{4000.0, 0.3};
  const double radius = 0.0564, spacing = 2.02 * radius;
  for (int i = 0; i < 3; ++i) {
    const double angle = 2.0 * 3.141592653589793 * i / 3.0;
    model.add_beam({"f" + std::to_string(i), 1.0, radius, 2,
                    Vec3(0.0, std::cos(angle), std::sin(angle)) * spacing / std::sqrt(3.0), Vec3::UnitX(),
                    Vec3::UnitY(), material, 1.0});
  }
  auto ends = [&](int local) {
    std::vector<int> nodes;
    for (int b = 0; b < 3; ++b) nodes.push_back(model.beam(b).node(local));
    return nodes;
  };
  const int start = model.add_body("start", ends(0));
  const int end = model.add_body("end", ends(4));
  const int middle = model.add_body("middle", {model.beam(1).node(2)});
  auto ref = [&](int b) { return loading::BodyRef{model.body(b).block, model.body_dof(b)}; };

  loading::Conditions conditions;
  const loading::DofMask all{true, true, true, true, true, true, false, false, false};
  const loading::DofMask some{false, true, true, true, false, false, false, false, false};  // y, z, rx
  const int hold = conditions.add_body_motion("hold", {ref(start)}, all);
  const int turn = conditions.add_body_motion("turn", {ref(end)}, some, Vec3(1.0, 0.0, 0.0));
  const Vec3 axis = Vec3(1.0, 0.2, -0.1).normalized();
  const int push = conditions.add_body_load("push", ref(middle), Vec3::Zero(), axis, 0.0);
  const loading::DofMask x_and_z{true, false, true, false, false, false, false, false, false};
  const int bind = conditions.add_body_bind("bind", {ref(end), ref(middle)}, x_and_z, 50.0);
  for (int c : {hold, turn, push, bind}) conditions.activate(c, 0.0, model.reference());
  conditions.add_motion_keyframe(turn, 1.0, Vec3::Zero(), Vec3(0.6, 0.0, 0.0));
  conditions.add_load_keyframe(push, 1.0, Vec3(0.01, -0.02, 0.03), 0.004);

  EquilibriumProblem problem(model, conditions, Tolerances{});
  problem.add_term(std::make_unique<model::AveragedConditionsTerm>(model, std::vector<double>{},
                                                                   std::vector<double>{0.01, 0.01, 0.01}));
  problem.set_stabilization({0.0, 1.0, 2.0, 2.0});
  problem.set_time(0.0);
  problem.commit();
  problem.set_time(0.5);
  // The free unknowns: every node but none of the held body's; the turned body's x, ry, rz; the middle
  // body's six. Perturbed at random, rotations by up to 0.3 rad.
  Eigen::VectorXd u = problem.unknowns();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  for (int i = 0; i < u.size(); ++i) u[i] += 0.01 * noise(rng);
  const int free_middle = static_cast<int>(u.size()) - 6;  // the last block's unknowns are the last ones
  for (int k = 3; k < 6; ++k) u[free_middle + k] += 0.3 * noise(rng);
  ASSERT_EQ(problem.size(), 3 * 5 * 9 + 3 + 6);

  problem.set_unknowns(u);
  Eigen::VectorXd r, rp, rm;
  problem.evaluate(r, true);
  const Eigen::MatrixXd k(problem.tangent());
  const double h = 1e-6;
  Eigen::MatrixXd fd(u.size(), u.size());
  for (int j = 0; j < u.size(); ++j) {
    Eigen::VectorXd v = u;
    v[j] += h;
    problem.set_unknowns(v);
    problem.evaluate(rp, false);
    v[j] = u[j] - h;
    problem.set_unknowns(v);
    problem.evaluate(rm, false);
    fd.col(j) = (rp - rm) / (2 * h);
  }
  const double scale = k.cwiseAbs().maxCoeff();
  const double error = (k - fd).cwiseAbs().maxCoeff();
  std::printf("assembled problem with bodies: max |K - FD| %.2e, max |K| %.2e, |R| %.2e\n", error, scale,
              r.norm());
  EXPECT_GT(r.norm(), 1.0);  // far from equilibrium: every term contributes
  EXPECT_LT(error, 1e-8 * scale);
}

}  // namespace
}  // namespace nodus::simulation
