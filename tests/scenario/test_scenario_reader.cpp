// Tests of the scenario reader: a valid scenario resolves correctly, every kind of bad input gives a
// one-line ScenarioError "FILE:LINE: KEY: expected ..., got ...".

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {
namespace {

/// A small valid scenario; error tests change single lines of it (line numbers in the comments of the tests).
const std::string kBase = R"(materials:
  - name: nylon
    young_modulus: 4000
    poisson_ratio: 0.3
beams:
  - name: rod
    material: nylon
    radius: 0.1
    length: 20
    elements: 10
conditions:
  - name: root
    type: clamp
    beam: rod
    at: start
  - name: tip
    type: motion
    beam: rod
    at: end
    active: false
  - name: push
    type: load
    beam: rod
    at: 10
    force: [0, 0, 0]
stages:
  - name: bend
    steps: 20
    activate: [tip]
    motions:
      tip: {translation: [0, 0, 1]}
    loads:
      push: {force: [0, -1, 0]}
)";

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// `text` with its 1-based line `line` replaced by `replacement` (which may hold several lines, or none:
/// an empty replacement removes the line). Line numbers past the end append.
std::string with_line(const std::string& text, int line, const std::string& replacement) {
  std::vector<std::string> lines = split_lines(text);
  if (line < 1) ADD_FAILURE() << "bad line " << line;
  std::string out;
  for (int i = 1; i <= static_cast<int>(lines.size()) || i <= line; ++i) {
    if (i == line) {
      if (!replacement.empty()) out += replacement + "\n";
    } else if (i <= static_cast<int>(lines.size())) {
      out += lines[i - 1] + "\n";
    }
  }
  return out;
}

/// `text` with `insertion` (one or more lines) inserted after 1-based line `line`.
std::string after_line(const std::string& text, int line, const std::string& insertion) {
  const std::vector<std::string> lines = split_lines(text);
  return with_line(text, line, lines.at(line - 1) + "\n" + insertion);
}

/// The message of the ScenarioError that parsing `yaml` throws; a test failure if there is none.
std::string error_of(const std::string& yaml, const std::string& file = "knot.yaml") {
  try {
    parse_scenario(yaml, file);
  } catch (const ScenarioError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "not a ScenarioError: " << error.what();
    return {};
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return {};
}

/// Checks the message of parsing `yaml`: one line "knot.yaml:LINE: KEY: expected ..., got ...".
::testing::AssertionResult fails_at(const std::string& yaml, int line, const std::string& key) {
  const std::string message = error_of(yaml);
  const std::string prefix = "knot.yaml:" + std::to_string(line) + ": " + key + ": expected ";
  if (message.rfind(prefix, 0) != 0) {
    return ::testing::AssertionFailure()
           << "message \"" << message << "\" does not start with \"" << prefix << "\"";
  }
  if (message.find(", got ") == std::string::npos) {
    return ::testing::AssertionFailure() << "no \", got \" in \"" << message << "\"";
  }
  if (message.find('\n') != std::string::npos) {
    return ::testing::AssertionFailure() << "message has more than one line: \"" << message << "\"";
  }
  return ::testing::AssertionSuccess() << message;
}

constexpr double kTight = 1e-14;

// ---- valid input ----

TEST(ScenarioReader, BaseScenarioIsValid) {
  const Scenario scenario = parse_scenario(kBase, "knot.yaml");
  EXPECT_EQ(scenario.path, "knot.yaml");
  ASSERT_EQ(scenario.materials.size(), 1u);
  ASSERT_EQ(scenario.beams.size(), 1u);
  ASSERT_EQ(scenario.conditions.size(), 3u);
  ASSERT_EQ(scenario.stages.size(), 1u);
}

const std::string kFull = R"(# a full scenario using every key
units: {length: mm, force: N, stress: MPa, time: s}
materials:
  - name: nylon
    young_modulus: 4000
    poisson_ratio: 0.3
  - name: steel
    young_modulus: 2.1e5
    poisson_ratio: 0
beams:
  - name: rod
    material: steel
    radius: 0.1
    length: 20
    elements: 300
  - name: strand
    material: nylon
    radius: 0.25
    length: 12.5
    elements: 4
    start: [1, -2, 3.5]
    direction: [3, 4, 0]
    director1: [0, 1, 1]
    bending_factor: 0.3
  - name: vertical
    material: nylon
    radius: 1
    length: 1
    elements: 1
    direction: [0, 0, -2]
conditions:
  - name: root
    type: clamp
    beam: rod
    at: start
  - name: tip
    type: motion
    beam: rod
    at: end
    dofs: [position, g1x, z]
    active: false
  - name: mid_load
    type: load
    beam: strand
    at: 3
    force: [0, 0, 1]
    moment: [0, 0, 2]
  - name: side
    type: clamp
    beam: strand
    at: end
    dofs: [directors]
stages:
  - name: bend
    steps: 20
    activate: [tip]
    motions:
      tip:
        translation: [0, 0, 1]
        rotation: [0, 0, 90]
    loads:
      mid_load: {force: [0, -1, 0]}
  - name: twist
    steps: 5
    duration: 2.5
    release: [side]
    motions:
      tip:
        keyframes:
          - {at: 0.25, translation: [1, 0, 0]}
          - {at: 1, rotation: [720, 0, 0]}
    loads:
      mid_load: {moment: [0, 0, -4]}
  - name: hold
    steps: 1
    activate: [side]
    release: [tip]
    loads:
      mid_load: {}
solver:
  linear_solver: umfpack
  max_newton_iterations: 40
  residual_tolerance: 1.0e-10
  increment_tolerance: 1e-9
  max_cutbacks: 0
  easy_iterations: 2
  line_search: false
  director_update: additive
  gauss_points: 3
  fold_stiffness: 0.5
output:
  vtk_every: 0
  tube_sides: 16
  progress_seconds: 0
contact:
  enabled: true
  self_contact: false
  beams: [vertical, rod]
  proximity_distance: 0.5
  separation_distance: auto
  test_point_spacing: 0.3
  matching_length: 0.6
  element_spacing: 0.05
  forces: true
  penalty: 500
  max_penetration: auto
  regularization: 0.0004
  friction: 0.25
  max_reversible_slip: 0.001
  max_detections: 3
  max_normal_iterations: 8
  normal_tolerance: 0.002
)";

TEST(ScenarioReader, FullScenarioResolves) {
  const Scenario s = parse_scenario(kFull, "full.yaml");

  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[1].name, "steel");
  EXPECT_DOUBLE_EQ(s.materials[1].young_modulus, 2.1e5);
  EXPECT_DOUBLE_EQ(s.materials[1].poisson_ratio, 0.0);
  EXPECT_DOUBLE_EQ(s.materials[0].poisson_ratio, 0.3);

  ASSERT_EQ(s.beams.size(), 3u);
  const BeamSpec& rod = s.beams[0];
  EXPECT_EQ(rod.material, 1);
  EXPECT_DOUBLE_EQ(rod.radius, 0.1);
  EXPECT_DOUBLE_EQ(rod.length, 20.0);
  EXPECT_EQ(rod.elements, 300);
  EXPECT_TRUE(rod.start.isZero());                     // default
  EXPECT_TRUE(rod.direction.isApprox(Vec3::UnitX()));  // default
  EXPECT_TRUE(rod.director1.isApprox(Vec3::UnitY()));  // default for direction e_x
  EXPECT_DOUBLE_EQ(rod.bending_factor, 1.0);           // default

  const BeamSpec& strand = s.beams[1];
  EXPECT_EQ(strand.material, 0);
  EXPECT_TRUE(strand.start.isApprox(Vec3(1, -2, 3.5)));
  EXPECT_NEAR((strand.direction - Vec3(0.6, 0.8, 0)).norm(), 0.0, kTight);  // normalised
  // director1 [0,1,1] made orthogonal to [0.6,0.8,0] and normalised.
  const Vec3 g = Vec3(0, 1, 1) - 0.8 * Vec3(0.6, 0.8, 0);
  EXPECT_NEAR((strand.director1 - g.normalized()).norm(), 0.0, kTight);
  EXPECT_NEAR(strand.director1.norm(), 1.0, kTight);
  EXPECT_NEAR(strand.director1.dot(strand.direction), 0.0, kTight);
  EXPECT_DOUBLE_EQ(strand.bending_factor, 0.3);

  const BeamSpec& vertical = s.beams[2];
  EXPECT_TRUE(vertical.direction.isApprox(-Vec3::UnitZ()));
  EXPECT_TRUE(vertical.director1.isApprox(Vec3::UnitX()));  // e_x is least parallel to -e_z (first of x, y)

  ASSERT_EQ(s.conditions.size(), 4u);
  const ConditionSpec& root = s.conditions[0];
  EXPECT_EQ(root.type, ConditionType::clamp);
  EXPECT_EQ(root.beam, 0);
  EXPECT_EQ(root.node, 0);
  EXPECT_TRUE(root.initially_active);
  for (bool dof : root.dofs) EXPECT_TRUE(dof);  // default: all nine
  EXPECT_EQ(root.line, 32);

  const ConditionSpec& tip = s.conditions[1];
  EXPECT_EQ(tip.type, ConditionType::motion);
  EXPECT_EQ(tip.node, 600);  // end = 2 * elements
  EXPECT_FALSE(tip.initially_active);
  const DofMask tip_dofs{true, true, true, true, false, false, false, false, false};
  EXPECT_EQ(tip.dofs, tip_dofs);
  EXPECT_EQ(tip.line, 36);

  const ConditionSpec& load = s.conditions[2];
  EXPECT_EQ(load.type, ConditionType::load);
  EXPECT_EQ(load.beam, 1);
  EXPECT_EQ(load.node, 3);
  EXPECT_TRUE(load.force.isApprox(Vec3(0, 0, 1)));
  EXPECT_TRUE(load.moment.isApprox(Vec3(0, 0, 2)));

  const ConditionSpec& side = s.conditions[3];
  EXPECT_EQ(side.node, 8);
  const DofMask directors{false, false, false, true, true, true, true, true, true};
  EXPECT_EQ(side.dofs, directors);

  ASSERT_EQ(s.stages.size(), 3u);
  const StageSpec& bend = s.stages[0];
  EXPECT_EQ(bend.name, "bend");
  EXPECT_EQ(bend.steps, 20);
  EXPECT_DOUBLE_EQ(bend.duration, 1.0);  // default
  EXPECT_EQ(bend.activate, std::vector<int>{1});
  EXPECT_TRUE(bend.release.empty());
  ASSERT_EQ(bend.motions.size(), 1u);
  EXPECT_EQ(bend.motions[0].condition, 1);
  ASSERT_EQ(bend.motions[0].keyframes.size(), 1u);  // short form: one keyframe at 1
  EXPECT_DOUBLE_EQ(bend.motions[0].keyframes[0].at, 1.0);
  EXPECT_TRUE(bend.motions[0].keyframes[0].translation.isApprox(Vec3(0, 0, 1)));
  EXPECT_TRUE(bend.motions[0].keyframes[0].rotation.isApprox(Vec3(0, 0, 90)));
  ASSERT_EQ(bend.loads.size(), 1u);
  EXPECT_EQ(bend.loads[0].condition, 2);
  EXPECT_TRUE(bend.loads[0].force.isApprox(Vec3(0, -1, 0)));
  EXPECT_TRUE(bend.loads[0].moment.isApprox(Vec3(0, 0, 2)));  // omitted: the initial moment

  const StageSpec& twist = s.stages[1];
  EXPECT_EQ(twist.steps, 5);
  EXPECT_DOUBLE_EQ(twist.duration, 2.5);
  EXPECT_EQ(twist.release, std::vector<int>{3});
  ASSERT_EQ(twist.motions.size(), 1u);
  const auto& frames = twist.motions[0].keyframes;
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_DOUBLE_EQ(frames[0].at, 0.25);
  EXPECT_TRUE(frames[0].translation.isApprox(Vec3(1, 0, 0)));
  EXPECT_TRUE(frames[0].rotation.isZero());
  EXPECT_DOUBLE_EQ(frames[1].at, 1.0);
  EXPECT_TRUE(frames[1].translation.isZero());
  EXPECT_TRUE(frames[1].rotation.isApprox(Vec3(720, 0, 0)));
  ASSERT_EQ(twist.loads.size(), 1u);
  EXPECT_TRUE(twist.loads[0].force.isApprox(Vec3(0, -1, 0)));   // kept from stage "bend"
  EXPECT_TRUE(twist.loads[0].moment.isApprox(Vec3(0, 0, -4)));  // antiparallel: same axis

  const StageSpec& hold = s.stages[2];
  EXPECT_EQ(hold.activate, std::vector<int>{3});
  EXPECT_EQ(hold.release, std::vector<int>{1});
  EXPECT_TRUE(hold.motions.empty());
  ASSERT_EQ(hold.loads.size(), 1u);
  EXPECT_TRUE(hold.loads[0].force.isApprox(Vec3(0, -1, 0)));
  EXPECT_TRUE(hold.loads[0].moment.isApprox(Vec3(0, 0, -4)));

  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::umfpack);
  EXPECT_EQ(s.solver.max_newton_iterations, 40);
  EXPECT_DOUBLE_EQ(s.solver.residual_tolerance, 1e-10);
  EXPECT_DOUBLE_EQ(s.solver.increment_tolerance, 1e-9);
  EXPECT_EQ(s.solver.max_cutbacks, 0);
  EXPECT_EQ(s.solver.easy_iterations, 2);
  EXPECT_FALSE(s.solver.line_search);
  EXPECT_EQ(s.solver.director_update, model::DirectorUpdate::additive);
  EXPECT_EQ(s.solver.gauss_points, 3);
  EXPECT_EQ(s.solver.fold_stiffness, 0.5);
  EXPECT_EQ(s.output.vtk_every, 0);
  EXPECT_EQ(s.output.tube_sides, 16);
  EXPECT_DOUBLE_EQ(s.output.progress_seconds, 0.0);
  EXPECT_TRUE(s.contact.enabled);
  EXPECT_FALSE(s.contact.self_contact);
  EXPECT_EQ(s.contact.beams, (std::vector<int>{2, 0}));
  EXPECT_DOUBLE_EQ(s.contact.proximity_distance, 0.5);
  EXPECT_EQ(s.contact.separation_distance, 0.0);  // auto
  EXPECT_DOUBLE_EQ(s.contact.test_point_spacing, 0.3);
  EXPECT_DOUBLE_EQ(s.contact.matching_length, 0.6);
  EXPECT_DOUBLE_EQ(s.contact.element_spacing, 0.05);
  EXPECT_TRUE(s.contact.forces);
  EXPECT_DOUBLE_EQ(s.contact.penalty, 500.0);
  EXPECT_EQ(s.contact.max_penetration, 0.0);  // auto
  EXPECT_DOUBLE_EQ(s.contact.regularization, 0.0004);
  EXPECT_DOUBLE_EQ(s.contact.friction, 0.25);
  EXPECT_DOUBLE_EQ(s.contact.max_reversible_slip, 0.001);
  EXPECT_EQ(s.contact.max_detections, 3);
  EXPECT_EQ(s.contact.max_normal_iterations, 8);
  EXPECT_DOUBLE_EQ(s.contact.normal_tolerance, 0.002);
}

