// Tests of the key table: consistent, in sync with the struct defaults and with docs/scenario.md; and the
// defaults of the scenario structs equal those of the library structs that the run fills from them.

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"
#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/contact_loops.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::scenario {
namespace {

std::string read_docs() {
  std::ifstream in(std::string(NODUS_SOURCE_DIR) + "/docs/scenario.md");
  EXPECT_TRUE(in.good()) << "cannot open docs/scenario.md";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ScenarioKeys, EveryKeyPathIsDocumented) {
  const std::string docs = read_docs();
  for (const KeyDoc& key : scenario_keys()) {
    EXPECT_NE(docs.find(std::string(key.path)), std::string::npos)
        << key.path << " missing from docs/scenario.md";
  }
}

TEST(ScenarioKeys, DocsHoldTheCurrentTable) {
  EXPECT_NE(read_docs().find(scenario_keys_markdown()), std::string::npos)
      << "docs/scenario.md does not hold the current output of scenario_keys_markdown(); paste it:\n"
      << scenario_keys_markdown();
}

TEST(ScenarioKeys, DocsExampleIsValid) {
  // Every ```yaml block of the docs whose first line starts with "# Example" is a complete valid scenario.
  const std::string docs = read_docs();
  int examples = 0;
  for (std::size_t start = docs.find("```yaml\n# Example"); start != std::string::npos;
       start = docs.find("```yaml\n# Example", start + 1)) {
    const std::size_t begin = start + 8;
    const std::size_t end = docs.find("```", begin);
    ASSERT_NE(end, std::string::npos);
    EXPECT_NO_THROW(parse_scenario(docs.substr(begin, end - begin), "docs/scenario.md example"));
    ++examples;
  }
  EXPECT_GE(examples, 1);
}

TEST(ScenarioKeys, TableIsConsistent) {
  const std::set<std::string_view> types{"number", "integer", "string", "bool",
                                         "vector", "list",    "map",    "choice"};
  std::set<std::string_view> paths;
  for (const KeyDoc& key : scenario_keys()) {
    EXPECT_TRUE(paths.insert(key.path).second) << "duplicate " << key.path;
    EXPECT_TRUE(types.count(key.type)) << key.path << ": type " << key.type;
    EXPECT_FALSE(key.default_value.empty()) << key.path;
    EXPECT_FALSE(key.help.empty()) << key.path;
    if (key.type == "choice") {
      EXPECT_FALSE(key.range.empty()) << key.path;
    }
    // The parent of every key is a key listed before it (a list for "[]" items).
    std::string parent(parent_pattern(key.path));
    if (parent.empty()) continue;
    if (parent.ends_with("[]")) parent.resize(parent.size() - 2);
    EXPECT_TRUE(paths.count(parent)) << key.path << ": parent " << parent << " not listed before it";
  }
}

TEST(ScenarioKeys, ExpectedTexts) {
  EXPECT_EQ(expected_text(scenario_key("beams[].radius")), "a number > 0 (mm)");
  EXPECT_EQ(expected_text(scenario_key("materials[].poisson_ratio")), "a number in [0, 0.5)");
  EXPECT_EQ(expected_text(scenario_key("beams[].elements")), "an integer >= 1");
  EXPECT_EQ(expected_text(scenario_key("solver.linear_solver")),
            "one of cholmod | umfpack | mumps | klu | petsc | auto");
  EXPECT_EQ(expected_text(scenario_key("units.length")), "exactly mm");
  EXPECT_EQ(expected_text(scenario_key("solver.line_search")), "true or false");
  EXPECT_EQ(expected_text(scenario_key("beams[].start")), "a list of 3 numbers (mm)");
  EXPECT_EQ(expected_text(scenario_key("contact.proximity_distance")), "a number > 0 or auto (mm)");
  EXPECT_EQ(expected_text(scenario_key("contact.beams")), "a list of beam names, non-empty, each beam once");
  EXPECT_EQ(expected_text(scenario_key("contact")), "a map");
  EXPECT_EQ(expected_text(scenario_key("contact.penalty")), "a number > 0 or auto (N/mm)");
  EXPECT_EQ(expected_text(scenario_key("contact.friction")), "a number >= 0");
  EXPECT_EQ(expected_text(scenario_key("contact.max_detections")), "an integer >= 1");
  EXPECT_EQ(expected_text(scenario_key("contact.normal_tolerance")), "a number > 0 (rad)");
  EXPECT_EQ(expected_text(scenario_key("contact.forces")), "true or false");
  EXPECT_THROW(scenario_key("no.such.key"), std::logic_error);
}

double number(std::string_view text) {
  return std::strtod(std::string(text).c_str(), nullptr);
}

TEST(ScenarioKeys, DefaultsMatchTheStructs) {
  const SolverSettings solver;
  EXPECT_EQ(scenario_key("solver.linear_solver").default_value, "auto");
  EXPECT_EQ(solver.linear_solver, LinearSolverKind::automatic);
  EXPECT_EQ(number(scenario_key("solver.max_newton_iterations").default_value), solver.max_newton_iterations);
  EXPECT_EQ(number(scenario_key("solver.residual_tolerance").default_value), solver.residual_tolerance);
  EXPECT_EQ(number(scenario_key("solver.increment_tolerance").default_value), solver.increment_tolerance);
  EXPECT_EQ(number(scenario_key("solver.max_cutbacks").default_value), solver.max_cutbacks);
  EXPECT_EQ(number(scenario_key("solver.easy_iterations").default_value), solver.easy_iterations);
  EXPECT_EQ(scenario_key("solver.line_search").default_value, solver.line_search ? "true" : "false");
  EXPECT_EQ(number(scenario_key("solver.gauss_points").default_value), solver.gauss_points);
  EXPECT_EQ(number(scenario_key("solver.fold_stiffness").default_value), solver.fold_stiffness);

  const OutputSettings output;
  EXPECT_EQ(number(scenario_key("output.vtk_every").default_value), output.vtk_every);
  EXPECT_EQ(number(scenario_key("output.tube_sides").default_value), output.tube_sides);
  EXPECT_EQ(number(scenario_key("output.progress_seconds").default_value), output.progress_seconds);
  EXPECT_EQ(number(scenario_key("output.checkpoint_every").default_value), output.checkpoint_every);
  EXPECT_EQ(scenario_key("output.hdf5").default_value, "true");
  EXPECT_TRUE(output.hdf5);

  const BeamSpec beam;
  EXPECT_EQ(number(scenario_key("beams[].bending_factor").default_value), beam.bending_factor);
  EXPECT_EQ(scenario_key("beams[].start").default_value, "[0, 0, 0]");
  EXPECT_EQ(scenario_key("beams[].direction").default_value, "[1, 0, 0]");
  const ContactSettings contact;
  EXPECT_EQ(scenario_key("contact.enabled").default_value, "true");  // when the section is present
  EXPECT_FALSE(contact.enabled);                                     // no section: no contact
  EXPECT_EQ(scenario_key("contact.self_contact").default_value, contact.self_contact ? "true" : "false");
  EXPECT_EQ(scenario_key("contact.beams").default_value, "all beams");
  EXPECT_TRUE(contact.beams.empty());
  for (const char* key :
       {"contact.proximity_distance", "contact.separation_distance", "contact.test_point_spacing",
        "contact.matching_length", "contact.element_spacing"}) {
    EXPECT_EQ(scenario_key(key).default_value, "auto") << key;
    EXPECT_EQ(scenario_key(key).unit, "mm") << key;
  }
  EXPECT_EQ(contact.proximity_distance, 0.0);
  EXPECT_EQ(contact.separation_distance, 0.0);
  EXPECT_EQ(contact.test_point_spacing, 0.0);
  EXPECT_EQ(contact.matching_length, 0.0);
  EXPECT_EQ(contact.element_spacing, 0.0);
  EXPECT_EQ(scenario_key("contact.forces").default_value, contact.forces ? "true" : "false");
  EXPECT_EQ(scenario_key("contact.penalty").default_value, "auto");
  EXPECT_EQ(scenario_key("contact.penalty").unit, "N/mm");
  EXPECT_EQ(contact.penalty, 0.0);
  for (const char* key :
       {"contact.max_penetration", "contact.regularization", "contact.max_reversible_slip"}) {
    EXPECT_EQ(scenario_key(key).default_value, "auto") << key;
    EXPECT_EQ(scenario_key(key).unit, "mm") << key;
  }
  EXPECT_EQ(contact.max_penetration, 0.0);
  EXPECT_EQ(contact.regularization, 0.0);
  EXPECT_EQ(contact.max_reversible_slip, 0.0);
  EXPECT_EQ(number(scenario_key("contact.friction").default_value), contact.friction);
  EXPECT_EQ(number(scenario_key("contact.max_detections").default_value), contact.max_detections);
  EXPECT_EQ(number(scenario_key("contact.max_normal_iterations").default_value),
            contact.max_normal_iterations);
  EXPECT_EQ(number(scenario_key("contact.normal_tolerance").default_value), contact.normal_tolerance);
  EXPECT_EQ(scenario_key("contact.normal_tolerance").unit, "rad");
  EXPECT_EQ(scenario_key("contact.friction_tangent").default_value, "frozen");
  EXPECT_EQ(contact.friction_tangent, FrictionTangent::frozen);

  const StageSpec stage;
  EXPECT_EQ(number(scenario_key("stages[].duration").default_value), stage.duration);
  EXPECT_EQ(scenario_key("conditions[].active").default_value,
            ConditionSpec{}.initially_active ? "true" : "false");
}

// A library user who leaves a setting at its default gets what a scenario file that leaves out the key gets:
// each pair of defaults, scenario struct and library struct, is equal.
TEST(ScenarioKeys, LibraryDefaultsEqualTheScenarioDefaults) {
  const SolverSettings solver;
  const nodus::solver::NewtonSettings newton;
  EXPECT_EQ(newton.max_iterations, solver.max_newton_iterations);
  EXPECT_EQ(newton.stagnation_iterations, solver.stagnation_iterations);
  EXPECT_EQ(newton.line_search, solver.line_search);
  EXPECT_FALSE(newton.line_search);  // the scenario default (docs/model.md)
  EXPECT_EQ(newton.backtrack_from, solver.backtrack_from);
  EXPECT_EQ(newton.backtrack_from, 0);  // off: the full Newton step, as before the key
  const nodus::solver::StepControl stepping;
  EXPECT_EQ(stepping.max_cutbacks, solver.max_cutbacks);
  EXPECT_EQ(stepping.easy_iterations, solver.easy_iterations);
  const simulation::Tolerances tolerances;
  EXPECT_EQ(tolerances.residual, solver.residual_tolerance);
  EXPECT_EQ(tolerances.increment, solver.increment_tolerance);
  const model::Model model;
  EXPECT_EQ(model.gauss_points(), solver.gauss_points);
  EXPECT_EQ(model.fold_stiffness(), solver.fold_stiffness);

  const ContactSettings contact;
  const contact::DetectionParameters detection;
  EXPECT_EQ(detection.self_contact, contact.self_contact);
  // Lengths <= 0: auto in both.
  EXPECT_EQ(detection.proximity_distance, contact.proximity_distance);
  EXPECT_EQ(detection.separation_distance, contact.separation_distance);
  EXPECT_EQ(detection.test_point_spacing, contact.test_point_spacing);
  EXPECT_EQ(detection.matching_length, contact.matching_length);
  EXPECT_EQ(detection.element_spacing, contact.element_spacing);
  const simulation::ContactLawSettings laws;
  EXPECT_EQ(laws.max_detections, contact.max_detections);
  EXPECT_EQ(laws.max_normal_iterations, contact.max_normal_iterations);
  EXPECT_EQ(laws.normal_tolerance, contact.normal_tolerance);
  EXPECT_EQ(laws.facing_particles, contact.facing_particles);
  EXPECT_EQ(laws.centre_facing, contact.centre_facing);
  EXPECT_EQ(laws.friction_normal_coupling, contact.friction_tangent == FrictionTangent::varying);
  EXPECT_FALSE(laws.friction.has_value());  // no friction, as contact.friction = 0
  EXPECT_EQ(contact.friction, 0.0);
}

TEST(ScenarioKeys, MarkdownHasOneRowPerKey) {
  const std::string table = scenario_keys_markdown();
  std::istringstream in(table);
  int rows = 0;
  for (std::string line; std::getline(in, line);) {
    ASSERT_TRUE(line.starts_with("| ") || line.starts_with("|--")) << line;
    ++rows;
  }
  EXPECT_EQ(rows, static_cast<int>(scenario_keys().size()) + 2);
  EXPECT_NE(table.find("| `beams[].radius` | number | mm | required | > 0 |"), std::string::npos) << table;
  EXPECT_NE(table.find("clamp \\| motion \\| rigid \\| load"), std::string::npos) << table;  // escaped bars
}

}  // namespace
}  // namespace nodus::scenario
