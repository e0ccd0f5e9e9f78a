// Rigid bodies bound to fibre ends by averaged conditions (docs/bodies.md), against closed forms: a bundle
// of parallel fibres pulled by its bodies carries N lambda E A E33 (uniaxial St-Venant-Kirchhoff, as in
// test_tension_torsion.cpp), its bound ends follow the body to within the penalty's error k n C_c = F, and
// a rigid rotation of everything leaves every fibre rigidly rotated and every reaction zero.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "nodus/model/averaged_conditions_term.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "step_recorder.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {
namespace {

constexpr double kRadius = 0.05, kLength = 4.0, kYoung = 4000.0, kPoisson = 0.3;
constexpr int kElements = 4;

/// One roving of seven fibres (a hexagon around one), bodies at both ends; `extra` appends conditions and
/// stages.
std::string bundle(const std::string& extra, bool bodies = true) {
  return R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
yarns:
  - {name: b, rovings: 1, fibres_per_roving: 7, fibre_radius: 0.05, length: 4, elements: 4, material: m, bodies: )" +
         std::string(bodies ? "true" : "false") + "}\n" + extra;
}

/// The x of node `local` of beam `beam` in state x.
double node_x(const simulation::Simulation& sim, const Eigen::VectorXd& x, int beam, int local) {
  return x[sim.model().node_dof(sim.model().beam(beam).node(local))];
}

TEST(Bodies, BundlePulledByItsBodiesCarriesNTimesTheFibreForce) {
  const double delta = 0.004;  // strain 1e-3
  const scenario::Scenario s = scenario::parse_scenario(bundle(R"(conditions:
  - {name: hold, type: clamp, bodies: [b.r1.start]}
  - {name: pull, type: motion, bodies: [b.r1.end]}
stages:
  - name: stretch
    steps: 2
    motions:
      pull: {translation: [0.004, 0, 0]}
)"),
                                                        "bundle.yaml");
  VerifiedSimulation sim(s);
  StepRecorder steps;
  ASSERT_TRUE(sim.run({&steps}).converged);
  const simulation::StepRecord& last = steps.records.back();
  const Eigen::VectorXd& x = sim.state();
  const int n = 7, last_node = 2 * kElements;
  const double area = std::numbers::pi * kRadius * kRadius;
  // Every fibre stretched alike; the force from the fibres' own stretch.
  double total = 0.0, mean_end = 0.0, first_stretch = 0.0;
  for (int f = 0; f < n; ++f) {
    const double stretch = (node_x(sim, x, f, last_node) - node_x(sim, x, f, 0)) / kLength;
    if (f == 0) first_stretch = stretch;
    EXPECT_NEAR(stretch, first_stretch, 1e-12) << "fibre " << f;
    const double e33 = 0.5 * (stretch * stretch - 1.0);
    total += stretch * kYoung * area * e33;
    mean_end += (node_x(sim, x, f, last_node) - kLength) / n;
  }
  const simulation::BodyRecord& end = last.bodies[1];
  const simulation::BodyRecord& start = last.bodies[0];
  std::printf(
      "bundle: body force %.10f N, sum of the fibres' lambda E A E33 %.10f N (error %.2e); start %.10f\n",
      end.force.x(), total, end.force.x() / total - 1.0, start.force.x());
  // The body's force on its fibres includes its tie's (below), which the fibres' stretch also feels at their
  // ends; the two agree to that force and Newton's tolerance.
  EXPECT_NEAR(end.force.x(), total, end.tie + 1e-9 * total);
  EXPECT_NEAR(start.force.x(), -total, start.tie + 1e-9 * total);
  EXPECT_LT(end.force.tail<2>().norm() + end.moment.norm(), 1e-9);
  // The motion condition's reaction on the body is the force the body exerts on its fibres.
  EXPECT_NEAR(last.sections[1].force.x(), end.force.x(), 1e-9 * total);
  // The bound ends follow the body to within the penalty's error: the mean end displacement lags the
  // body's by C_c = F / (k n), k = 1e3 E A / h, and steps.csv's error is |C_c| (C_t = 0 by symmetry).
  const double k = 1e3 * kYoung * area / (kLength / kElements);
  const double lag = delta - mean_end;
  std::printf(
      "bundle: body %.6f mm, mean end %.12f mm, lag %.3e mm, reported error %.3e mm, F / (k n) %.3e\n", delta,
      mean_end, lag, end.error, total / (k * n));
  EXPECT_NEAR(lag, end.error, 1e-9 * end.error);
  EXPECT_NEAR(end.error, total / (k * n), 1e-6 * end.error);
  EXPECT_NEAR(start.error, end.error, 1e-6 * end.error);
  // The tie resists each step's change of the sections' misfit relative to the body: here the lag, half of
  // which forms in the last of the two steps, on each of the n sections (the directors' Poisson contraction
  // adds a few per cent).
  const double tie =
      model::AveragedConditionsTerm::kDefaultTie * k * 0.5 * lag * std::sqrt(static_cast<double>(n));
  std::printf("bundle: tie force %.3e N, k_t lag / 2 sqrt(n) %.3e N\n", end.tie, tie);
  EXPECT_NEAR(end.tie, tie, 0.1 * tie);
}

// The bundle's fibres, held only at their ends, have free modes (spreading radially, turning about their own
// axes) that only the tie holds; at the default tie (1e-10 k, 3e-6 N/mm here) the round-off of the residual
// moves them by up to 5e-6 mm, a state as much in equilibrium as the rigidly moved one. The tie is zero on a
// rigid motion whatever its size, so this test takes it at 1e-6 to read the rigid motion to 1e-9 mm.
TEST(Bodies, RigidRotationOfEverythingLeavesNoReaction) {
  const scenario::Scenario s = scenario::parse_scenario(bundle(R"(bodies:
  - {name: start, beams: [b.r1.f1, b.r1.f2, b.r1.f3, b.r1.f4, b.r1.f5, b.r1.f6, b.r1.f7], at: start, tie: 1e-6}
  - {name: end, beams: [b.r1.f1, b.r1.f2, b.r1.f3, b.r1.f4, b.r1.f5, b.r1.f6, b.r1.f7], at: end, tie: 1e-6}
conditions:
  - {name: turn_start, type: motion, bodies: [start], pivot: [2, 0, 0]}
  - {name: turn_end, type: motion, bodies: [end], pivot: [2, 0, 0]}
stages:
  - name: turn
    steps: 3
    motions:
      turn_start: {rotation: [0, 90, 30], translation: [0.5, 0, 0]}
      turn_end: {rotation: [0, 90, 30], translation: [0.5, 0, 0]}
)",
                                                               false),
                                                        "bundle.yaml");
  VerifiedSimulation sim(s);
  StepRecorder steps;
  ASSERT_TRUE(sim.run({&steps}).converged);
  const Eigen::Vector3d pivot(2, 0, 0), shift(0.5, 0, 0);
  const Eigen::Vector3d rotation = Eigen::Vector3d(0, 90, 30) * std::numbers::pi / 180;
  const Eigen::Matrix3d q = Eigen::AngleAxisd(rotation.norm(), rotation.normalized()).toRotationMatrix();
  const Eigen::VectorXd& x = sim.state();
  const Eigen::VectorXd& x0 = sim.model().reference();
  double worst = 0.0;
  for (int node = 0; node < sim.model().num_nodes(); ++node) {
    const int i = sim.model().node_dof(node);
    worst = std::max(worst, (x.segment<3>(i) - (pivot + shift + q * (x0.segment<3>(i) - pivot))).norm());
    worst = std::max(worst, (x.segment<3>(i + 3) - q * x0.segment<3>(i + 3)).norm());
    worst = std::max(worst, (x.segment<3>(i + 6) - q * x0.segment<3>(i + 6)).norm());
  }
  std::printf("rigid rotation: largest departure from the rigidly moved reference %.2e\n", worst);
  EXPECT_LT(worst, 1e-9);
  for (const simulation::StepRecord& r : steps.records) {
    for (const loading::SectionForce& f : r.sections) EXPECT_LT(f.force.norm() + f.moment.norm(), 1e-7);
    for (const simulation::BodyRecord& b : r.bodies) EXPECT_LT(b.error, 1e-12);
  }
}