TEST(ScenarioReader, DefaultsOfOptionalSections) {
  const Scenario s = parse_scenario(kBase, "knot.yaml");
  const SolverSettings solver_defaults;
  // The default, auto, chooses CHOLMOD for the symmetric tangent of beams without friction.
  EXPECT_EQ(solver_defaults.linear_solver, LinearSolverKind::automatic);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::cholmod);
  EXPECT_EQ(s.solver.max_newton_iterations, solver_defaults.max_newton_iterations);
  EXPECT_EQ(s.solver.residual_tolerance, solver_defaults.residual_tolerance);
  EXPECT_EQ(s.solver.gauss_points, solver_defaults.gauss_points);
  EXPECT_EQ(s.solver.fold_stiffness, solver_defaults.fold_stiffness);
  EXPECT_EQ(s.output.vtk_every, 1);
  EXPECT_EQ(s.output.tube_sides, 12);
  EXPECT_EQ(s.conditions[2].node, 10);  // integer at
  EXPECT_EQ(s.conditions[1].node, 20);  // end
  EXPECT_TRUE(s.conditions[2].moment.isZero());
  EXPECT_TRUE(s.stages[0].loads[0].moment.isZero());
  EXPECT_FALSE(s.contact.enabled);  // no contact section: no contact
  EXPECT_TRUE(s.contact.beams.empty());
  const ContactSettings contact_defaults;
  EXPECT_EQ(s.contact.forces, contact_defaults.forces);
  EXPECT_EQ(s.contact.penalty, contact_defaults.penalty);
  EXPECT_EQ(s.contact.max_penetration, contact_defaults.max_penetration);
  EXPECT_EQ(s.contact.regularization, contact_defaults.regularization);
  EXPECT_EQ(s.contact.friction, contact_defaults.friction);
  EXPECT_EQ(s.contact.max_reversible_slip, contact_defaults.max_reversible_slip);
  EXPECT_EQ(s.contact.max_detections, contact_defaults.max_detections);
  EXPECT_EQ(s.contact.max_normal_iterations, contact_defaults.max_normal_iterations);
  EXPECT_EQ(s.contact.normal_tolerance, contact_defaults.normal_tolerance);
}

