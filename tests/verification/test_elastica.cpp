// Cantilever under a dead tip load perpendicular to its axis against the elastica [Bisshopp and Drucker 1945,
// Q. Appl. Math. 3:272]: tip deflection v / L and shortening u / L for P L^2 / EI = 1, 2, 10.

#include <gtest/gtest.h>

#include <cstdio>

#include "cantilever.hpp"

namespace nodus::verification {
namespace {

struct ElasticaCase {
  double load;        // P L^2 / EI
  double deflection;  // v / L
  double shortening;  // u / L
};

class Elastica : public ::testing::TestWithParam<ElasticaCase> {};

TEST_P(Elastica, TipDisplacement) {
  const ElasticaCase e = GetParam();
  BeamCase c;
  c.radius = 0.1;
  scenario::Scenario s = single_beam(c);
  add_condition(s, "root", scenario::ConditionType::clamp, false);
  const int tip = add_condition(s, "tip", scenario::ConditionType::load, true);
  scenario::StageSpec stage;
  stage.name = "load";
  stage.steps = 10;
  // Load along -y, the beam along x with g1 = y: bending in the x-y plane.
  stage.loads.push_back(
      {tip, Eigen::Vector3d(0, -e.load * c.ei() / (c.length * c.length), 0), Eigen::Vector3d::Zero()});
  s.stages.push_back(stage);
  VerifiedSimulation sim(s);
  const simulation::RunSummary summary = run_quietly(sim);
  ASSERT_TRUE(summary.converged) << summary.failure;
  const Eigen::Vector3d d = centre(sim, 2 * c.elements) - centre(sim, 0);
  const double v = -d.y() / c.length, u = 1.0 - d.x() / c.length;
  std::printf(
      "PL^2/EI = %g: v/L = %.5f (ref %.5f, error %.3f%%), u/L = %.5f (ref %.5f, error %.3f%%), %d steps, "
      "%d Newton iterations\n",
      e.load, v, e.deflection, 100 * (v / e.deflection - 1), u, e.shortening, 100 * (u / e.shortening - 1),
      summary.steps, summary.newton_iterations);
  EXPECT_NEAR(v, e.deflection, 0.005 * e.deflection);
  EXPECT_NEAR(u, e.shortening, 0.005 * e.shortening);
  EXPECT_NEAR(d.z(), 0.0, 1e-9 * c.length);
}

INSTANTIATE_TEST_SUITE_P(BisshoppDrucker, Elastica,
                         ::testing::Values(ElasticaCase{1.0, 0.30172, 0.05643},
                                           ElasticaCase{2.0, 0.49346, 0.16064},
                                           ElasticaCase{10.0, 0.81061, 0.55500}));

}  // namespace
}  // namespace nodus::verification
