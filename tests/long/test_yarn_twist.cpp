// A coarse 3x1 yarn twisted by its rigid bodies (docs/bodies.md, docs/yarns.md): three fibres laid side by
// side, the start bodies clamped, the end bodies turned about the yarn axis with their sections' orientation
// held (planetary: the fibres are not twisted about their own axes), free along the axis under a small
// tension, with contact and friction (the varying friction tangent: the fibres slip as they wind). Checked
// on every converged step: nothing passes through anything (every pair of fibre axes at least R_I + R_J -
// 2 p_max apart). At the end, against the equilibrium of helical rods with three plies (derived in
// docs/verification/strand.md): neighbouring axes as close as 2 R s - p, the bodies' axial force and torque,
// the contact line load; the bodies pass their loads on. And the same yarn with its fibres and bodies
// numbered the other way round gives the same state.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/analysis/knot_metrics.hpp"
#include "nodus/analysis/yarn_metrics.hpp"
#include "nodus/beam/strain_measures.hpp"
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
         "contact: {friction: 0.3, particles: facing, friction_tangent: varying}\nsolver: {linear_solver: "
         "klu}\n"
         "stages:\n  - name: twist\n    steps: " +
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
  // Neighbouring axes are closest where the contact presses: 2 R s - p apart, s the contracted sections'
  // scale (the directors' length), p the penetration the penalty leaves. For helices of radius rho and rate k
  // a third of a turn apart, the closest points are not in one cross-section: the squared distance between
  // the points dz apart along the axis is 2 rho^2 (1 - cos(2 pi / 3 + k dz)) + dz^2, least at dz of about
  // -rho^2 k sin(2 pi / 3); rho sqrt(3), the distance in one cross-section, is 8e-5 mm (0.07 p_max) more
  // here.
  for (int b = 0; b < 3; ++b) {
    const int middle = sim.model().node_dof(sim.model().beam(b).node(sim.model().beam(b).num_nodes() / 2));
    const double s_contraction = 0.5 * (x.segment<3>(middle + 3).norm() + x.segment<3>(middle + 6).norm());
    const analysis::HelixFit fit = analysis::fit_helix(
        sim.model(), x, b, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), kLength / 3, 2 * kLength / 3);
    const double rho = fit.radius, k = fit.rate, third = 2.0 * std::numbers::pi / 3.0;
    double dz = -rho * rho * k * std::sin(third);
    for (int it = 0; it < 20; ++it)  // Newton on d/d(dz) of the squared distance
      dz -= (2 * rho * rho * k * std::sin(third + k * dz) + 2 * dz) /
            (2 * rho * rho * k * k * std::cos(third + k * dz) + 2);
    const double closest = std::sqrt(2 * rho * rho * (1 - std::cos(third + k * dz)) + dz * dz);
    const double expected = 2.0 * kRadius * s_contraction - penetration;
    std::printf(
        "fibre %d: helix radius %.7f mm (spread %.1e), rate %.4f rad/mm; closest neighbour axis %.7f mm, "
        "2 R s - p = %.7f mm (p = %.2e mm, %+.1e p_max)\n",
        b, rho, fit.radius_spread, k, closest, expected, penetration, (closest - expected) / p_max);
    // 5e-3 p_max: rho and p are means over the middle third, where on this coarse mesh (0.35 rad of helix per
    // element) the nodes' distances to the axis spread by 2.5e-5 mm (0.02 p_max); measured: 1.6e-3 to 2.3e-3.
    EXPECT_NEAR(closest, expected, 5e-3 * p_max);
  }
  // The strand against the equilibrium of helical rods (docs/verification/double_helix.md, sections 3, 4
  // and 6, with three plies): each fibre is a helix of radius rho and winding rate k, tan(alpha) = rho k,
  // curvature kappa = rho k^2 / (1 + rho^2 k^2), torsion tau = k / (1 + rho^2 k^2), carrying the tension
  // T = lambda E A e33 and the twisting moment M3 = (E/2) J Omega of its section (Omega = q21 - q12, the
  // directors' twist), and bent with B = E I. The axial force and torque of the three through any section,
  // F = 3 (T cos(alpha) + N_b sin(alpha)), M = 3 (rho (T sin(alpha) - N_b cos(alpha)) + B kappa sin(alpha)
  // + M3 cos(alpha)), N_b = kappa (M3 - B tau), are those the end bodies carry; and the outward line load
  // that holds each fibre on its helix, p = kappa T + kappa tau (B tau - M3) per unit length, comes from its
  // two neighbours pressing along the lines of centres, 30 degrees either side of the radial direction:
  // p = 2 q cos(30 deg) = sqrt(3) q, q the line load between two fibres.
  {
    const double area = std::numbers::pi * kRadius * kRadius, inertia = area * kRadius * kRadius / 4;
    const double young = 4000.0, bend = young * inertia, torsion = 0.5 * young * 2 * inertia;
    // At the two Gauss points, where the internal forces are evaluated: the quadratic interpolation of the
    // helix (0.35 rad per element here) makes r'.r' vary along an element by about as much as e33 itself.
    const double gauss = 1.0 / std::sqrt(3.0);
    const Eigen::MatrixXd strains =
        0.5 * (sim.model().element_strains(x, -gauss) + sim.model().element_strains(x, gauss));
    double e33 = 0.0, lateral = 0.0, omega = 0.0, rho = 0.0, k = 0.0;
    int elements = 0;
    for (int b = 0; b < 3; ++b) {
      const analysis::HelixFit fit = analysis::fit_helix(
          sim.model(), x, b, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), kLength / 3, 2 * kLength / 3);
      rho += fit.radius / 3;
      k += fit.rate / 3;
      const beam::Beam& beam = sim.model().beam(b);
      for (int e = 0; e < beam.num_elements(); ++e) {
        const double centre = (e + 0.5) * beam.element_length();
        if (centre < kLength / 3 || centre > 2 * kLength / 3) continue;
        const int g = sim.model().first_element(b) + e;
        e33 += strains(beam::kE33, g);
        lateral += strains(beam::kE11, g) + strains(beam::kE22, g);
        omega += strains(beam::kQ21, g) - strains(beam::kQ12, g);
        ++elements;
      }
    }
    e33 /= elements;
    lateral /= elements;
    omega /= elements;
    // The section's axial force from its constant strains (model.md: S = lambda_L tr(E0) + 2 mu E0): the
    // contact squeezes the section, so e11 + e22 is not -2 nu e33 and T is not E A e33.
    const double nu = 0.3, mu = young / (2 * (1 + nu)), lame = young * nu / ((1 + nu) * (1 - 2 * nu));
    const double stretch = std::sqrt(1 + 2 * e33);
    const double tension = stretch * area * ((lame + 2 * mu) * e33 + lame * lateral), m3 = torsion * omega;
    const double alpha = std::atan(rho * k), kappa = rho * k * k / (1 + rho * rho * k * k),
                 tau = k / (1 + rho * rho * k * k);
    const double n_b = kappa * (m3 - bend * tau);
    const double force_ref = 3 * (tension * std::cos(alpha) + n_b * std::sin(alpha));
    const double moment_ref = 3 * (rho * (tension * std::sin(alpha) - n_b * std::cos(alpha)) +
                                   bend * kappa * std::sin(alpha) + m3 * std::cos(alpha));
    const double load_ref = kappa * tension + kappa * tau * (bend * tau - m3);
    double force = 0.0, moment = 0.0;
    for (int b = 1; b < 6; b += 2) {
      const simulation::BodyRecord& body = gaps.last.bodies[static_cast<std::size_t>(b)];
      const Eigen::Vector3d c = x.segment<3>(sim.model().body_dof(b));
      force += body.force.x();
      moment += Eigen::Vector3d(0, c.y(), c.z()).cross(body.force).x() + body.moment.x();
    }
    // q: the mean R_N of the middle third's contact elements over their mean spacing along fibre I (current
    // length: reference spacing times the stretch).
    double sum = 0.0, spacing = 0.0;
    int counted_spacing = 0, counted_elements = 0;
    for (Eigen::Index e = 0; e < table.gap.size(); ++e) {
      if (table.abscissa_i[e] < kLength / 3 || table.abscissa_i[e] > 2 * kLength / 3) continue;
      sum += table.normal_force[e];
      ++counted_elements;
      if (e > 0 && table.zone[e] == table.zone[e - 1] && table.abscissa_i[e - 1] >= kLength / 3) {
        spacing += std::abs(table.abscissa_i[e] - table.abscissa_i[e - 1]);
        ++counted_spacing;
      }
    }
    const double q = (sum / counted_elements) / (stretch * spacing / counted_spacing);
    std::printf("strand: rho %.6f mm, k %.5f rad/mm, alpha %.3f deg, T %.6f N (e33 %.3e), M3 %.3e N mm\n",
                rho, k, alpha * 180 / std::numbers::pi, tension, e33, m3);
    std::printf(
        "strand: axial force %.6f N, helical rods %.6f N (%+.2e); torque %.6e N mm, helical rods %.6e "
        "(%+.2e); line load sqrt(3) q %.6f N/mm, helical rods %.6f N/mm (%+.2e)\n",
        force, force_ref, force / force_ref - 1, moment, moment_ref, moment / moment_ref - 1,
        std::sqrt(3.0) * q, load_ref, std::sqrt(3.0) * q / load_ref - 1);
    EXPECT_NEAR(force, force_ref, 0.01 * force_ref);
    EXPECT_NEAR(moment, moment_ref, 0.01 * std::abs(moment_ref));
    EXPECT_NEAR(std::sqrt(3.0) * q, load_ref, 0.01 * load_ref);
  }
  // The end bodies, free along the axis, pass their pulls on: 0.05 N each.
  for (int b = 1; b < 6; b += 2)
    EXPECT_NEAR(gaps.last.bodies[static_cast<std::size_t>(b)].force.x(), 0.05, 1e-6) << "body " << b;
}