TEST(ScenarioReader, OptionalListsAndMapsMayBeEmpty) {
  std::string yaml = with_line(kBase, 11, "conditions: []");
  for (int line = 12; line <= 25; ++line) yaml = with_line(yaml, 12, "");
  // now: 26 -> 12 stages, 13 name, 14 steps, 15 activate, 16 motions, 17 tip, 18 loads, 19 push
  yaml = with_line(yaml, 15, "    activate: []");
  yaml = with_line(yaml, 16, "    motions:");
  yaml = with_line(yaml, 17, "");
  yaml = with_line(yaml, 17, "    loads: {}");
  yaml = with_line(yaml, 18, "");
  yaml += "solver:\noutput: {}\ncontact: {}\n";
  const Scenario s = parse_scenario(yaml, "knot.yaml");
  EXPECT_TRUE(s.contact.enabled);  // an empty contact section switches contact on
  EXPECT_TRUE(s.conditions.empty());
  EXPECT_TRUE(s.stages[0].motions.empty());
  EXPECT_TRUE(s.stages[0].loads.empty());
}

TEST(ScenarioReader, DirectorOnlyAlmostParallelIsAccepted) {
  // |sin angle| = 1e-5 > 1e-6: accepted and orthogonalised.
  const Scenario s = parse_scenario(after_line(kBase, 10, "    director1: [1, 1e-5, 0]"), "knot.yaml");
  EXPECT_NEAR((s.beams[0].director1 - Vec3::UnitY()).norm(), 0.0, 1e-9);
}

