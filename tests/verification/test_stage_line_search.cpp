// A stage's own line search (stages[].line_search) against the solver section's (solver.line_search). The
// cantilever bent into a half circle by an end moment, M = pi EI / L (tip at (0, 2 L / pi) from the root),
// in two stages of 5 steps each: the line search changes Newton's iterates (the elastica takes more
// iterations with it, docs/model.md) but not the equilibrium. A stage that names its own setting must run
// exactly as a run whose solver section has that setting, and a stage that does not must follow the solver
// section.

#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "cantilever.hpp"
#include "step_recorder.hpp"

namespace nodus::verification {
namespace {

struct Bent {
  int iterations = 0;
  std::vector<int> stage_iterations;  // per stage
  Eigen::VectorXd state;
  Eigen::Vector3d tip;
};

/// The half circle in two stages (half the moment, then all of it); `solver` is solver.line_search,
/// `first` and `second` each stage's own setting.
Bent bend(bool solver, scenario::StageSwitch first, scenario::StageSwitch second) {
  BeamCase c;
  c.radius = 0.1;  // L / R = 1000
  scenario::Scenario s = single_beam(c);
  s.solver.line_search = solver;
  add_condition(s, "root", scenario::ConditionType::clamp, false);
  const int tip = add_condition(s, "tip", scenario::ConditionType::load, true);
  const double moment = std::numbers::pi * c.ei() / c.length;
  for (const auto& [name, fraction, choice] :
       {std::tuple{"half", 0.5, first}, std::tuple{"full", 1.0, second}}) {
    scenario::StageSpec stage;
    stage.name = name;
    stage.steps = 5;
    stage.line_search = choice;
    stage.loads.push_back({tip, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, fraction * moment)});
    s.stages.push_back(stage);
  }
  VerifiedSimulation sim(s);
  StepRecorder recorder;
  const simulation::RunSummary summary = sim.run({&recorder});
  EXPECT_TRUE(summary.converged) << summary.failure;
  Bent out;
  out.iterations = summary.newton_iterations;
  out.stage_iterations.assign(2, 0);
  for (const simulation::StepRecord& r : recorder.records)
    out.stage_iterations.at(static_cast<std::size_t>(r.stage)) += r.newton_iterations;
  out.state = sim.state();
  out.tip = centre(sim, 2 * c.elements) - centre(sim, 0);
  return out;
}

TEST(StageLineSearch, AStageTakesItsOwnSettingOrTheSolverSections) {
  using scenario::StageSwitch;
  const Bent off = bend(false, StageSwitch::solver, StageSwitch::solver);
  const Bent on = bend(true, StageSwitch::solver, StageSwitch::solver);
  std::printf(
      "half circle in 2 x 5 steps: %d Newton iterations without the line search (%d + %d), %d with it "
      "(%d + %d); tips %.3e mm apart\n",
      off.iterations, off.stage_iterations[0], off.stage_iterations[1], on.iterations, on.stage_iterations[0],
      on.stage_iterations[1], (off.tip - on.tip).norm());
  // The line search changes the iterates of both stages, not the equilibrium (the closed form's tip, 2 L / pi
  // = 6.37 mm from the root, within the solver's tolerance).
  ASSERT_NE(off.stage_iterations[0], on.stage_iterations[0]);
  ASSERT_NE(off.stage_iterations[1], on.stage_iterations[1]);
  EXPECT_LT((off.tip - on.tip).norm(), 1e-6);

  // Each stage's own setting, against the solver section's: the same run, exactly.
  const Bent own_on = bend(false, StageSwitch::on, StageSwitch::on);
  EXPECT_EQ(own_on.stage_iterations, on.stage_iterations);
  EXPECT_EQ(own_on.state, on.state);
  const Bent own_off = bend(true, StageSwitch::off, StageSwitch::off);
  EXPECT_EQ(own_off.stage_iterations, off.stage_iterations);
  EXPECT_EQ(own_off.state, off.state);

  // Mixed: the first stage as the solver section says (off), the second with its own line search. The first
  // stage is the run without it; the second starts from that state.
  const Bent mixed = bend(false, StageSwitch::solver, StageSwitch::on);
  EXPECT_EQ(mixed.stage_iterations[0], off.stage_iterations[0]);
  EXPECT_NE(mixed.stage_iterations[1], off.stage_iterations[1]);
  EXPECT_LT((mixed.tip - off.tip).norm(), 1e-6);
}

}  // namespace
}  // namespace nodus::verification
