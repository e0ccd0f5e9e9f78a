// Two simply supported beams crossing at right angles, pressed together by moving the upper beam's supports
// down (displacement control) [Durville 2012, Sect. 5.1]: in the small-deflection range the contact force is
// F = (delta - g0 - p) / (L1^3 / (48 E I1) + L2^3 / (48 E I2)), with p the penetration the penalty allows.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {
namespace {

constexpr double kLength = 10.0, kRadius = 0.1, kYoung = 4000.0;
constexpr double kGap0 = 0.01;   // initial surface gap [mm]
constexpr double kDelta = 0.05;  // support displacement [mm]

/// Pinned at the start (and the rotation about the axis held by g1z), on a roller at the end: no membrane
/// tension, so the beams follow the simply supported formula.
const char* kScenario = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: lower, material: m, radius: 0.1, length: 10, elements: 200, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: upper, material: m, radius: 0.1, length: 10, elements: 200, start: [0, -5, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: l0, type: clamp, beam: lower, at: start, dofs: [position, g1z]}
  - {name: l1, type: clamp, beam: lower, at: end, dofs: [y, z]}
  - {name: u0, type: motion, beam: upper, at: start, dofs: [position, g1z]}
  - {name: u1, type: motion, beam: upper, at: end, dofs: [x, z]}
stages:
  - name: press
    steps: 5
    motions:
      u0: {translation: [0, 0, -0.05]}
      u1: {translation: [0, 0, -0.05]}
contact: {self_contact: false}
)";

class Recorder : public simulation::StepObserver {
 public:
  std::vector<simulation::StepRecord> records;
  void on_step(const simulation::Simulation&, const simulation::StepRecord& r) override {
    records.push_back(r);
  }
};

TEST(ContactCrossing, ForceMatchesTheSimplySupportedBeams) {
  VerifiedSimulation sim(scenario::parse_scenario(kScenario, "crossing.yaml"));
  Recorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  const double inertia = std::numbers::pi * std::pow(kRadius, 4) / 4.0;
  const double compliance = 2.0 * std::pow(kLength, 3) / (48.0 * kYoung * inertia);
  const double p_max = sim.contact_laws().max_penetration;
  for (const simulation::StepRecord& r : recorder.records) {
    const double delta = kDelta * r.time;
    // The contact force, measured as the upper beam's support reactions (sections 2 and 3).
    const double support = -(r.sections[2].force.z() + r.sections[3].force.z());
    const double penetration = r.penetration_ratio * p_max;
    const double reference = std::max(0.0, delta - kGap0 - penetration) / compliance;
    std::printf(
        "delta %.3f mm: F = %.6e N (supports), %.6e N (sum of R_N); reference %.6e N; error %.3f %%; "
        "penetration %.3f p_max; Newton %d, detections %d, normal iterations %d\n",
        delta, support, r.normal_force, reference,
        delta - kGap0 > 1e-9 ? 100.0 * (support / reference - 1.0) : 0.0, r.penetration_ratio,
        r.newton_iterations, r.detections, r.normal_iterations);
    EXPECT_LE(r.penetration_ratio, 1.0);
    if (delta - kGap0 <= 1e-9) {  // not yet touching
      // Zero, to within the residual Newton accepts (its rounding floor, 6.4e-9 N, below): 7e-12 N with
      // the directors turned by the rotation update, 1e-13 N when they were added (two more iterations).
      EXPECT_NEAR(support, 0.0, 1e-9);
      continue;
    }
    // Equilibrium of the upper beam: the support reactions carry the contact force, to within the residual
    // the solver accepts. Here that is its rounding floor, 6.4e-9 N (EquilibriumProblem), 2e-5 of the
    // smallest force; the loop on contact elements stops as soon as a new set leaves the residual below it.
    EXPECT_NEAR(r.normal_force, support, 1e-4 * support);
    // The contact elements sit at most h_c / 2 = 0.0125 mm from the crossing point, where the circular
    // sections leave a clearance of 2 R (1 - cos) < 1e-4 p_max; shear and the Poisson effect of the 9-dof
    // beams are of order (R / L)^2 = 1e-4. Hence 0.5 %.
    EXPECT_NEAR(support, reference, 5e-3 * reference);
  }
}

}  // namespace
}  // namespace nodus::verification