TEST(ScenarioReader, AStageMayNameItsOwnLineSearch) {
  // Line 28 is the stage's `steps`.
  const Scenario solver = parse_scenario(kBase, "knot.yaml");
  EXPECT_EQ(solver.stages[0].line_search, StageSwitch::solver);
  const Scenario on = parse_scenario(after_line(kBase, 28, "    line_search: true"), "knot.yaml");
  EXPECT_EQ(on.stages[0].line_search, StageSwitch::on);
  const Scenario off = parse_scenario(after_line(kBase, 28, "    line_search: false"), "knot.yaml");
  EXPECT_EQ(off.stages[0].line_search, StageSwitch::off);
  EXPECT_TRUE(fails_at(after_line(kBase, 28, "    line_search: maybe"), 29, "stages[0].line_search"));

  // The fingerprint of a stage without its own setting has no line for it (the checkpoints of scenarios
  // written before the key stay valid); one with it differs.
  const std::string text = state_fingerprint_text(solver, 1);
  EXPECT_EQ(text.find("line_search = solver"), std::string::npos) << text;
  EXPECT_NE(text.find("solver.line_search = false"), std::string::npos) << text;
  EXPECT_NE(state_fingerprint_text(on, 1), text);
  EXPECT_NE(state_fingerprint_text(off, 1), text);
  EXPECT_NE(state_fingerprint_text(on, 1), state_fingerprint_text(off, 1));

  // The echo shows it where it is set, and reads back as the same scenario.
  const std::string echo = describe(on);
  EXPECT_NE(echo.find("    line_search: true\n"), std::string::npos) << echo;
  EXPECT_EQ(describe(solver).find("    line_search:"), std::string::npos);
  EXPECT_EQ(state_fingerprint_text(parse_scenario(echo, "echo.yaml"), 1), state_fingerprint_text(on, 1));
}

// ---- errors: one line "FILE:LINE: KEY: expected ..., got ..." ----

TEST(ScenarioErrors, ExampleFromTheSpecification) {
  const std::string message = error_of(with_line(kBase, 8, "    radius: -0.1"));
  EXPECT_EQ(message, "knot.yaml:8: beams[0].radius: expected a number > 0 (mm), got -0.1");
}

TEST(ScenarioErrors, NotYaml) {
  EXPECT_TRUE(fails_at(with_line(kBase, 29, "    activate: [tip"), 30, "yaml"));
  EXPECT_TRUE(fails_at(with_line(kBase, 9, "     length: 20"), 9, "yaml"));  // bad indentation
  EXPECT_TRUE(fails_at(with_line(kBase, 9, "\tlength: 20"), 9, "yaml"));
}

TEST(ScenarioErrors, TopLevelNotAMap) {
  EXPECT_TRUE(fails_at("- 1\n- 2\n", 1, "top level"));
  EXPECT_TRUE(fails_at("", 1, "top level"));
  EXPECT_TRUE(fails_at("# only a comment\n", 1, "top level"));
  EXPECT_TRUE(fails_at("just text\n", 1, "top level"));
}

TEST(ScenarioErrors, UnknownKeys) {
  EXPECT_TRUE(fails_at(kBase + "colour: red\n", 34, "colour"));
  EXPECT_TRUE(fails_at(after_line(kBase, 8, "    radus: 1"), 9, "beams[0].radus"));
  EXPECT_TRUE(fails_at(after_line(kBase, 28, "    stepz: 1"), 29, "stages[0].stepz"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, "      tip: {translation: [0, 0, 1], spin: 3}"), 31,
                       "stages[0].motions.tip.spin"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  tolerance: 1\n", 35, "solver.tolerance"));
  EXPECT_TRUE(fails_at(kBase + "output: {vtk: 1}\n", 34, "output.vtk"));
  EXPECT_TRUE(fails_at(kBase + "contact:\n  self_contact: true\n  coulomb: 0.1\n", 36, "contact.coulomb"));
  EXPECT_TRUE(fails_at(kBase + "units: {length: mm, mass: kg}\n", 34, "units.mass"));
  const std::string message = error_of(after_line(kBase, 8, "    radus: 1"));
  EXPECT_NE(message.find("radius"), std::string::npos) << message;  // lists the allowed keys
}

TEST(ScenarioErrors, DuplicateKey) {
  EXPECT_TRUE(fails_at(after_line(kBase, 8, "    radius: 0.2"), 9, "beams[0].radius"));
}

TEST(ScenarioErrors, WrongTypes) {
  EXPECT_TRUE(fails_at(with_line(kBase, 8, "    radius: thin"), 8, "beams[0].radius"));
  EXPECT_TRUE(
      fails_at(with_line(kBase, 8, "    radius: \"0.1\""), 8, "beams[0].radius"));  // quoted: a string
  EXPECT_TRUE(fails_at(with_line(kBase, 8, "    radius: [0.1]"), 8, "beams[0].radius"));
  EXPECT_TRUE(fails_at(with_line(kBase, 8, "    radius:"), 8, "beams[0].radius"));
  EXPECT_TRUE(fails_at(with_line(kBase, 8, "    radius: .inf"), 8, "beams[0].radius"));
  EXPECT_TRUE(fails_at(with_line(kBase, 3, "    young_modulus: 4e3.5"), 3, "materials[0].young_modulus"));
  // a map where a list is expected
  std::string yaml = kBase;
  for (int i = 0; i < 3; ++i) yaml = with_line(yaml, 2, "");
  yaml = with_line(yaml, 1, "materials: {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}");
  EXPECT_TRUE(fails_at(yaml, 1, "materials"));
  // a list where a map is expected
  EXPECT_TRUE(fails_at(kBase + "solver: [1, 2]\n", 34, "solver"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, "      tip: [0, 0, 1]"), 31, "stages[0].motions.tip"));
  // a list item that is not a map
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "  - rod2"), 11, "beams[1]"));
  // booleans
  EXPECT_TRUE(fails_at(with_line(kBase, 20, "    active: maybe"), 20, "conditions[1].active"));
  EXPECT_TRUE(fails_at(kBase + "solver: {line_search: 1}\n", 34, "solver.line_search"));
  // names must be non-empty scalars
  EXPECT_TRUE(fails_at(with_line(kBase, 6, "  - name: [rod]"), 6, "beams[0].name"));
  EXPECT_TRUE(fails_at(with_line(kBase, 6, "  - name: \"\""), 6, "beams[0].name"));
}

TEST(ScenarioErrors, Vectors) {
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    start: [0, 0]"), 11, "beams[0].start"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    start: [0, 0, 0, 0]"), 11, "beams[0].start"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    start: 0"), 11, "beams[0].start"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    start: [0, a, 0]"), 11, "beams[0].start[1]"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    start:\n      - 0\n      - 0\n      - x"), 14,
                       "beams[0].start[2]"));
  EXPECT_TRUE(
      fails_at(with_line(kBase, 33, "      push: {force: [0, -1]}"), 33, "stages[0].loads.push.force"));
}

