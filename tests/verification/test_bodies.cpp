// Rigid bodies bound to fibre ends by averaged conditions (docs/bodies.md), against closed forms: a bundle
// of parallel fibres pulled by its bodies carries N lambda E A E33 (uniaxial St-Venant-Kirchhoff, as in
// test_tension_torsion.cpp), its bound ends follow the body to within the penalty's error k n C_c = F, and
// a rigid rotation of everything leaves every fibre rigidly rotated and every reaction zero.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "step_recorder.hpp"

namespace nodus::verification {
namespace {

constexpr double kRadius = 0.05, kLength = 4.0, kYoung = 4000.0, kPoisson = 0.3;
constexpr int kElements = 4;

/// One roving of seven fibres (a hexagon around one), bodies at both ends; `extra` appends conditions and
/// stages.
std::string bundle(const std::string& extra) {
  return R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
yarns:
  - {name: b, rovings: 1, fibres_per_roving: 7, fibre_radius: 0.05, length: 4, elements: 4, material: m}
)" + extra;
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
  simulation::Simulation sim(s);
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
  const double tie = 1e-6 * k * 0.5 * lag * std::sqrt(static_cast<double>(n));
  std::printf("bundle: tie force %.3e N, k_t lag / 2 sqrt(n) %.3e N\n", end.tie, tie);
  EXPECT_NEAR(end.tie, tie, 0.1 * tie);
}

TEST(Bodies, RigidRotationOfEverythingLeavesNoReaction) {
  const scenario::Scenario s = scenario::parse_scenario(bundle(R"(conditions:
  - {name: start, type: motion, bodies: [b.r1.start], pivot: [2, 0, 0]}
  - {name: end, type: motion, bodies: [b.r1.end], pivot: [2, 0, 0]}
stages:
  - name: turn
    steps: 3
    motions:
      start: {rotation: [0, 90, 30], translation: [0.5, 0, 0]}
      end: {rotation: [0, 90, 30], translation: [0.5, 0, 0]}
)"),
                                                        "bundle.yaml");
  simulation::Simulation sim(s);
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

}  // namespace
}  // namespace nodus::verification
