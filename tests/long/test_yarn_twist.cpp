// A coarse 3x1 yarn twisted by its rigid bodies (docs/bodies.md, docs/yarns.md): three fibres laid side by
// side, the start bodies clamped, the end bodies turned about the yarn axis with their sections' orientation
// held (planetary: the fibres are not twisted about their own axes), free along the axis under a small
// tension, with contact and friction. Checked on every converged step: nothing passes through anything (every
// pair of fibre axes at least R_I + R_J - 2 p_max apart). At the end: the fibre centres lie on a helix of
// radius 2 (R s - p / 2) / sqrt(3) about the yarn axis (the three contracted sections, s the directors'
// length, pressing each other by the penetration p the penalty leaves), and the bodies' tension balances
// the loads. And the same yarn with its fibres and bodies numbered the other way round gives the same state.
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "nodus/analysis/knot_metrics.hpp"
#include "nodus/analysis/yarn_metrics.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus {
namespace {

constexpr double kRadius = 0.0564, kLength = 6.0;

/// Three fibres in a triangle, as the yarns section lays them (clearance 0.01 R), written out as beams and
/// bodies in the given order of rovings; `turn` degrees in `steps` steps.
std::string strand(const std::vector<int>& order, int elements, double turn, int steps) {
  const double spacing = 2.01 * kRadius, rho = spacing / std::sqrt(3.0);
  std::string beams, bodies, hold, end, pulls;
  for (int k : order) {
    const double angle = 2.0 * 3.14159265358979323846 * k / 3.0;
    beams += "  - {name: f" + std::to_string(k) +
             ", material: m, radius: 0.0564, length: 6, elements: " + std::to_string(elements) +
             ", start: [0, " + std::to_string(rho * std::cos(angle)) + ", " +
             std::to_string(rho * std::sin(angle)) + "], director1: [0, 1, 0]}\n";
    bodies += "  - {name: s" + std::to_string(k) + ", beams: [f" + std::to_string(k) + "], at: start}\n";
    bodies += "  - {name: e" + std::to_string(k) + ", beams: [f" + std::to_string(k) + "], at: end}\n";
    hold += std::string(hold.empty() ? "" : ", ") + "s" + std::to_string(k);
    end += std::string(end.empty() ? "" : ", ") + "e" + std::to_string(k);
    pulls += "  - {name: pull" + std::to_string(k) + ", type: load, bodies: [e" + std::to_string(k) +
             "], force: [0.05, 0, 0]}\n";
  }
  return "materials:\n  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}\nbeams:\n" + beams +
         "bodies:\n" + bodies + "conditions:\n  - {name: hold, type: clamp, bodies: [" + hold +
         "]}\n  - {name: turn, type: motion, bodies: [" + end + "], dofs: [y, z], pivot: [6, 0, 0]}\n" +
         "  - {name: keep, type: clamp, bodies: [" + end + "], dofs: [rotation]}\n" + pulls +
         "contact: {friction: 0.3, particles: facing}\nstages:\n  - name: twist\n    steps: " +
         std::to_string(steps) + "\n    motions:\n      turn: {rotation: [" + std::to_string(turn) +
         ", 0, 0]}\n";
}

/// Checks every converged state: no two fibre axes closer than R_I + R_J - 2 p_max.
struct GapCheck : simulation::StepObserver {
  double smallest = INFINITY;
  int worst_step = 0;
  simulation::StepRecord last;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    last = r;
    const analysis::AxisGap g = analysis::smallest_axis_gap(sim.model(), sim.state());
    if (g.gap < smallest) {
      smallest = g.gap;
      worst_step = r.step;
    }
  }
};

TEST(YarnTwist, ThreeFibresWindIntoAHelixWithoutPassingThroughEachOther) {
  const scenario::Scenario s = scenario::parse_scenario(strand({0, 1, 2}, 20, 360.0, 12), "strand.yaml");
  simulation::Simulation sim(s);
  GapCheck gaps;
  const simulation::RunSummary summary = sim.run({&gaps});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const double p_max = sim.contact_laws().max_penetration;
  std::printf(
      "3x1 twist: %d steps, %d Newton iterations, %.1f s; smallest axis gap %.3e mm = %.3f p_max (step %d)\n",
      summary.steps, summary.newton_iterations, summary.wall_seconds, gaps.smallest, gaps.smallest / p_max,
      gaps.worst_step);
  EXPECT_GE(gaps.smallest, -2.0 * p_max);

  // The helix, over the middle third, from the contracted sections and the penetrations there.
  const Eigen::VectorXd& x = sim.state();
  const analysis::ContactTable table = analysis::contact_table(sim);
  double penetration = 0.0;
  int counted = 0;
  for (Eigen::Index k = 0; k < table.gap.size(); ++k)
    if (table.abscissa_i[k] > kLength / 3 && table.abscissa_i[k] < 2 * kLength / 3) {
      penetration += -table.gap[k];
      ++counted;
    }
  ASSERT_GT(counted, 0);
  penetration /= counted;
  for (int b = 0; b < 3; ++b) {
    const int middle = sim.model().node_dof(sim.model().beam(b).node(sim.model().beam(b).num_nodes() / 2));
    const double s_contraction = 0.5 * (x.segment<3>(middle + 3).norm() + x.segment<3>(middle + 6).norm());
    const double expected = 2.0 * (kRadius * s_contraction - penetration / 2.0) / std::sqrt(3.0);
    const analysis::HelixFit fit = analysis::fit_helix(
        sim.model(), x, b, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), kLength / 3, 2 * kLength / 3);
    std::printf(
        "fibre %d: helix radius %.7f mm (spread %.1e), 2 (R s - p / 2) / sqrt(3) = %.7f mm, p = %.2e mm, "
        "rate %.4f rad/mm\n",
        b, fit.radius, fit.radius_spread, expected, penetration, fit.rate);
    EXPECT_NEAR(fit.radius, expected, 0.1 * p_max);
  }
  // The end bodies, free along the axis, pass their pulls on: 0.05 N each.
  for (int b = 1; b < 6; b += 2)
    EXPECT_NEAR(gaps.last.bodies[static_cast<std::size_t>(b)].force.x(), 0.05, 1e-6) << "body " << b;
}

// Numbering the fibres (and their bodies) the other way changes nothing: the same state, fibre by fibre.
TEST(YarnTwist, RenumberingTheFibresChangesNothing) {
  auto run = [](const std::vector<int>& order) {
    simulation::Simulation sim(scenario::parse_scenario(strand(order, 10, 120.0, 4), "strand.yaml"));
    EXPECT_TRUE(sim.run({}).converged);
    std::map<std::string, Eigen::VectorXd> fibres;
    for (int b = 0; b < 3; ++b) {
      const beam::Beam& beam = sim.model().beam(b);
      fibres[beam.name()] = sim.state().segment(sim.model().node_dof(beam.node(0)), 9 * beam.num_nodes());
    }
    return fibres;
  };
  const auto forward = run({0, 1, 2}), backward = run({2, 0, 1});
  double worst = 0.0;
  for (const auto& [name, x] : forward)
    worst = std::max(worst, (x - backward.at(name)).cwiseAbs().maxCoeff());
  std::printf("renumbered: largest difference %.2e\n", worst);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace nodus