TEST(ScenarioErrors, MissingRequiredKeys) {
  EXPECT_TRUE(fails_at(with_line(kBase, 9, ""), 6, "beams[0].length"));
  // keys may come in any order
  EXPECT_NO_THROW(
      parse_scenario(with_line(with_line(kBase, 2, "  - young_modulus: 4000"), 3, "    name: nylon"), "k"));
  EXPECT_TRUE(fails_at(with_line(kBase, 4, ""), 2, "materials[0].poisson_ratio"));
  EXPECT_TRUE(fails_at(with_line(kBase, 15, ""), 12, "conditions[0].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 28, ""), 27, "stages[0].steps"));
  EXPECT_TRUE(fails_at(with_line(kBase, 33, "      push: {moment: [0, 0, 1], sign: 1}"), 33,
                       "stages[0].loads.push.sign"));
  const std::string message = error_of(with_line(kBase, 9, ""));
  EXPECT_NE(message.find("missing"), std::string::npos) << message;
  // top-level lists
  std::string no_stages = kBase;
  for (int i = 0; i < 8; ++i) no_stages = with_line(no_stages, 26, "");
  EXPECT_TRUE(fails_at(no_stages, 1, "stages"));
  std::string no_beams = kBase;
  for (int i = 0; i < 6; ++i) no_beams = with_line(no_beams, 5, "");
  EXPECT_TRUE(fails_at(no_beams, 1, "beams"));
}

TEST(ScenarioErrors, EmptyRequiredLists) {
  std::string yaml = kBase;
  for (int i = 0; i < 3; ++i) yaml = with_line(yaml, 2, "");
  EXPECT_TRUE(fails_at(with_line(yaml, 1, "materials: []"), 1, "materials"));
  EXPECT_TRUE(fails_at(with_line(yaml, 1, "materials:"), 1, "materials"));
}

TEST(ScenarioErrors, NumberRanges) {
  EXPECT_TRUE(fails_at(with_line(kBase, 8, "    radius: 0"), 8, "beams[0].radius"));
  EXPECT_TRUE(fails_at(with_line(kBase, 9, "    length: -20"), 9, "beams[0].length"));
  EXPECT_TRUE(fails_at(with_line(kBase, 9, "    length: 0"), 9, "beams[0].length"));
  EXPECT_TRUE(fails_at(with_line(kBase, 3, "    young_modulus: 0"), 3, "materials[0].young_modulus"));
  EXPECT_TRUE(fails_at(with_line(kBase, 4, "    poisson_ratio: 0.5"), 4, "materials[0].poisson_ratio"));
  EXPECT_TRUE(fails_at(with_line(kBase, 4, "    poisson_ratio: -0.1"), 4, "materials[0].poisson_ratio"));
  EXPECT_NE(
      error_of(with_line(kBase, 4, "    poisson_ratio: 0.5")).find("expected a number in [0, 0.5), got 0.5"),
      std::string::npos);
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    bending_factor: 0"), 11, "beams[0].bending_factor"));
  EXPECT_TRUE(fails_at(after_line(kBase, 28, "    duration: 0"), 29, "stages[0].duration"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  residual_tolerance: -1e-8\n", 35, "solver.residual_tolerance"));
  EXPECT_TRUE(fails_at(kBase + "output:\n  progress_seconds: -1\n", 35, "output.progress_seconds"));
}

TEST(ScenarioErrors, Integers) {
  EXPECT_TRUE(fails_at(with_line(kBase, 10, "    elements: 0"), 10, "beams[0].elements"));
  EXPECT_NE(error_of(with_line(kBase, 10, "    elements: 0")).find("expected an integer >= 1, got 0"),
            std::string::npos);
  EXPECT_TRUE(fails_at(with_line(kBase, 10, "    elements: 2.5"), 10, "beams[0].elements"));
  EXPECT_TRUE(fails_at(with_line(kBase, 10, "    elements: 10.0"), 10, "beams[0].elements"));
  EXPECT_TRUE(fails_at(with_line(kBase, 10, "    elements: 99999999999999999999"), 10, "beams[0].elements"));
  EXPECT_TRUE(fails_at(with_line(kBase, 10, "    elements: 1000000000"), 10, "beams[0].elements"));
  EXPECT_TRUE(fails_at(with_line(kBase, 28, "    steps: 0"), 28, "stages[0].steps"));
  EXPECT_TRUE(fails_at(with_line(kBase, 28, "    steps: ten"), 28, "stages[0].steps"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  gauss_points: 6\n", 35, "solver.gauss_points"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  gauss_points: 0\n", 35, "solver.gauss_points"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  fold_stiffness: -1\n", 35, "solver.fold_stiffness"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  max_newton_iterations: 0\n", 35, "solver.max_newton_iterations"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  max_cutbacks: -1\n", 35, "solver.max_cutbacks"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  easy_iterations: 0\n", 35, "solver.easy_iterations"));
  EXPECT_TRUE(fails_at(kBase + "output:\n  vtk_every: -1\n", 35, "output.vtk_every"));
  EXPECT_TRUE(fails_at(kBase + "output:\n  tube_sides: 2\n", 35, "output.tube_sides"));
}

TEST(ScenarioErrors, PetscSolverAndItsOptions) {
  // Options are words `-name` or the one value after an option.
  EXPECT_TRUE(fails_at(kBase + "solver:\n  petsc_options: superlu_dist\n", 35, "solver.petsc_options"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  petsc_options: \"-ksp_type gmres preonly\"\n", 35,
                       "solver.petsc_options"));
  EXPECT_TRUE(fails_at(kBase + "solver:\n  petsc_options: [a]\n", 35, "solver.petsc_options"));
  const std::string petsc =
      kBase + "solver:\n  linear_solver: petsc\n  petsc_options: \"-mat_mumps_cntl_1 -0.5 -ksp_view\"\n";
  if (nodus::parallel::available()) {
    const Scenario s = parse_scenario(petsc, "knot.yaml");
    EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::petsc);
    EXPECT_EQ(s.solver.petsc_options, "-mat_mumps_cntl_1 -0.5 -ksp_view");
  } else {
    // A build without PETSc refuses the solver at its line, saying why.
    EXPECT_TRUE(fails_at(petsc, 35, "solver.linear_solver"));
    EXPECT_NE(error_of(petsc).find("petsc needs nodus built with PETSc"), std::string::npos);
  }
}

TEST(ScenarioErrors, Choices) {
  EXPECT_TRUE(fails_at(kBase + "solver:\n  linear_solver: pardiso\n", 35, "solver.linear_solver"));
  EXPECT_TRUE(fails_at(with_line(kBase, 13, "    type: glue"), 13, "conditions[0].type"));
  EXPECT_TRUE(fails_at(kBase + "units: {length: m}\n", 34, "units.length"));
  EXPECT_TRUE(fails_at(kBase + "units: {length: mm, force: N, stress: GPa, time: s}\n", 34, "units.stress"));
  EXPECT_NE(error_of(with_line(kBase, 13, "    type: glue")).find("clamp | motion | rigid | load"),
            std::string::npos);
}

TEST(ScenarioErrors, DuplicateNames) {
  EXPECT_TRUE(fails_at(after_line(kBase, 4, "  - name: nylon\n    young_modulus: 1\n    poisson_ratio: 0"), 5,
                       "materials[1].name"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "  - name: rod\n    material: nylon"), 11, "beams[1].name"));
  EXPECT_TRUE(fails_at(with_line(kBase, 16, "  - name: root"), 16, "conditions[1].name"));
  EXPECT_TRUE(fails_at(kBase + "  - name: bend\n    steps: 1\n", 34, "stages[1].name"));
  EXPECT_NE(error_of(with_line(kBase, 16, "  - name: root")).find("line 12"), std::string::npos);
}

TEST(ScenarioErrors, UnknownReferences) {
  EXPECT_TRUE(fails_at(with_line(kBase, 7, "    material: steel"), 7, "beams[0].material"));
  EXPECT_NE(error_of(with_line(kBase, 7, "    material: steel")).find("nylon"), std::string::npos);
  EXPECT_TRUE(fails_at(with_line(kBase, 14, "    beam: rods"), 14, "conditions[0].beam"));
  EXPECT_TRUE(fails_at(with_line(kBase, 29, "    activate: [tip, nope]"), 29, "stages[0].activate[1]"));
  EXPECT_TRUE(fails_at(after_line(kBase, 29, "    release:\n      - root\n      - nope"), 32,
                       "stages[0].release[1]"));
  EXPECT_TRUE(
      fails_at(with_line(kBase, 31, "      nope: {translation: [0, 0, 1]}"), 31, "stages[0].motions.nope"));
  EXPECT_TRUE(fails_at(with_line(kBase, 33, "      nope: {force: [0, 1, 0]}"), 33, "stages[0].loads.nope"));
}

TEST(ScenarioErrors, StageLists) {
  EXPECT_TRUE(fails_at(after_line(kBase, 29, "    release: [root, tip]"), 30, "stages[0].release[1]"));
  EXPECT_TRUE(fails_at(with_line(kBase, 29, "    activate: [tip, tip]"), 29, "stages[0].activate[1]"));
  EXPECT_TRUE(fails_at(with_line(kBase, 29, "    activate: tip"), 29, "stages[0].activate"));
}

TEST(ScenarioErrors, TargetsOnConditionsOfTheWrongType) {
  EXPECT_TRUE(
      fails_at(with_line(kBase, 31, "      root: {translation: [0, 0, 1]}"), 31, "stages[0].motions.root"));
  EXPECT_NE(error_of(with_line(kBase, 31, "      root: {translation: [0, 0, 1]}")).find("clamp"),
            std::string::npos);
  EXPECT_TRUE(
      fails_at(with_line(kBase, 31, "      push: {translation: [0, 0, 1]}"), 31, "stages[0].motions.push"));
  EXPECT_TRUE(fails_at(with_line(kBase, 33, "      tip: {force: [0, 1, 0]}"), 33, "stages[0].loads.tip"));
}

TEST(ScenarioErrors, NodeIndexOutOfRange) {
  EXPECT_TRUE(fails_at(with_line(kBase, 24, "    at: 21"), 24, "conditions[2].at"));
  EXPECT_NE(error_of(with_line(kBase, 24, "    at: 21")).find("[0, 20]"), std::string::npos);
  EXPECT_TRUE(fails_at(with_line(kBase, 24, "    at: -1"), 24, "conditions[2].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 24, "    at: 2.5"), 24, "conditions[2].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 24, "    at: middle"), 24, "conditions[2].at"));
  EXPECT_EQ(parse_scenario(with_line(kBase, 24, "    at: 20"), "k").conditions[2].node, 20);
  EXPECT_EQ(parse_scenario(with_line(kBase, 24, "    at: 0"), "k").conditions[2].node, 0);
}

TEST(ScenarioErrors, DofsAndTypeSpecificKeys) {
  EXPECT_TRUE(fails_at(after_line(kBase, 15, "    dofs: [x, q]"), 16, "conditions[0].dofs[1]"));
  EXPECT_TRUE(fails_at(after_line(kBase, 15, "    dofs: []"), 16, "conditions[0].dofs"));
  EXPECT_TRUE(fails_at(after_line(kBase, 15, "    dofs: all"), 16, "conditions[0].dofs"));
  EXPECT_TRUE(fails_at(after_line(kBase, 25, "    dofs: [all]"), 26, "conditions[2].dofs"));
  EXPECT_TRUE(fails_at(after_line(kBase, 15, "    force: [0, 0, 1]"), 16, "conditions[0].force"));
  EXPECT_TRUE(fails_at(after_line(kBase, 19, "    moment: [0, 0, 1]"), 20, "conditions[1].moment"));
}

TEST(ScenarioErrors, Directions) {
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    direction: [0, 0, 0]"), 11, "beams[0].direction"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    director1: [2, 0, 0]"), 11, "beams[0].director1"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    director1: [-1, 1e-7, 0]"), 11, "beams[0].director1"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    director1: [0, 0, 0]"), 11, "beams[0].director1"));
  EXPECT_TRUE(fails_at(after_line(kBase, 10, "    direction: [0, 1, 0]\n    director1: [0, 3, 0]"), 12,
                       "beams[0].director1"));
}

