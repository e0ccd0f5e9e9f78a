// A converged state in which a section has turned into the orientation barrier (det[g1, g2, r'] < 1/2) is not
// accepted: the step is cut back (simulation.cpp, docs/model.md). The case forces it: one element held on the
// x axis and shortened by 70 % by moving its end, so that r' = (1 - 0.7 t) e_x at load time t. The directors
// can stretch only against the section's stiffness, so J = r'.(g1 x g2) falls with |r'|: without the barrier
// to 0.38 at the end. With the barrier the run stops once a step would end below 1/2, with the failure named,
// and every step it accepted has J >= 1/2; without it (fold_barrier: 0) nothing is checked.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::simulation {
namespace {

std::string scenario_text(double fold_barrier) {
  return R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: nylon, radius: 0.1, length: 1, elements: 1, start: [0, 0, 0]}
conditions:
  - {name: hold, type: clamp, beam: rod, at: start, dofs: [position]}
  - {name: mid, type: clamp, beam: rod, at: 1, dofs: [y, z]}
  - {name: push, type: motion, beam: rod, at: end, dofs: [position]}
stages:
  - name: push
    steps: 6
    motions:
      push: {translation: [-0.7, 0, 0]}
solver: {max_cutbacks: 4, linear_solver: klu, fold_barrier: )" +
         std::to_string(fold_barrier) + "}\n";
}

class Orientations : public StepObserver {
 public:
  std::vector<double> min_orientation;
  void on_step(const Simulation& /*sim*/, const StepRecord& r) override {
    min_orientation.push_back(r.min_orientation);
  }
};

TEST(OrientationAcceptance, AStateInsideTheBarrierIsCutBackAndTheRunStops) {
  Simulation sim(scenario::parse_scenario(scenario_text(1.0), "turn.yaml"));
  Orientations seen;
  const RunSummary summary = sim.run({&seen});
  EXPECT_FALSE(summary.converged);
  EXPECT_NE(summary.failure.find("orientation barrier"), std::string::npos) << summary.failure;
  ASSERT_GE(seen.min_orientation.size(), 5U);  // the first five nominal steps end at J >= 0.52
  for (double j : seen.min_orientation) EXPECT_GE(j, 0.5);
}

TEST(OrientationAcceptance, WithoutTheBarrierNothingIsChecked) {
  Simulation sim(scenario::parse_scenario(scenario_text(0.0), "turn.yaml"));
  Orientations seen;
  const RunSummary summary = sim.run({&seen});
  ASSERT_TRUE(summary.converged) << summary.failure;
  ASSERT_EQ(seen.min_orientation.size(), 6U);
  // Shortened by 70 %: J about 0.3 times the directors' stretch, below 1/2.
  EXPECT_LT(seen.min_orientation.back(), 0.5);
}

}  // namespace
}  // namespace nodus::simulation
