// A large rigid motion of a whole beam, prescribed at both ends, leaves it stress-free: every node is the
// rigidly moved reference node and the support reactions vanish.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "cantilever.hpp"

namespace nodus::verification {
namespace {

TEST(RigidMotion, GivesNoInternalForce) {
  BeamCase c;
  c.elements = 8;
  scenario::Scenario s = single_beam(c);
  const int a = add_condition(s, "start", scenario::ConditionType::motion, false);
  const int b = add_condition(s, "end", scenario::ConditionType::motion, true);
  const Eigen::Vector3d rotation_degrees(70.0, -100.0, 40.0);  // about an oblique axis, |.| = 128 degrees
  const Eigen::Vector3d axis = rotation_degrees.normalized();
  const Eigen::Matrix3d q =
      Eigen::AngleAxisd(rotation_degrees.norm() * std::numbers::pi / 180, axis).matrix();
  const Eigen::Vector3d shift(12.0, -30.0, 7.0);
  const Eigen::Vector3d end(c.length, 0, 0);
  scenario::StageSpec stage;
  stage.name = "move";
  stage.steps = 8;
  stage.motions.push_back({a, {{1.0, shift, rotation_degrees}}});
  stage.motions.push_back({b, {{1.0, q * end + shift - end, rotation_degrees}}});
  s.stages.push_back(stage);
  VerifiedSimulation sim(s);
  LastStep capture;
  const simulation::RunSummary summary = sim.run({&capture});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Eigen::VectorXd& x = sim.state();
  const Eigen::VectorXd& x0 = sim.model().reference();
  for (int n = 0; n < sim.model().num_nodes(); ++n) {
    EXPECT_LT((x.segment<3>(9 * n) - (q * x0.segment<3>(9 * n) + shift)).norm(), 1e-9 * c.length) << n;
    EXPECT_LT((x.segment<3>(9 * n + 3) - q * x0.segment<3>(9 * n + 3)).norm(), 1e-9) << n;
    EXPECT_LT((x.segment<3>(9 * n + 6) - q * x0.segment<3>(9 * n + 6)).norm(), 1e-9) << n;
  }
  const double ea = c.young * c.area();
  for (const auto& f : capture.last.sections) {
    EXPECT_LT(f.force.norm(), 1e-9 * ea);
    EXPECT_LT(f.moment.norm(), 1e-9 * ea * c.length);
  }
}

}  // namespace
}  // namespace nodus::verification