TEST(ScenarioErrors, Keyframes) {
  const std::string head = "      tip:\n        keyframes:\n";
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {at: 0.5}\n          - {at: 0.5}"), 34,
                       "stages[0].motions.tip.keyframes[1].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {at: 0.5}\n          - {at: 0.25}"), 34,
                       "stages[0].motions.tip.keyframes[1].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {at: 0.5}\n          - {at: 0.8}"), 34,
                       "stages[0].motions.tip.keyframes[1].at"));
  EXPECT_NE(error_of(with_line(kBase, 31, head + "          - {at: 0.5}\n          - {at: 0.8}"))
                .find("expected 1 for the last keyframe, got 0.8"),
            std::string::npos);
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {at: 0}\n          - {at: 1}"), 33,
                       "stages[0].motions.tip.keyframes[0].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {at: 1.5}"), 33,
                       "stages[0].motions.tip.keyframes[0].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          - {translation: [1, 0, 0]}"), 33,
                       "stages[0].motions.tip.keyframes[0].at"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31, head + "          []"), 32, "stages[0].motions.tip.keyframes"));
  EXPECT_TRUE(fails_at(with_line(kBase, 31,
                                 "      tip:\n        translation: [0, 0, 1]\n        keyframes:\n"
                                 "          - {at: 1}"),
                       32, "stages[0].motions.tip.translation"));
  // a valid long form
  const Scenario s = parse_scenario(
      with_line(kBase, 31, head + "          - {at: 0.5}\n          - {at: 1, rotation: [0, 0, 1]}"),
      "knot.yaml");
  EXPECT_EQ(s.stages[0].motions[0].keyframes.size(), 2u);
}

