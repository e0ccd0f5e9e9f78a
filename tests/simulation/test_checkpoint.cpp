// Saved states (output/checkpoint.hpp): a run stopped after any step, saved to checkpoint bytes, read back
// into a new Simulation and continued gives exactly the run that was never stopped (the reference: the same
// computation done in one go), and damaged or foreign checkpoints are refused with one line.
//
// The scenario exercises every part of the state: a tool beam dragged with friction (contact geometry,
// penalties, reversible slips), a moment load (its turn count), a clamp activated and then released (anchors,
// ramped-down support), motion keyframes inside a stage, and several steps per stage (the secant predictor).

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/persistence/checkpoint_files.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::simulation {
namespace {

const std::string kScenario = R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 16, start: [-5, 0, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 2, start: [0, -1, 0.31],
     direction: [0, 1, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: hold, type: clamp, beam: beam, at: 8, dofs: [x], active: false}
  - {name: press, type: rigid, beam: tool}
  - {name: twist, type: load, beam: beam, at: 12}
stages:
  - name: press
    steps: 2
    motions:
      press: {translation: [0, 0, -0.1]}
    loads:
      twist: {moment: [0.0005, 0, 0]}
  - name: drag
    steps: 3
    activate: [hold]
    motions:
      press:
        keyframes:
          - {at: 0.5, translation: [0, 0.1, -0.1]}
          - {at: 1, translation: [0, 0.25, -0.1], rotation: [0, 0, 5]}
  - name: let_go
    steps: 3
    release: [hold]
    loads:
      twist: {moment: [-0.0005, 0, 0]}
contact:
  self_contact: false
  friction: 0.3
)";

constexpr int kSteps = 8;  // converged steps of the whole run (no cutbacks)

class Recorder : public StepObserver {
 public:
  std::vector<StepRecord> records;
  std::vector<int> stage_ends;
  int finished = 0;
  void on_step(const Simulation& /*sim*/, const StepRecord& r) override { records.push_back(r); }
  void on_stage_end(const Simulation& /*sim*/, int stage) override { stage_ends.push_back(stage); }
  void on_finish(const Simulation& /*sim*/, const RunSummary& /*summary*/) override { ++finished; }
};

/// Bitwise equality of two records (all that steps.csv shows).
void expect_same(const StepRecord& a, const StepRecord& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.stage, b.stage);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.newton_iterations, b.newton_iterations);
  EXPECT_EQ(a.cutbacks, b.cutbacks);
  EXPECT_EQ(a.residual, b.residual);
  EXPECT_EQ(a.increment, b.increment);
  EXPECT_EQ(a.zones, b.zones);
  EXPECT_EQ(a.contact_elements, b.contact_elements);
  EXPECT_EQ(a.detections, b.detections);
  EXPECT_EQ(a.normal_iterations, b.normal_iterations);
  EXPECT_EQ(a.penetration_ratio, b.penetration_ratio);
  EXPECT_EQ(a.normal_force, b.normal_force);
  EXPECT_EQ(a.tangential_force, b.tangential_force);
  EXPECT_EQ(a.slipping, b.slipping);
  EXPECT_EQ(a.step_size, b.step_size);
  EXPECT_EQ(a.regime_changes, b.regime_changes);
  EXPECT_EQ(a.cutback_causes, b.cutback_causes);
  ASSERT_EQ(a.sections.size(), b.sections.size());
  for (std::size_t c = 0; c < a.sections.size(); ++c) {
    EXPECT_EQ(a.sections[c].force, b.sections[c].force) << "condition " << c;
    EXPECT_EQ(a.sections[c].moment, b.sections[c].moment) << "condition " << c;
  }
}