// A moment on a free body twists the fibre it holds as a moment on its section would: T = (E / 2) J theta'
// (the 9-dof model's torsional stiffness, test_tension_torsion.cpp), and the body turns with the section.
TEST(Bodies, MomentOnAFreeBodyTwistsItsFibre) {
  const double moment = 2e-4;  // N mm
  const scenario::Scenario s = scenario::parse_scenario(R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: f, material: m, radius: 0.05, length: 4, elements: 8}
bodies:
  - {name: a, beams: [f], at: start}
  - {name: b, beams: [f], at: end}
conditions:
  - {name: hold, type: clamp, bodies: [a]}
  - {name: twist, type: load, bodies: [b], moment: [0, 0, 0]}
stages:
  - name: load
    steps: 2
    loads:
      twist: {moment: [2e-4, 0, 0]}
)",
                                                        "twist.yaml");
  VerifiedSimulation sim(s);
  StepRecorder steps;
  ASSERT_TRUE(sim.run({&steps}).converged);
  const double j = std::numbers::pi * std::pow(kRadius, 4) / 2;
  const double angle = moment * kLength / (0.5 * kYoung * j);
  const Eigen::VectorXd& x = sim.state();
  const double body_angle = x[sim.model().body_dof(1) + 3];
  const int end = sim.model().node_dof(sim.model().beam(0).node(2 * 8));
  const double section_angle = std::atan2(x[end + 5], x[end + 4]);  // g1 = (0, 1, 0) turned about x
  std::printf("free body twisted: body %.8f rad, end section %.8f rad, (E/2) J reference %.8f rad\n",
              body_angle, section_angle, angle);
  EXPECT_NEAR(section_angle, angle, 2e-3 * angle);  // the torsion test's tolerance on the same element
  // The body leads its section by the penalty's error: for one section (a = 0, J = 2 w = R^2 / 2) a twist
  // delta gives C_t = 2 w delta, W = (k / 2) C_t^2 / J = k R^2 delta^2 / 4, a torsional stiffness k R^2 / 2.
  const double k = 1e3 * kYoung * std::numbers::pi * kRadius * kRadius / (kLength / 8);
  const double lead = moment / (0.5 * k * kRadius * kRadius);
  std::printf("free body twisted: lead %.4e rad, M / (k R^2 / 2) %.4e rad\n", body_angle - section_angle,
              lead);
  EXPECT_NEAR(body_angle - section_angle, lead, 1e-3 * lead);
  EXPECT_NEAR(steps.records.back().bodies[1].moment.x(), moment, 1e-9);
  EXPECT_NEAR(steps.records.back().sections[1].moment.x(), moment, 1e-12);
}