TEST(ScenarioErrors, MomentAxisMustStayFixed) {
  const std::string yaml =
      with_line(after_line(kBase, 25, "    moment: [0, 0, 1]"), 34, "      push: {moment: [0, 1, 0]}");
  EXPECT_TRUE(fails_at(yaml, 34, "stages[0].loads.push.moment"));
  EXPECT_NE(error_of(yaml).find("moment axis must stay fixed"), std::string::npos);
  // between two stages, with a zero moment in between (zero has no axis)
  const std::string two_stages =
      with_line(kBase, 33, "      push: {moment: [1, 0, 0]}") +
      "  - name: s2\n    steps: 1\n    loads:\n      push: {moment: [0, 0, 0]}\n" +
      "  - name: s3\n    steps: 1\n    loads:\n      push: {moment: [1, 1e-6, 0]}\n";
  EXPECT_TRUE(fails_at(two_stages, 41, "stages[2].loads.push.moment"));
  // antiparallel and scaled moments keep the axis
  const std::string fine =
      with_line(after_line(kBase, 25, "    moment: [0, 0, 1]"), 34, "      push: {moment: [0, 0, -3.5]}");
  EXPECT_TRUE(parse_scenario(fine, "knot.yaml").stages[0].loads[0].moment.isApprox(Vec3(0, 0, -3.5)));
}

TEST(ScenarioErrors, FileNameAppearsInMessage) {
  const std::string message = error_of(with_line(kBase, 8, "    radius: -1"), "dir/other name.yaml");
  EXPECT_EQ(message.rfind("dir/other name.yaml:8: beams[0].radius: expected", 0), 0u) << message;
}

// ---- describe ----

