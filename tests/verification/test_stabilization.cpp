// Viscous stabilisation (stages[].stabilization): a drag -eta w_n (x_n - x_n,prev) / dt on every node, w_n
// the node's share of the beam length. A cantilever is dragged sideways by its clamped end at constant speed
// v: once the transient has died out every node moves at v, so the clamp carries the whole drag eta L v and
// the beam bends as a cantilever under the uniform load q = eta v, tip lag q L^4 / (8 E I). The drag then
// decays to exactly 0 while the end holds still: the beam must be straight again and the clamp unloaded.
// The directors feel the drag of the section's points averaged over the disc, eta R^2/4 each: a rod spun
// about its axis by its clamp at rate omega carries, once every section turns at omega, a clamp moment sum_n
// 2 (eta R^2/4) w_n omega = eta R^2 L omega / 2.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "step_recorder.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {
namespace {

constexpr double kLength = 10.0, kRadius = 0.1, kYoung = 4000.0;
constexpr double kEta = 2.5e-5;  // N s/mm^2
constexpr double kSpeed = 1.0;   // mm per s of load time

const char* kScenario = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 20}
conditions:
  - {name: grip, type: motion, beam: rod, at: start}
stages:
  - name: drag
    steps: 50
    stabilization: 2.5e-5
    motions:
      grip: {translation: [0, 1, 0]}
  - name: settle
    steps: 30
    stabilization: 2.5e-5
    stabilization_end: 0
)";

TEST(Stabilization, DraggedCantileverCarriesTheDragAndRelaxesWhenItVanishes) {
  const scenario::Scenario scenario = scenario::parse_scenario(kScenario, "drag.yaml");
  VerifiedSimulation sim(scenario);
  StepRecorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  const beam::Beam& rod = sim.model().beam(0);
  const int tip = rod.node(rod.num_nodes() - 1);
  const double inertia = std::numbers::pi * std::pow(kRadius, 4) / 4.0;
  const double q = kEta * kSpeed;

  // The last step of the drag: the transient decays by 1 / (1 + dt / tau) per step, tau = eta / (E I k^4)
  // = 0.06 s for the first mode, dt = 0.02 s: 2e-6 after 50 steps.
  std::size_t last_drag = 0;
  while (last_drag + 1 < recorder.records.size() && recorder.records[last_drag + 1].stage == 0) ++last_drag;
  const simulation::StepRecord& dragged = recorder.records[last_drag];
  const Eigen::VectorXd& x = recorder.states[last_drag];
  const double reaction = dragged.sections[0].force.y();
  std::printf(
      "drag: clamp force %.9e N (eta L v = %.9e), drag norm %.3e N, tip lag %.6e mm (q L^4/8EI %.6e)\n",
      reaction, kEta * kLength * kSpeed, dragged.stabilization_force, x[0 + 1] - x[9 * tip + 1],
      q * std::pow(kLength, 4) / (8.0 * kYoung * inertia));
  // The clamp carries the whole drag: the Simpson weights add up to L exactly. Tolerance: the solver's
  // residual floor (1e-10 N here) over eta L v = 2.5e-4 N, and the transient (2e-6).
  EXPECT_NEAR(reaction, kEta * kLength * kSpeed, 1e-5 * kEta * kLength * kSpeed);
  EXPECT_GT(dragged.stabilization_force, 0.0);
  // Tip lag: Euler-Bernoulli under uniform load; shear adds q L^2 / (2 k G A) = 3e-4 of it and the finite
  // rotation (lag / L = 1e-2) terms of order 1e-4: 0.2 %.
  const double lag = x[1] - x[9 * tip + 1];
  const double reference = q * std::pow(kLength, 4) / (8.0 * kYoung * inertia);
  EXPECT_NEAR(lag, reference, 2e-3 * reference);

  // The drag decays to exactly 0 with the end still: straight again, nothing on the clamp.
  const simulation::StepRecord& settled = recorder.records.back();
  const Eigen::VectorXd& y = recorder.states.back();
  EXPECT_EQ(settled.stabilization_force, 0.0);
  EXPECT_NEAR(settled.sections[0].force.norm(), 0.0, 1e-9);
  for (int n = 0; n < rod.num_nodes(); ++n) EXPECT_NEAR(y[9 * rod.node(n) + 1], 1.0, 1e-9) << "node " << n;
}

TEST(Stabilization, ReaderChecksTheValues) {
  const std::string head = R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 2}
stages:
)";
  const auto error_of = [&](const std::string& stage) -> std::string {
    try {
      scenario::parse_scenario(head + stage, "s.yaml");
    } catch (const scenario::ScenarioError& e) {
      return e.what();
    }
    return {};
  };
  EXPECT_EQ(error_of("  - {name: a, steps: 1, stabilization: -1}\n"),
            "s.yaml:6: stages[0].stabilization: expected a number >= 0 (N s/mm^2), got -1");
  EXPECT_EQ(
      error_of("  - {name: a, steps: 1, stabilization_end: 0.1}\n"),
      "s.yaml:6: stages[0].stabilization_end: expected 0 when stabilization is 0 (the decay is geometric "
      "from stabilization), got 0.1");
  const scenario::Scenario s = scenario::parse_scenario(
      head + "  - {name: a, steps: 1, stabilization: 0.5, stabilization_end: 0}\n", "s.yaml");
  EXPECT_EQ(s.stages[0].stabilization, 0.5);
  EXPECT_EQ(s.stages[0].stabilization_end, 0.0);
  EXPECT_NE(scenario::describe(s).find("stabilization_end: 0"), std::string::npos);
}

const char* kSpin = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 20}
conditions:
  - {name: grip, type: motion, beam: rod, at: start}
stages:
  - name: spin
    steps: 50
    stabilization: 0.01
    motions:
      grip: {rotation: [90, 0, 0]}
)";

TEST(Stabilization, SpunRodCarriesTheDragOfItsSectionsOnTheDirectors) {
  VerifiedSimulation sim(scenario::parse_scenario(kSpin, "spin.yaml"));
  StepRecorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  // Over a step dt each director turns by omega dt along a chord: the moment of its drag is
  // g x (g - g_prev) / dt = sin(omega dt) / dt, not omega (1.6e-4 less here).
  const double omega = std::numbers::pi / 2.0, dt = 1.0 / 50.0;  // rad per s of load time; s
  const double eta = 0.01, reference = eta * kRadius * kRadius * kLength * std::sin(omega * dt) / dt / 2.0;
  const simulation::StepRecord& last = recorder.records.back();
  std::printf(
      "spin: clamp moment %.9e N mm (eta R^2 L sin(omega dt) / dt / 2 = %.9e), other components %.2e %.2e\n",
      last.sections[0].moment.x(), reference, last.sections[0].moment.y(), last.sections[0].moment.z());
  // Transient: tau = eta R^2 / 2 / (G J (pi / 2L)^2) = 8e-3 s against dt = 0.02 s, gone after 50 steps; the
  // directors' length changes (Poisson effect of the twist, strain of order (R theta')^2 = 1e-7) scale the
  // drag by |g|^2. Tolerance 1e-5.
  EXPECT_NEAR(last.sections[0].moment.x(), reference, 1e-5 * reference);
  EXPECT_LT(last.sections[0].force.norm(), 1e-9);
}

}  // namespace
}  // namespace nodus::verification
