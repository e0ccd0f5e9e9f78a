// Uniaxial tension and torsion of a straight rod against closed forms.
//
// Tension: with the section free to contract, the split law gives the uniaxial St-Venant-Kirchhoff response:
// S33 = E E33, E11 = E22 = -nu E33 exactly, so the end force is N = lambda E A E33 (first Piola-Kirchhoff,
// with lambda the stretch and E33 = (lambda^2 - 1) / 2) and each director has length sqrt(1 - 2 nu E33).
//
// Torsion: the shear strains of a twisted section are linear in (xi1, xi2) and carry the nu = 0 law of the
// higher-order terms (s_a = E E_a, i.e. shear modulus mu* = E / 2, Eq. 22-23). The torque is then
// T = (E / 2) J theta' with J = pi R^4 / 2, i.e. (1 + nu) G J: the 9-dof model is stiffer in torsion than
// the classical G J by the factor 1 + nu (docs/model.md).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cantilever.hpp"

namespace nodus::verification {
namespace {

TEST(Tension, AxialForceAndPoissonContraction) {
  BeamCase c;
  c.elements = 4;
  scenario::Scenario s = single_beam(c);
  // Start: centre fixed, twist blocked by g1z; end: centre moved along x; directors free to contract.
  add_condition(s, "start", scenario::ConditionType::clamp, false,
                {true, true, true, false, false, true, false, false, false});
  const int end = add_condition(s, "end", scenario::ConditionType::motion, true, position_dofs());
  const double stretch = 1.05;
  scenario::StageSpec stage;
  stage.name = "pull";
  stage.steps = 2;
  stage.motions.push_back(
      {end, {{1.0, Eigen::Vector3d((stretch - 1) * c.length, 0, 0), Eigen::Vector3d::Zero()}}});
  s.stages.push_back(stage);
  VerifiedSimulation sim(s);
  LastStep capture;
  ASSERT_TRUE(sim.run({&capture}).converged);
  const double e33 = 0.5 * (stretch * stretch - 1);
  const double force = stretch * c.young * c.area() * e33;
  const double fx = capture.last.sections[static_cast<std::size_t>(end)].force.x();
  std::printf("tension: N = %.6f N, reference lambda E A E33 = %.6f N, error %.2e\n", fx, force,
              fx / force - 1);
  EXPECT_NEAR(fx, force, 1e-8 * force);
  const double director = std::sqrt(1 - 2 * c.poisson * e33);
  for (int n = 0; n <= 2 * c.elements; ++n) {
    const Eigen::VectorXd& x = sim.state();
    const int base = 9 * sim.model().beam(0).node(n);
    EXPECT_NEAR(x.segment<3>(base + 3).norm(), director, 1e-10) << "node " << n;
    EXPECT_NEAR(x.segment<3>(base + 6).norm(), director, 1e-10) << "node " << n;
  }
}

TEST(Torsion, TorqueTwistSlope) {
  BeamCase c;
  c.elements = 10;
  scenario::Scenario s = single_beam(c);
  add_condition(s, "start", scenario::ConditionType::clamp, false);
  // End: the directors are turned about the axis; the centre is free.
  const int end = add_condition(s, "end", scenario::ConditionType::motion, true,
                                {false, false, false, true, true, true, true, true, true});
  const double twist_degrees = 0.5;
  scenario::StageSpec stage;
  stage.name = "twist";
  stage.steps = 1;
  stage.motions.push_back({end, {{1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(twist_degrees, 0, 0)}}});
  s.stages.push_back(stage);
  VerifiedSimulation sim(s);
  LastStep capture;
  ASSERT_TRUE(sim.run({&capture}).converged);
  const double theta = twist_degrees * std::numbers::pi / 180;
  const double torque = capture.last.sections[static_cast<std::size_t>(end)].moment.x();
  const double j = std::numbers::pi * std::pow(c.radius, 4) / 2;
  const double model_stiffness = 0.5 * c.young * j;              // (E / 2) J
  const double classical = c.young / (2 * (1 + c.poisson)) * j;  // G J
  const double slope = torque * c.length / theta;
  std::printf("torsion: T L / theta = %.6f N mm^2, (E/2) J = %.6f (error %.2e), G J = %.6f (ratio %.4f)\n",
              slope, model_stiffness, slope / model_stiffness - 1, classical, slope / classical);
  EXPECT_NEAR(slope, model_stiffness, 1e-3 * model_stiffness);
}

}  // namespace
}  // namespace nodus::verification