void expect_same(const Scenario& a, const Scenario& b) {
  constexpr double tol = 1e-15;
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].young_modulus, b.materials[i].young_modulus);
    EXPECT_EQ(a.materials[i].poisson_ratio, b.materials[i].poisson_ratio);
  }
  ASSERT_EQ(a.beams.size(), b.beams.size());
  for (std::size_t i = 0; i < a.beams.size(); ++i) {
    const BeamSpec& x = a.beams[i];
    const BeamSpec& y = b.beams[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.radius, y.radius);
    EXPECT_EQ(x.length, y.length);
    EXPECT_EQ(x.elements, y.elements);
    EXPECT_EQ(x.start, y.start);
    EXPECT_NEAR((x.direction - y.direction).norm(), 0.0, tol);
    EXPECT_NEAR((x.director1 - y.director1).norm(), 0.0, tol);
    EXPECT_EQ(x.bending_factor, y.bending_factor);
  }
  ASSERT_EQ(a.conditions.size(), b.conditions.size());
  for (std::size_t i = 0; i < a.conditions.size(); ++i) {
    const ConditionSpec& x = a.conditions[i];
    const ConditionSpec& y = b.conditions[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.beam, y.beam);
    EXPECT_EQ(x.node, y.node);
    EXPECT_EQ(x.dofs, y.dofs);
    EXPECT_EQ(x.initially_active, y.initially_active);
    EXPECT_EQ(x.force, y.force);
    EXPECT_EQ(x.moment, y.moment);
  }
  ASSERT_EQ(a.stages.size(), b.stages.size());
  for (std::size_t i = 0; i < a.stages.size(); ++i) {
    const StageSpec& x = a.stages[i];
    const StageSpec& y = b.stages[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.steps, y.steps);
    EXPECT_EQ(x.duration, y.duration);
    EXPECT_EQ(x.activate, y.activate);
    EXPECT_EQ(x.release, y.release);
    ASSERT_EQ(x.motions.size(), y.motions.size());
    for (std::size_t m = 0; m < x.motions.size(); ++m) {
      EXPECT_EQ(x.motions[m].condition, y.motions[m].condition);
      ASSERT_EQ(x.motions[m].keyframes.size(), y.motions[m].keyframes.size());
      for (std::size_t k = 0; k < x.motions[m].keyframes.size(); ++k) {
        EXPECT_EQ(x.motions[m].keyframes[k].at, y.motions[m].keyframes[k].at);
        EXPECT_EQ(x.motions[m].keyframes[k].translation, y.motions[m].keyframes[k].translation);
        EXPECT_EQ(x.motions[m].keyframes[k].rotation, y.motions[m].keyframes[k].rotation);
      }
    }
    ASSERT_EQ(x.loads.size(), y.loads.size());
    for (std::size_t l = 0; l < x.loads.size(); ++l) {
      EXPECT_EQ(x.loads[l].condition, y.loads[l].condition);
      EXPECT_EQ(x.loads[l].force, y.loads[l].force);
      EXPECT_EQ(x.loads[l].moment, y.loads[l].moment);
    }
  }
  EXPECT_EQ(a.solver.linear_solver, b.solver.linear_solver);
  EXPECT_EQ(a.solver.max_newton_iterations, b.solver.max_newton_iterations);
  EXPECT_EQ(a.solver.residual_tolerance, b.solver.residual_tolerance);
  EXPECT_EQ(a.solver.increment_tolerance, b.solver.increment_tolerance);
  EXPECT_EQ(a.solver.max_cutbacks, b.solver.max_cutbacks);
  EXPECT_EQ(a.solver.easy_iterations, b.solver.easy_iterations);
  EXPECT_EQ(a.solver.line_search, b.solver.line_search);
  EXPECT_EQ(a.solver.director_update, b.solver.director_update);
  EXPECT_EQ(a.solver.gauss_points, b.solver.gauss_points);
  EXPECT_EQ(a.solver.fold_stiffness, b.solver.fold_stiffness);
  EXPECT_EQ(a.output.vtk_every, b.output.vtk_every);
  EXPECT_EQ(a.output.tube_sides, b.output.tube_sides);
  EXPECT_EQ(a.output.progress_seconds, b.output.progress_seconds);
  EXPECT_EQ(a.contact.enabled, b.contact.enabled);
  EXPECT_EQ(a.contact.self_contact, b.contact.self_contact);
  // describe names every beam where the file leaves contact.beams out (all beams)
  std::vector<int> all_beams(a.beams.size());
  for (std::size_t i = 0; i < all_beams.size(); ++i) all_beams[i] = static_cast<int>(i);
  EXPECT_EQ(a.contact.beams.empty() ? all_beams : a.contact.beams,
            b.contact.beams.empty() ? all_beams : b.contact.beams);
  EXPECT_EQ(a.contact.proximity_distance, b.contact.proximity_distance);
  EXPECT_EQ(a.contact.separation_distance, b.contact.separation_distance);
  EXPECT_EQ(a.contact.test_point_spacing, b.contact.test_point_spacing);
  EXPECT_EQ(a.contact.matching_length, b.contact.matching_length);
  EXPECT_EQ(a.contact.element_spacing, b.contact.element_spacing);
  EXPECT_EQ(a.contact.forces, b.contact.forces);
  EXPECT_EQ(a.contact.penalty, b.contact.penalty);
  EXPECT_EQ(a.contact.max_penetration, b.contact.max_penetration);
  EXPECT_EQ(a.contact.regularization, b.contact.regularization);
  EXPECT_EQ(a.contact.friction, b.contact.friction);
  EXPECT_EQ(a.contact.max_reversible_slip, b.contact.max_reversible_slip);
  EXPECT_EQ(a.contact.max_detections, b.contact.max_detections);
  EXPECT_EQ(a.contact.max_normal_iterations, b.contact.max_normal_iterations);
  EXPECT_EQ(a.contact.normal_tolerance, b.contact.normal_tolerance);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ScenarioDescribe, ShowsResolvedValuesAndDefaults) {
  const std::string text = describe(parse_scenario(kFull, "full.yaml"));
  EXPECT_TRUE(contains(text, "full.yaml")) << text;
  EXPECT_TRUE(contains(text, "young_modulus: 210000")) << text;
  EXPECT_TRUE(contains(text, "direction: [0.6, 0.8, 0]")) << text;
  EXPECT_TRUE(contains(text, "direction: [0, 0, -1]")) << text;
  EXPECT_TRUE(contains(text, "director1: [1, 0, 0]")) << text;
  EXPECT_TRUE(contains(text, "bending_factor: 1")) << text;  // default filled in
  EXPECT_TRUE(contains(text, "dofs: [position, g1x]")) << text;
  EXPECT_TRUE(contains(text, "dofs: [directors]")) << text;
  EXPECT_TRUE(contains(text, "at: end  # node 600")) << text;
  EXPECT_TRUE(contains(text, "{at: 1, translation: [0, 0, 0], rotation: [720, 0, 0]}")) << text;
  EXPECT_TRUE(contains(text, "mid_load: {force: [0, -1, 0], moment: [0, 0, -4]}")) << text;
  EXPECT_TRUE(contains(text, "linear_solver: umfpack")) << text;
  EXPECT_TRUE(contains(text, "residual_tolerance: 1e-10")) << text;
  EXPECT_TRUE(contains(text, "tube_sides: 16")) << text;
  EXPECT_TRUE(contains(text,
                       "  self_contact: false\n  beams: [vertical, rod]\n  proximity_distance: 0.5  # mm\n"
                       "  separation_distance: auto  # mm\n"))
      << text;

  const std::string base = describe(parse_scenario(kBase, "knot.yaml"));
  EXPECT_TRUE(contains(base, "gauss_points: 2")) << base;
  EXPECT_TRUE(contains(base, "linear_solver: cholmod")) << base;
  EXPECT_TRUE(contains(base, "start: [0, 0, 0]")) << base;
  EXPECT_TRUE(contains(base, "duration: 1")) << base;
  EXPECT_TRUE(contains(base, "dofs: [all]")) << base;
  EXPECT_TRUE(contains(base, "active: false")) << base;
  EXPECT_TRUE(contains(base, "contact:\n  enabled: false\n")) << base;
}

TEST(ScenarioDescribe, IsItselfAValidScenarioWithTheSameContent) {
  for (const std::string& yaml : {kBase, kFull}) {
    const Scenario original = parse_scenario(yaml, "original.yaml");
    const std::string text = describe(original);
    Scenario again;
    ASSERT_NO_THROW(again = parse_scenario(text, "described.yaml")) << text;
    expect_same(original, again);
  }
}

TEST(ScenarioDescribe, QuotesNamesThatNeedIt) {
  std::string yaml = with_line(kBase, 2, "  - name: \"my: nylon\"");
  yaml = with_line(yaml, 7, "    material: \"my: nylon\"");
  yaml = with_line(yaml, 6, "  - name: \"true\"");
  for (int line : {14, 18, 23}) yaml = with_line(yaml, line, "    beam: \"true\"");
  const Scenario original = parse_scenario(yaml, "q.yaml");
  const Scenario again = parse_scenario(describe(original), "q2.yaml");
  EXPECT_EQ(again.materials[0].name, "my: nylon");
  EXPECT_EQ(again.beams[0].name, "true");
}

// ---- files ----

TEST(ScenarioFiles, ReadsFromDisk) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("nodus_scenario_test_" + std::to_string(::getpid()) + ".yaml");
  {
    std::ofstream out(path);
    out << kBase;
  }
  const Scenario s = read_scenario(path.string());
  EXPECT_EQ(s.path, path.string());
  EXPECT_EQ(s.beams.at(0).elements, 10);

  {
    std::ofstream out(path);
    out << with_line(kBase, 8, "    radius: -0.1");
  }
  try {
    read_scenario(path.string());
    ADD_FAILURE() << "no error";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(std::string(error.what()),
              path.string() + ":8: beams[0].radius: expected a number > 0 (mm), got -0.1");
  }
  std::filesystem::remove(path);
}

TEST(ScenarioFiles, MissingFile) {
  const std::string path = "/nonexistent/nodus/no_such_scenario.yaml";
  try {
    read_scenario(path);
    ADD_FAILURE() << "no error";
  } catch (const ScenarioError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
    EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_THROW(read_scenario(std::filesystem::temp_directory_path().string()), ScenarioError);  // a directory
}

}  // namespace
}  // namespace nodus::scenario