// Released, a body that pulled its fibre lets go: its support's reaction ramps down to zero over the stage
// and the fibre springs back to its length.
TEST(Bodies, ReleasedBodyLetsItsFibreSpringBack) {
  const scenario::Scenario s = scenario::parse_scenario(R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: f, material: m, radius: 0.05, length: 4, elements: 4}
bodies:
  - {name: a, beams: [f], at: start}
  - {name: b, beams: [f], at: end}
conditions:
  - {name: hold, type: clamp, bodies: [a]}
  - {name: pull, type: motion, bodies: [b]}
stages:
  - name: pull
    steps: 2
    motions:
      pull: {translation: [0.01, 0, 0]}
  - {name: let_go, steps: 4, release: [pull]}
)",
                                                        "release.yaml");
  VerifiedSimulation sim(s);
  StepRecorder steps;
  ASSERT_TRUE(sim.run({&steps}).converged);
  const double pulled = steps.records[1].bodies[1].force.x();
  EXPECT_NEAR(pulled, kYoung * std::numbers::pi * kRadius * kRadius * 0.01 / kLength, 0.01 * pulled);
  const simulation::StepRecord& mid = steps.records[3];  // half the release stage: half the force
  EXPECT_NEAR(mid.sections[1].force.x(), 0.5 * pulled, 1e-6 * pulled);
  const Eigen::VectorXd& x = sim.state();
  const double length = node_x(sim, x, 0, 8) - node_x(sim, x, 0, 0);
  EXPECT_NEAR(length, kLength, 1e-9);
  EXPECT_LT(steps.records.back().bodies[1].force.norm(), 1e-8);
}

