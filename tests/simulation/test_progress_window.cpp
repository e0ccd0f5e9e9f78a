// solver.progress_window gives a step attempt up for too little progress, but never the last attempt that
// max_cutbacks allows (simulation.cpp): there Newton keeps its whole budget, so the rule cannot end a run
// that would have gone on. The case forces it: a cantilever of 20 elements rolled into a full circle by an
// end moment in 4 steps, with a rule that no Newton solve of 3 or more iterations passes (a window of 1
// asking for a fall by 1e12 in one iteration) and 2 cutbacks. The first step needs more than 3 iterations
// even at a quarter of its size: the run goes on only because its third attempt was not judged. Elastic, the
// rolled-up state does not depend on the steps taken: it is the run's without the rule, to Newton's
// tolerance.

#include <string>

#include <gtest/gtest.h>

#include "../verification/step_recorder.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::simulation {
namespace {

std::string scenario_text(const std::string& rule) {
  return R"(materials:
  - {name: polyamide, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: polyamide, radius: 0.1, length: 20, elements: 20, start: [0, 0, 0]}
conditions:
  - {name: root, type: clamp, beam: rod, at: start}
  - {name: tip, type: load, beam: rod, at: end}
stages:
  - name: roll_up
    steps: 4
    loads:
      tip: {moment: [0, 0, 0.0986960440]}
solver: {linear_solver: cholmod, max_cutbacks: 2)" +
         rule + "}\n";
}

TEST(ProgressWindow, TheLastAttemptAStepIsAllowedKeepsNewtonsWholeBudget) {
  Simulation plain(scenario::parse_scenario(scenario_text(""), "roll.yaml"));
  verification::StepRecorder plain_steps;
  const RunSummary a = plain.run({&plain_steps});
  ASSERT_TRUE(a.converged) << a.failure;

  Simulation ruled(
      scenario::parse_scenario(scenario_text(", progress_window: 1, progress_ratio: 1e-12"), "roll.yaml"));
  verification::StepRecorder ruled_steps;
  const RunSummary b = ruled.run({&ruled_steps});
  ASSERT_TRUE(b.converged) << b.failure;
  ASSERT_FALSE(ruled_steps.records.empty());
  // The first step converged on its last attempt, in more iterations than the rule lets through.
  EXPECT_EQ(ruled_steps.records.front().cutbacks, 2);
  EXPECT_GT(ruled_steps.records.front().newton_iterations, 3);
  EXPECT_GT(ruled_steps.records.size(), plain_steps.records.size());
  EXPECT_LT((ruled.state() - plain.state()).lpNorm<Eigen::Infinity>(), 1e-6);
}

}  // namespace
}  // namespace nodus::simulation
