// Tests of the branches of a scenario (key `branches`) and of output.checkpoint_every: the reader resolves
// them, reports bad ones in one line "FILE:LINE: KEY: expected ..., got ...", describe() echoes them as a
// valid scenario, branch_scenario() makes the run of a branch, and the fingerprint of a saved state depends
// on what made the state only.

#include <string>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::scenario {
namespace {

/// Two beams crossing, a tool pressing; stages press, drag, back; two branches from drag.
const std::string kBase = R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 10, start: [-5, 0, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 2, start: [0, -1, 0.31],
     direction: [0, 1, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool}
  - {name: pull, type: load, beam: beam, at: end, force: [0.1, 0, 0]}
stages:
  - name: press
    steps: 3
    motions:
      press: {translation: [0, 0, -0.1]}
  - name: drag
    steps: 4
    motions:
      press: {translation: [0, 0.3, -0.1]}
    loads:
      pull: {force: [0.2, 0, 0], moment: [0.01, 0, 0]}
  - name: back
    steps: 3
contact:
  friction: 0.3
branches:
  - name: mu_0.30
    from: drag
    stages:
      - name: back
        steps: 3
        loads:
          pull: {force: [0.3, 0, 0]}
  - name: mu_0.1
    from: press
    contact: {friction: 0.1}
    stages:
      - name: loosen
        steps: 2
        duration: 2
        release: [pull]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "b.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenarioBranches, AreRead) {
  const Scenario s = parse_scenario(kBase, "b.yaml");
  ASSERT_EQ(s.branches.size(), 2u);
  const BranchSpec& a = s.branches[0];
  EXPECT_EQ(a.name, "mu_0.30");
  EXPECT_EQ(a.from, 1);
  EXPECT_FALSE(a.friction);
  EXPECT_EQ(a.line, 28);
  ASSERT_EQ(a.stages.size(), 1u);
  EXPECT_EQ(a.stages[0].name, "back");  // a name of `stages` may be used again in a branch
  // A load target goes on from the value of the load at the end of the `from` stage: the moment set in drag.
  ASSERT_EQ(a.stages[0].loads.size(), 1u);
  EXPECT_EQ(a.stages[0].loads[0].force, Vec3(0.3, 0, 0));
  EXPECT_EQ(a.stages[0].loads[0].moment, Vec3(0.01, 0, 0));
  const BranchSpec& b = s.branches[1];
  EXPECT_EQ(b.from, 0);
  ASSERT_TRUE(b.friction);
  EXPECT_EQ(*b.friction, 0.1);
  EXPECT_EQ(b.stages[0].duration, 2.0);
  EXPECT_EQ(b.stages[0].release, std::vector<int>{3});
  // The moment axis of the load is resolved once for the whole file.
  ASSERT_TRUE(s.conditions[3].moment_axis);
  EXPECT_EQ(*s.conditions[3].moment_axis, Vec3::UnitX());
}

// output.hdf5 (result.h5, docs/output.md): on unless the file says false; a flag, so nothing else is
// taken. Like every output key it is not part of the checkpoint fingerprint.
TEST(ScenarioOutput, Hdf5IsRead) {
  EXPECT_TRUE(parse_scenario(kBase, "b.yaml").output.hdf5);
  const Scenario off = parse_scenario(kBase + "output: {hdf5: false}\n", "b.yaml");
  EXPECT_FALSE(off.output.hdf5);
  EXPECT_EQ(state_fingerprint_text(off, 1), state_fingerprint_text(parse_scenario(kBase, "b.yaml"), 1));
  EXPECT_NE(error_of(kBase + "output: {hdf5: 3}\n").find("output.hdf5"), std::string::npos)
      << error_of(kBase + "output: {hdf5: 3}\n");
}

TEST(ScenarioBranches, CheckpointEveryIsRead) {
  EXPECT_EQ(parse_scenario(kBase, "b.yaml").output.checkpoint_every, 0);
  const Scenario s = parse_scenario(kBase + "output: {checkpoint_every: 5}\n", "b.yaml");
  EXPECT_EQ(s.output.checkpoint_every, 5);
  EXPECT_NE(error_of(kBase + "output: {checkpoint_every: -1}\n")
                .find("b.yaml:43: output.checkpoint_every: expected an integer >= 0, got -1"),
            std::string::npos)
      << error_of(kBase + "output: {checkpoint_every: -1}\n");
}

TEST(ScenarioBranches, BadBranchesGiveOneLineErrors) {
  struct Case {
    std::string text, expect;
  };
  const Case cases[] = {
      {replaced(kBase, "from: drag", "from: dreg"),
       "b.yaml:29: branches[0].from: expected the name of a stage of stages (press | drag | back), got dreg"},
      {replaced(kBase, "name: mu_0.1", "name: mu_0.30"),
       "b.yaml:35: branches[1].name: expected a name unique among branches (already used at line 28), got "
       "mu_0.30"},
      {replaced(kBase, "name: mu_0.1", "name: ../up"),
       "b.yaml:35: branches[1].name: expected a name of letters"},
      {replaced(kBase, "contact:\n  friction: 0.3\n", ""),
       "b.yaml:35: branches[1].contact: expected no contact override in a scenario without a contact "
       "section, "
       "got a map"},
      {replaced(kBase, "contact: {friction: 0.1}", "contact: {penalty: 1}"),
       "b.yaml:37: branches[1].contact.penalty: expected one of the keys friction, got an unknown key"},
      {replaced(kBase, "contact: {friction: 0.1}", "contact: {friction: -1}"),
       "b.yaml:37: branches[1].contact.friction: expected a number >= 0, got -1"},
      {replaced(kBase, "    from: press\n", ""),
       "b.yaml:35: branches[1].from: expected a string naming a stage"},
      {replaced(kBase, "        steps: 2\n", ""),
       "b.yaml:39: branches[1].stages[0].steps: expected an integer >= 1, got nothing (missing key)"},
      {replaced(kBase, "        duration: 2", "        duration: 0"),
       "b.yaml:41: branches[1].stages[0].duration: expected a number > 0 (s), got 0"},
      {replaced(kBase, "        release: [pull]", "        release: [pul]"),
       "b.yaml:42: branches[1].stages[0].release[0]: expected the name of a condition"},
      {replaced(kBase, "        release: [pull]", "      - {name: loosen, steps: 1}"),
       "b.yaml:42: branches[1].stages[1].name: expected a name unique among stages (already used at line "
       "39)"},
      {replaced(kBase, "    stages:\n      - name: loosen", "    stagez:\n      - name: loosen"),
       "b.yaml:38: branches[1].stagez: expected one of the keys name | from | contact | stages, got an "
       "unknown "
       "key"},
      {replaced(kBase, "pull: {force: [0.3, 0, 0]}", "pull: {moment: [0, 0.3, 0]}"),
       "b.yaml:34: branches[0].stages[0].loads.pull.moment: expected a moment parallel to [0.01, 0, 0]"},
  };
  for (const Case& c : cases) {
    const std::string error = error_of(c.text);
    EXPECT_EQ(error.find(c.expect), 0u) << "got:    " << error << "\nwanted: " << c.expect;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(ScenarioBranches, DescribeEchoesThemAsAValidScenario) {
  const Scenario s = parse_scenario(kBase + "output: {checkpoint_every: 7}\n", "b.yaml");
  const std::string text = describe(s);
  EXPECT_NE(text.find("branches:\n  - name: mu_0.30\n    from: drag\n    stages:\n      - name: back\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("    contact: {friction: 0.1}\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  checkpoint_every: 7\n"), std::string::npos) << text;
  const Scenario again = parse_scenario(text, "echo.yaml");
  ASSERT_EQ(again.branches.size(), s.branches.size());
  for (std::size_t b = 0; b < s.branches.size(); ++b) {
    EXPECT_EQ(again.branches[b].name, s.branches[b].name);
    EXPECT_EQ(again.branches[b].from, s.branches[b].from);
    EXPECT_EQ(again.branches[b].friction, s.branches[b].friction);
    EXPECT_EQ(again.branches[b].stages.size(), s.branches[b].stages.size());
  }
  EXPECT_EQ(again.output.checkpoint_every, 7);
  // The same state: the echo describes the same run.
  EXPECT_EQ(state_fingerprint_text(again, 3), state_fingerprint_text(s, 3));
}

TEST(ScenarioBranches, BranchScenarioContinuesItsParent) {
  const Scenario s = parse_scenario(kBase, "b.yaml");
  const Scenario a = branch_scenario(s, 0);
  ASSERT_EQ(a.stages.size(), 3u);  // press, drag, then the branch's back
  EXPECT_EQ(a.stages[1].name, "drag");
  EXPECT_EQ(a.stages[2].loads[0].force, Vec3(0.3, 0, 0));
  EXPECT_EQ(a.contact.friction, 0.3);
  EXPECT_TRUE(a.branches.empty());
  ASSERT_TRUE(a.origin);
  EXPECT_EQ(a.origin->from, 1);
  const Scenario b = branch_scenario(s, 1);
  ASSERT_EQ(b.stages.size(), 2u);
  EXPECT_EQ(b.stages[1].name, "loosen");
  EXPECT_EQ(b.contact.friction, 0.1);
  EXPECT_EQ(b.origin->parent_friction, 0.3);
}

TEST(ScenarioBranches, FingerprintDependsOnWhatMadeTheState) {
  const Scenario s = parse_scenario(kBase, "b.yaml");
  const auto hash = [](const Scenario& scenario, int stages) {
    return fingerprint_hash(state_fingerprint_text(scenario, stages));
  };
  // Not on the path, the output settings, comments (line numbers), branches, or stages still to come.
  Scenario moved = parse_scenario("# a comment\n" + kBase + "output: {vtk_every: 3}\n", "elsewhere.yaml");
  moved.branches.clear();
  EXPECT_EQ(hash(s, 2), hash(moved, 2));
  const Scenario longer = parse_scenario(
      replaced(kBase, "  - name: back\n    steps: 3\n", "  - name: back\n    steps: 9\n"), "b.yaml");
  EXPECT_EQ(hash(s, 2), hash(longer, 2));
  EXPECT_NE(hash(s, 3), hash(longer, 3));
  // On the model, the contact settings and the stages run.
  EXPECT_NE(hash(s, 2),
            hash(parse_scenario(replaced(kBase, "young_modulus: 4000", "young_modulus: 4001"), "b.yaml"), 2));
  EXPECT_NE(hash(s, 2), hash(parse_scenario(replaced(kBase, "friction: 0.3", "friction: 0.2"), "b.yaml"), 2));
  EXPECT_NE(hash(s, 1), hash(s, 2));
  // A branch's run is its parent's up to the end of `from`, its own beyond.
  const Scenario b = branch_scenario(s, 1);
  EXPECT_EQ(hash(b, 1), hash(s, 1));
  EXPECT_NE(hash(b, 2), hash(s, 2));
  const Scenario a = branch_scenario(s, 0);
  EXPECT_EQ(hash(a, 2), hash(s, 2));
  EXPECT_NE(hash(a, 3), hash(s, 3));  // the branch's stage `back` differs from the main one
  Scenario same_friction = s;
  same_friction.branches[1].friction = 0.3;
  EXPECT_NE(hash(branch_scenario(same_friction, 1), 2), hash(b, 2));
}

TEST(ScenarioBranches, ActivationIsCheckedInTheBranches) {
  // In branch mu_0.30 the activity goes on from the end of drag; activating a second clamp on the
  // already clamped start section over-constrains it there, and only there.
  const std::string text = replaced(
      replaced(
          kBase, "  - {name: press, type: rigid, beam: tool}",
          "  - {name: press, type: rigid, beam: tool}\n  - {name: hold, type: clamp, beam: beam, at: start, "
          "active: false}"),
      "        steps: 3\n        loads:", "        steps: 3\n        activate: [hold]\n        loads:");
  const Scenario s = parse_scenario(text, "b.yaml");
  try {
    simulation::Simulation sim(s);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("in stage 'back' of branch 'mu_0.30'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace nodus::scenario
