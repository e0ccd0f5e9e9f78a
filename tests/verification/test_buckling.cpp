// Euler buckling of a pinned-pinned column under end shortening, against the exact inextensible elastica:
// with k = sin(theta0 / 2) (theta0 the end rotation), the shortening is Delta / L = 2 (1 - E(k) / K(k)) and
// the load P = Pcr (2 K(k) / pi)^2, Pcr = pi^2 EI / L^2. A tiny lateral force selects the buckling direction.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cantilever.hpp"

namespace nodus::verification {
namespace {

/// Exact elastica load ratio P / Pcr at a bending shortening Delta / L (bisection on k).
double elastica_load_ratio(double shortening) {
  double lo = 0.0, hi = 0.99;
  for (int i = 0; i < 200; ++i) {
    const double k = 0.5 * (lo + hi);
    const double d = 2 * (1 - std::comp_ellint_2(k) / std::comp_ellint_1(k));
    (d < shortening ? lo : hi) = k;
  }
  const double k = 0.5 * (lo + hi);
  return std::pow(2 * std::comp_ellint_1(k) / std::numbers::pi, 2);
}

TEST(Buckling, PinnedColumnFollowsTheElastica) {
  BeamCase c;
  c.radius = 0.5;
  c.elements = 20;
  scenario::Scenario s = single_beam(c);
  // Start: centre fixed and twist blocked (g1z); end: centre moved along the axis, free to rotate.
  add_condition(s, "start", scenario::ConditionType::clamp, false,
                {true, true, true, false, false, true, false, false, false});
  const int end = add_condition(s, "end", scenario::ConditionType::motion, true, position_dofs());
  // Imperfection: a lateral force of 1e-4 Pcr at mid-span. At the final state it changes the end force by
  // about 2 F L / (pi^2 w) = 3e-4 Pcr (virtual work with the mid deflection w = 0.064 L), well inside the
  // tolerance.
  const int nudge = add_condition(s, "nudge", scenario::ConditionType::load, false);
  s.conditions[static_cast<std::size_t>(nudge)].node = c.elements;
  const double pcr = std::numbers::pi * std::numbers::pi * c.ei() / (c.length * c.length);
  s.conditions[static_cast<std::size_t>(nudge)].force = Eigen::Vector3d(0, 1e-4 * pcr, 0);
  // First through the bifurcation (at Delta / L = Pcr / EA = 6e-5) in small steps, then on to 1 %.
  const double shortening = 0.01;  // Delta / L
  scenario::StageSpec onset;
  onset.name = "onset";
  onset.steps = 20;
  onset.motions.push_back({end, {{1.0, Eigen::Vector3d(-2e-4 * c.length, 0, 0), Eigen::Vector3d::Zero()}}});
  s.stages.push_back(onset);
  scenario::StageSpec stage;
  stage.name = "compress";
  stage.steps = 20;
  stage.motions.push_back(
      {end, {{1.0, Eigen::Vector3d(-shortening * c.length, 0, 0), Eigen::Vector3d::Zero()}}});
  s.stages.push_back(stage);
  VerifiedSimulation sim(s);
  LastStep capture;
  const simulation::RunSummary summary = sim.run({&capture});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const double p = -capture.last.sections[static_cast<std::size_t>(end)].force.x();
  // Part of the shortening is axial compression P L / E A; the elastica is inextensible.
  const double bending_shortening = shortening - p / (c.young * c.area());
  const double reference = elastica_load_ratio(bending_shortening) * pcr;
  const double mid_deflection = std::abs(centre(sim, c.elements).y());
  std::printf(
      "buckling: P = %.6f N, Pcr = %.6f N, elastica P(Delta) = %.6f N, error %.3f%%, mid deflection / L = "
      "%.4f, %d Newton iterations\n",
      p, pcr, reference, 100 * (p / reference - 1), mid_deflection / c.length, summary.newton_iterations);
  EXPECT_NEAR(p, reference, 0.005 * reference);
  EXPECT_GT(mid_deflection, 0.05 * c.length) << "the column must have buckled";
}

}  // namespace
}  // namespace nodus::verification