// Rovings of several fibres (docs/yarns.md, "Rovings of several fibres: the tie"): three rovings of three
// fibres, the end bodies turned with their rotation (a ply twist) by a tenth of the examples' twist at their
// nominal step (7.36 degrees), with the yarn's tie at 1e-6 of the penalty (with the default tie the steps
// of this case are cut back to 1/16 of the nominal within four steps). Each step converges with at most two
// cutbacks; nothing passes through anything; the yarn as a whole is in equilibrium: the held bodies carry
// the three pulls, and the moments about the axis on the held and the turned bodies cancel but for the
// couple of the friction forces, which act between particles a gap apart (at most the largest penetration
// times the sum of the friction forces).
TEST(YarnTwist, RovingsOfThreeFibresTwistAtTheNominalStepWithTheTie) {
  const std::string text = R"(materials:
  - {name: polyamide, young_modulus: 4000, poisson_ratio: 0.3}
yarns:
  - {name: yarn, rovings: 3, fibres_per_roving: 3, fibre_radius: 0.0188, length: 6, elements: 30,
     material: polyamide, tie: 1e-6}
conditions:
  - {name: hold, type: clamp, bodies: [yarn.r1.start, yarn.r2.start, yarn.r3.start]}
  - {name: turn, type: motion, bodies: [yarn.r1.end, yarn.r2.end, yarn.r3.end], dofs: [y, z, rotation], pivot: [6, 0, 0]}
  - {name: pull1, type: load, bodies: [yarn.r1.end], force: [0.05, 0, 0]}
  - {name: pull2, type: load, bodies: [yarn.r2.end], force: [0.05, 0, 0]}
  - {name: pull3, type: load, bodies: [yarn.r3.end], force: [0.05, 0, 0]}
contact: {friction: 0.3, particles: facing, friction_tangent: varying}
solver: {linear_solver: mumps, easy_iterations: 20}
stages:
  - {name: twist, steps: 14, motions: {turn: {rotation: [103, 0, 0]}}}
)";
  simulation::Simulation sim(scenario::parse_scenario(text, "rovings.yaml"));
  // The gap away from the fibres' last element at each end: there the bodies turn each roving about its own
  // centre, and the rovings, laid as close as their orientation allows, press into each other at the end
  // sections, where no contact element sits (docs/yarns.md); the crossing guard still refuses any step in
  // which two axes pass through each other.
  struct Watch : GapCheck {
    int most_cutbacks = 0;
    double largest_tie = 0.0, smallest_at_ends = INFINITY;
    void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
      last = r;
      const double element = sim.model().beam(0).element_length();
      smallest = std::min(smallest, analysis::smallest_axis_gap(sim.model(), sim.state(), 8, element).gap);
      smallest_at_ends =
          std::min(smallest_at_ends, analysis::smallest_axis_gap(sim.model(), sim.state()).gap);
      most_cutbacks = std::max(most_cutbacks, r.cutbacks);
      for (const simulation::BodyRecord& b : r.bodies) largest_tie = std::max(largest_tie, b.tie);
    }
  } watch;
  const simulation::RunSummary summary = sim.run({&watch});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const double p_max = sim.contact_laws().max_penetration;
  std::printf(
      "3x3 twist: %d steps, %d Newton iterations, %.1f s; most cutbacks in a step %d; smallest axis gap "
      "%.3f p_max (%.3f p_max with the end elements); largest tie force %.2e N\n",
      summary.steps, summary.newton_iterations, summary.wall_seconds, watch.most_cutbacks,
      watch.smallest / p_max, watch.smallest_at_ends / p_max, watch.largest_tie);
  EXPECT_LE(watch.most_cutbacks, 2);
  EXPECT_GE(watch.smallest, -2.0 * p_max);
  // Condition 0 holds the start bodies, condition 1 turns the end bodies about the yarn axis (x).
  const simulation::StepRecord& last = watch.last;
  const double held = last.sections[0].moment.x(), turned = last.sections[1].moment.x();
  const double couple = last.penetration_ratio * p_max * last.tangential_force;
  std::printf(
      "moments about the axis: held %.6e, turned %.6e N mm (sum %.2e, friction couple at most %.2e); held "
      "force %.9f N\n",
      held, turned, held + turned, couple, last.sections[0].force.x());
  EXPECT_GT(std::abs(turned), 0.0);
  EXPECT_LE(std::abs(held + turned), couple);
  EXPECT_NEAR(last.sections[0].force.x(), -0.15, 1e-6);
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