// Two equal fibres side by side, each clamped at its start by a body of its own, their end bodies held across
// x and in rotation and bound in x by a bind; a force F along x on the first end body alone. Each fibre with
// its body penalty in series is a spring of stiffness s along x; the bind a spring k / 2 between the two
// bodies (energy (k/2) sum_i (u_i - u_mean)^2 = (k/4) (u_1 - u_2)^2). Hence the first fibre carries
// T_1 = F (2 s + k) / (2 (s + k)), the second T_2 = F k / (2 (s + k)), and the bind pulls the first body back
// by T_1 - F = -F k / (2 (s + k)): with k = 4000 s, F / 2 each to 1.2e-4.
TEST(Bodies, BoundBodiesShareTheForceOnOne) {
  const std::string text = R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: f1, material: m, radius: 0.05, length: 4, elements: 4}
  - {name: f2, material: m, radius: 0.05, length: 4, elements: 4, start: [0, 0.5, 0]}
bodies:
  - {name: a1, beams: [f1], at: start}
  - {name: a2, beams: [f2], at: start}
  - {name: b1, beams: [f1], at: end}
  - {name: b2, beams: [f2], at: end}
conditions:
  - {name: hold, type: clamp, bodies: [a1, a2]}
  - {name: guide, type: clamp, bodies: [b1, b2], dofs: [y, z, rotation]}
  - {name: pull, type: load, bodies: [b1], force: [0, 0, 0]}
)";
  const std::string bound = R"(  - {name: together, type: bind, bodies: [b1, b2], dofs: [x]}
stages:
  - name: pull
    steps: 2
    loads:
      pull: {force: [0.0314, 0, 0]}
)";
  const double force = 0.0314;  // strain about 5e-4 in each fibre
  VerifiedSimulation sim(scenario::parse_scenario(text + bound, "bind.yaml"));
  StepRecorder steps;
  ASSERT_TRUE(sim.run({&steps}).converged);
  const simulation::StepRecord& last = steps.records.back();
  const double t1 = last.bodies[2].force.x(), t2 = last.bodies[3].force.x();
  const double u1 = sim.state()[sim.model().body_dof(2)] - kLength;
  const double u2 = sim.state()[sim.model().body_dof(3)] - kLength;
  // s from the fibres' own response: T_i = s u_i (the same spring for both, linear to the strain's 5e-4).
  const double s_spring = (t1 - t2) / (u1 - u2);
  const double area = std::numbers::pi * kRadius * kRadius;
  const double k = 1e3 * kYoung * area / (kLength / kElements);
  const double t1_expected = force * (2 * s_spring + k) / (2 * (s_spring + k));
  std::printf(
      "bind: T1 %.10f N, T2 %.10f N (F/2 %.4f), expected T1 %.10f N; s %.4f N/mm (E A / L %.4f), "
      "bind force on b1 %.10f N\n",
      t1, t2, 0.5 * force, t1_expected, s_spring, kYoung * area / kLength, last.sections[3].force.x());
  EXPECT_NEAR(t1 + t2, force, 1e-9 * force);  // no force lost
  EXPECT_NEAR(t1, t1_expected, 1e-7 * force);
  // The springs: the fibre's E A / L, up to St-Venant-Kirchhoff's tangent stiffening at this strain (3 x
  // 5e-4) less the body penalty in series (s / k = 2.5e-4): 1.3e-3 (measured 1.0e-3).
  EXPECT_NEAR(s_spring, kYoung * area / kLength, 2e-3 * s_spring);
  // The bind's force on its first body, as steps.csv reports it.
  EXPECT_NEAR(last.sections[3].force.x(), t1 - force, 1e-9 * force);
  EXPECT_NEAR(last.sections[3].force.x(), -0.5 * k * (u1 - u2), 1e-9 * force);

  // Without the bind the loaded fibre carries everything.
  const std::string unbound = R"(stages:
  - name: pull
    steps: 2
    loads:
      pull: {force: [0.0314, 0, 0]}
)";
  VerifiedSimulation alone(scenario::parse_scenario(text + unbound, "alone.yaml"));
  StepRecorder alone_steps;
  ASSERT_TRUE(alone.run({&alone_steps}).converged);
  EXPECT_NEAR(alone_steps.records.back().bodies[2].force.x(), force, 1e-9 * force);
  EXPECT_LT(std::abs(alone_steps.records.back().bodies[3].force.x()), 1e-9 * force);
}

}  // namespace
}  // namespace nodus::verification