std::string error_of(const std::string& bytes, const scenario::Scenario& s) {
  try {
    nodus::persistence::decode_checkpoint(bytes, s, "test.nodus-state");
  } catch (const scenario::ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Checkpoint, ResumedRunEqualsUninterrupted) {
  const scenario::Scenario s = scenario::parse_scenario(kScenario, "resume.yaml");
  Simulation reference(s);
  Recorder all;
  const RunSummary whole = reference.run({&all});
  ASSERT_TRUE(whole.converged) << whole.failure;
  ASSERT_EQ(static_cast<int>(all.records.size()), kSteps);
  EXPECT_EQ(all.stage_ends, (std::vector<int>{0, 1, 2}));
  ASSERT_FALSE(reference.contact_states().empty());

  for (int k = 1; k < kSteps; ++k) {
    SCOPED_TRACE("stopped after step " + std::to_string(k));
    Simulation first(s);
    Recorder before;
    const RunSummary stopped = first.run({&before}, {k});
    EXPECT_TRUE(stopped.interrupted);
    EXPECT_FALSE(stopped.converged);
    EXPECT_EQ(before.finished, 0);  // as if killed
    EXPECT_EQ(stopped.new_steps, k);
    const std::string bytes = nodus::persistence::encode_checkpoint(s, first.snapshot());

    Simulation second(s);
    second.restore(nodus::persistence::decode_checkpoint(bytes, s, "memory"), StartKind::resumed);
    EXPECT_EQ(second.steps(), k);
    Recorder after;
    const RunSummary rest = second.run({&after});
    ASSERT_TRUE(rest.converged) << rest.failure;
    EXPECT_EQ(rest.steps, kSteps);
    EXPECT_EQ(rest.new_steps, kSteps - k);
    EXPECT_EQ(rest.newton_iterations, whole.newton_iterations);

    ASSERT_EQ(before.records.size() + after.records.size(), all.records.size());
    for (std::size_t i = 0; i < all.records.size(); ++i)
      expect_same(i < before.records.size() ? before.records[i] : after.records[i - before.records.size()],
                  all.records[i]);
    EXPECT_EQ(second.time(), reference.time());
    EXPECT_EQ((second.state() - reference.state()).cwiseAbs().maxCoeff(), 0.0);
    ASSERT_EQ(second.contact_states().size(), reference.contact_states().size());
    for (std::size_t e = 0; e < reference.contact_states().size(); ++e) {
      EXPECT_EQ(second.contact_states()[e].tangential, reference.contact_states()[e].tangential);
      EXPECT_EQ(second.contact_states()[e].reversible, reference.contact_states()[e].reversible);
      EXPECT_EQ(second.contact_states()[e].normal_reaction, reference.contact_states()[e].normal_reaction);
    }
    // The final states save to the same bytes (the counters of wall time aside: compare without them).
    SimulationState x = second.snapshot(), y = reference.snapshot();
    x.counters = y.counters = {};
    EXPECT_EQ(nodus::persistence::encode_checkpoint(s, x), nodus::persistence::encode_checkpoint(s, y));
  }
}

/// Records the linear solver each stage runs with.
class StageSolvers : public StepObserver {
 public:
  std::vector<std::string> names;
  void on_stage(const Simulation& sim, int /*stage*/) override { names.push_back(sim.linear_solver_name()); }
};

// A stage's own linear solver (stages[].linear_solver): the run takes it from that stage on and returns to
// the solver section's where a stage has none; it reaches the equilibrium of the run with one solver to
// round-off, and a run stopped after any step and resumed repeats the uninterrupted one exactly (each change
// of solver starts a new one, as a resumed run does).
TEST(Checkpoint, AStageTakesItsOwnLinearSolverAndAResumedRunRepeatsIt) {
  std::string text = kScenario;
  const auto insert_after = [&text](const std::string& line, const std::string& added) {
    const std::size_t at = text.find(line);
    ASSERT_NE(at, std::string::npos) << line;
    text.insert(at + line.size(), added);
  };
  insert_after("  - name: drag\n    steps: 3\n", "    linear_solver: klu\n");
  insert_after("  - name: let_go\n    steps: 3\n", "    linear_solver: mumps\n");
  const scenario::Scenario s = scenario::parse_scenario(text, "stage_solvers.yaml");
  const scenario::Scenario one = scenario::parse_scenario(kScenario, "resume.yaml");

  Simulation single(one);
  ASSERT_TRUE(single.run({}).converged);
  Simulation reference(s);
  Recorder all;
  StageSolvers solvers;
  const RunSummary whole = reference.run({&all, &solvers});
  ASSERT_TRUE(whole.converged) << whole.failure;
  EXPECT_EQ(solvers.names, (std::vector<std::string>{"cholmod", "klu", "mumps_ldlt"}));
  ASSERT_EQ(static_cast<int>(all.records.size()), kSteps);
  EXPECT_LT((reference.state() - single.state()).cwiseAbs().maxCoeff(), 1e-10);

  for (int k = 1; k < kSteps; ++k) {
    SCOPED_TRACE("stopped after step " + std::to_string(k));
    Simulation first(s);
    first.run({}, {k});
    const std::string bytes = nodus::persistence::encode_checkpoint(s, first.snapshot());
    Simulation second(s);
    second.restore(nodus::persistence::decode_checkpoint(bytes, s, "memory"), StartKind::resumed);
    Recorder after;
    const RunSummary rest = second.run({&after});
    ASSERT_TRUE(rest.converged) << rest.failure;
    EXPECT_EQ(rest.newton_iterations, whole.newton_iterations);
    for (std::size_t i = 0; i < after.records.size(); ++i)
      expect_same(after.records[i], all.records[static_cast<std::size_t>(k) + i]);
    EXPECT_EQ((second.state() - reference.state()).cwiseAbs().maxCoeff(), 0.0);
  }
}

// The stepping of the Python module: a run stopped by RunOptions::stop_when or cancelled by
// RunOptions::cancel (Ctrl-C) in the middle of a Newton solve keeps its last converged state, and further
// calls of run() on the same Simulation end where one uninterrupted run ends.
TEST(Checkpoint, StoppedOrCancelledRunGoesOnInTheSameSimulation) {
  const scenario::Scenario s = scenario::parse_scenario(kScenario, "resume.yaml");
  Simulation reference(s);
  Recorder all;
  ASSERT_TRUE(reference.run({&all}).converged);

  Simulation sim(s);
  Recorder records;
  RunOptions to_stage_end;
  to_stage_end.stop_when = [](const StepRecord& r) { return r.ends_stage; };
  RunSummary first = sim.run({&records}, to_stage_end);
  EXPECT_TRUE(first.interrupted);
  EXPECT_FALSE(first.cancelled);
  EXPECT_EQ(sim.progress().stage, 1);  // stage 0 done, stage 1 not begun
  EXPECT_EQ(records.stage_ends, std::vector<int>{0});

  // Cancelled after the third Newton iteration of the next solve: no step converged, the state is the one
  // the stage ended with.
  const Eigen::VectorXd before = sim.state();
  const int steps_before = sim.steps();
  int asked = 0;
  RunOptions cancel;
  cancel.cancel = [&asked] { return ++asked > 3; };
  const RunSummary cancelled = sim.run({&records}, cancel);
  EXPECT_TRUE(cancelled.cancelled);
  EXPECT_TRUE(cancelled.interrupted);
  EXPECT_EQ(cancelled.new_steps, 0);
  EXPECT_EQ(sim.steps(), steps_before);
  EXPECT_EQ((sim.state() - before).cwiseAbs().maxCoeff(), 0.0);

  const RunSummary rest = sim.run({&records});
  ASSERT_TRUE(rest.converged) << rest.failure;
  EXPECT_EQ(records.finished, 1);
  ASSERT_EQ(records.records.size(), all.records.size());
  for (std::size_t i = 0; i < all.records.size(); ++i) expect_same(records.records[i], all.records[i]);
  EXPECT_EQ((sim.state() - reference.state()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Checkpoint, EncodingRoundTrips) {
  const scenario::Scenario s = scenario::parse_scenario(kScenario, "resume.yaml");
  Simulation sim(s);
  sim.run({}, {4});
  const std::string bytes = nodus::persistence::encode_checkpoint(s, sim.snapshot());
  EXPECT_EQ(bytes.substr(0, 12), "NODUS-STATE\n");
  EXPECT_EQ(
      nodus::persistence::encode_checkpoint(s, nodus::persistence::decode_checkpoint(bytes, s, "memory")),
      bytes);
}

TEST(Checkpoint, DamagedOrForeignFilesAreRefused) {
  const scenario::Scenario s = scenario::parse_scenario(kScenario, "resume.yaml");
  Simulation sim(s);
  sim.run({}, {4});
  const std::string bytes = nodus::persistence::encode_checkpoint(s, sim.snapshot());

  std::string flipped = bytes;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  std::string wrong_version = bytes;
  wrong_version[12] = 4;
  std::string other = kScenario;
  other.replace(other.find("young_modulus: 4000"), 19, "young_modulus: 3000");
  const scenario::Scenario other_scenario = scenario::parse_scenario(other, "other.yaml");
  struct Case {
    std::string bytes;
    const scenario::Scenario* scenario;
    std::string expect;
  };
  const Case cases[] = {
      {flipped, &s,
       "test.nodus-state: checkpoint: expected a complete checkpoint, got a damaged or truncated file"},
      {bytes.substr(0, bytes.size() - 100), &s, "expected a complete checkpoint, got a damaged"},
      {bytes.substr(0, 5), &s,
       "expected a nodus state file (starting with NODUS-STATE), got a file of another kind"},
      {"not a checkpoint at all", &s, "expected a nodus state file"},
      {wrong_version, &s, "test.nodus-state: checkpoint: expected format version 3, got version 4"},
      {bytes, &other_scenario,
       "test.nodus-state: checkpoint: expected a state of this scenario (fingerprint "},
  };
  for (const Case& c : cases) {
    const std::string error = error_of(c.bytes, *c.scenario);
    EXPECT_NE(error.find(c.expect), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  const std::string foreign = error_of(bytes, other_scenario);
  EXPECT_NE(foreign.find(
                "'materials[0].young_modulus = 4000' in the checkpoint, 'materials[0].young_modulus = 3000' "
                "in the scenario"),
            std::string::npos)
      << foreign;
  // A scenario with fewer stages than the checkpoint has run.
  scenario::Scenario shorter = s;
  shorter.stages.resize(1);
  EXPECT_NE(error_of(bytes, shorter)
                .find("expected a state of this scenario (1 stages), got a state after 2 stages"),
            std::string::npos)
      << error_of(bytes, shorter);
  // Stages still to come may change.
  scenario::Scenario longer = s;
  longer.stages.push_back(longer.stages.back());
  longer.stages.back().name = "again";
  EXPECT_NO_THROW(nodus::persistence::decode_checkpoint(bytes, longer, "test.nodus-state"));
}

TEST(Checkpoint, FileNames) {
  EXPECT_EQ(nodus::persistence::checkpoint_file_name(3, "tighten"), "003_tighten.nodus-state");
  EXPECT_EQ(nodus::persistence::checkpoint_file_name(12, "a b/c"), "012_a_b_c.nodus-state");
}

}  // namespace
}  // namespace nodus::simulation
