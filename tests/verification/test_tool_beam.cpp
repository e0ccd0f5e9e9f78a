// A tool beam (the paper's clamping beams, Sect. 7.2.1): a rigid condition moves every node of a short beam,
// which presses a simply supported beam at mid-span, turns about a pivot, and is then taken out of contact.
// References: the mid-span stiffness 48 E I / L^3 of the simply supported beam while pressed, the closed-form
// rigid motion r = p + u + Q (r0 - p) of every tool node, and the straight beam once the tool is removed.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "step_recorder.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {
namespace {

constexpr double kLength = 10.0, kRadius = 0.1, kYoung = 4000.0;
constexpr double kGap0 = 0.01;   // initial surface gap [mm]
constexpr double kDelta = 0.05;  // tool travel [mm]

/// The beam is pinned at its start and on a roller at its end (no membrane tension). The tool lies across it
/// above mid-span; press: down by kDelta; turn: 30 degrees about the vertical through its centre, still
/// pressing (a circular section pressed by a straight one: the force does not depend on the crossing
/// angle); lift: taken out of contact, where it stays.
const char* kScenario = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: m, radius: 0.1, length: 10, elements: 100, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: m, radius: 0.1, length: 2, elements: 4, start: [0, -1, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: pin, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: roller, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool, pivot: [0, 0, 0.21]}
stages:
  - name: press
    steps: 5
    motions:
      press: {translation: [0, 0, -0.05]}
  - name: turn
    steps: 3
    motions:
      press: {translation: [0, 0, -0.05], rotation: [0, 0, 30]}
  - {name: lift, steps: 1, contact_off: [tool]}
contact: {self_contact: false}
)";

TEST(ToolBeam, PressesTurnsAndIsRemoved) {
  VerifiedSimulation sim(scenario::parse_scenario(kScenario, "tool.yaml"));
  StepRecorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  ASSERT_EQ(recorder.records.size(), 9u);
  const double inertia = std::numbers::pi * std::pow(kRadius, 4) / 4.0;
  const double compliance = std::pow(kLength, 3) / (48.0 * kYoung * inertia);
  const double p_max = sim.contact_laws().max_penetration;
  const model::Model& model = sim.model();
  const beam::Beam& tool = model.beam(1);
  const beam::Beam& beam = model.beam(0);
  const int mid = beam.num_nodes() / 2;

  for (std::size_t k = 0; k < recorder.records.size(); ++k) {
    const simulation::StepRecord& r = recorder.records[k];
    const Eigen::VectorXd& x = recorder.states[k];
    // The rigid motion of every tool node, in closed form: pivot p = (0, 0, 0.21), translation u down,
    // rotation about z in the turn stage (load time 1..2).
    const double t = r.time;
    const Eigen::Vector3d pivot(0, 0, 0.21), u(0, 0, -kDelta * std::min(t, 1.0));
    const double angle = std::clamp(t - 1.0, 0.0, 1.0) * 30.0 * std::numbers::pi / 180.0;
    const Eigen::Matrix3d q = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (int n = 0; n < tool.num_nodes(); ++n) {
      const Eigen::Vector3d r0(0.0, -1.0 + 0.25 * n, 0.21);
      const Eigen::Vector3d expected = pivot + u + q * (r0 - pivot);
      EXPECT_LT((x.segment<3>(9 * tool.node(n)) - expected).norm(), 1e-12) << "node " << n << " t " << t;
      EXPECT_LT((x.segment<3>(9 * tool.node(n) + 3) - q * Eigen::Vector3d::UnitX()).norm(), 1e-12);
    }
    const double deflection = -x[9 * beam.node(mid) + 2];
    const double tool_force = -r.sections[2].force.z();  // the support of the tool holds it against the beam
    std::printf(
        "t %.3f: tool force %.6e N, sum R_N %.6e N, mid-span deflection %.6e mm, penetration %.3f "
        "p_max; Newton %d, detections %d, normal iterations %d\n",
        t, tool_force, r.normal_force, deflection, r.penetration_ratio, r.newton_iterations, r.detections,
        r.normal_iterations);
    if (t <= 2.0 + 1e-12) {
      // Pressed: the force is what the beam's mid-span stiffness needs for the travel less the initial gap
      // and the penetration; it acts through the contact elements.
      const double reference =
          std::max(0.0, kDelta * std::min(t, 1.0) - kGap0 - r.penetration_ratio * p_max) / compliance;
      EXPECT_LE(r.penetration_ratio, 1.0);
      if (kDelta * std::min(t, 1.0) - kGap0 <= 1e-9) {  // not yet pressing
        EXPECT_NEAR(tool_force, 0.0, 1e-12);
        continue;
      }
      // As in the crossed-beams test: shear and Poisson effects of order (R / L)^2 = 1e-4, contact elements
      // within h_c / 2 of the crossing. Hence 0.5 %.
      EXPECT_NEAR(tool_force, reference, 5e-3 * reference);
      EXPECT_NEAR(deflection, reference * compliance, 5e-3 * reference * compliance);
      // Equilibrium of the tool: its support carries the sum of the normal reactions (to the solver's
      // residual floor, 2e-5 of these forces; see test_contact_crossing.cpp).
      EXPECT_NEAR(r.normal_force, tool_force, 1e-4 * tool_force);
    } else {
      // Removed: no contact elements, the beam springs back straight and the tool's support carries nothing.
      EXPECT_EQ(r.contact_elements, 0);
      EXPECT_NEAR(tool_force, 0.0, 1e-12);
      EXPECT_NEAR(deflection, 0.0, 1e-9);
    }
  }
}

}  // namespace
}  // namespace nodus::verification
