#include "nodus/scenario/scenario.hpp"

#include <string>

#include <yaml-cpp/yaml.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/linear_solver_choice.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yaml_input.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

namespace {

/// Each stage's own linear solver (stages[].linear_solver, also in the branches) against the scenario's.
void check_stage_solvers(const Reader& reader, const MapView& top, const Scenario& s) {
  const auto check = [&](const Field& list, const std::vector<StageSpec>& stages) {
    const std::vector<Field> items = reader.list(list, true);
    for (std::size_t k = 0; k < stages.size() && k < items.size(); ++k) {
      const std::string_view expected = stage_solver_expected(stages[k], s);
      if (!expected.empty()) reader.fail(*MapView(reader, items[k]).get("linear_solver"), expected);
    }
  };
  check(top.require("stages"), s.stages);
  const auto branches = top.get("branches");
  if (!branches) return;
  const std::vector<Field> items = reader.list(*branches, true);
  for (std::size_t b = 0; b < s.branches.size() && b < items.size(); ++b) {
    const Field stages = MapView(reader, items[b]).require("stages");
    check(Field{stages.node, stages.path, "stages", stages.line}, s.branches[b].stages);  // as read_branches
  }
}

Scenario parse_root(const Reader& reader, const YAML::Node& root, const std::string& path) {
  if (!root.IsMap()) {
    std::string keys;
    for (const KeyDoc& key : scenario_keys()) {
      if (parent_pattern(key.path).empty()) keys += (keys.empty() ? "" : " | ") + std::string(key.path);
    }
    reader.fail(line_of(root, 1), "top level", "a map with the keys " + keys,
                root.IsNull() ? std::string("nothing (empty document)") : render(root));
  }
  const MapView top(reader, Field{root, "", "", line_of(root, 1)});
  Scenario scenario;
  scenario.path = path;
  read_units(reader, top);
  NameTable material_names;
  NameTable beam_names;
  NameTable condition_names;
  NameTable body_names;
  scenario.materials = read_materials(reader, top, material_names);
  scenario.beams = read_beams(reader, top, material_names, beam_names);
  // The yarns' fibres after the file's beams, and their bodies; the file's bodies, which may bind yarn
  // fibres, come after them.
  read_yarns(reader, top, material_names, beam_names, scenario);
  // Names of the yarns' bodies first, so that the file's bodies and conditions cannot take them.
  for (const BodySpec& body : scenario.bodies) {
    body_names.index_and_line.emplace(body.name,
                                      std::pair{static_cast<int>(body_names.names.size()), body.line});
    body_names.names.push_back(body.name);
  }
  std::vector<BodySpec> bodies = read_bodies(reader, top, beam_names, scenario.beams, body_names);
  scenario.bodies.insert(scenario.bodies.end(), bodies.begin(), bodies.end());
  MomentAxes moment_axes;
  scenario.conditions =
      read_conditions(reader, top, beam_names, scenario.beams, body_names, condition_names, moment_axes);

  scenario.contact = read_contact(reader, top, beam_names);
  if (const TestPoints points = contact_test_points(scenario); points.count > max_test_points()) {
    const Field contact = *top.get("contact");
    const auto spacing = MapView(reader, contact).get("test_point_spacing");
    reader.fail(spacing ? spacing->line : contact.line, "contact.test_point_spacing",
                test_points_expected(points), spacing ? render(spacing->node) : "auto");
  }
  LoadValues load_values = initial_load_values(scenario.conditions);
  std::vector<LoadValues> load_values_after;
  NameTable stage_names;
  scenario.stages =
      read_stages(reader, top.require("stages"), condition_names, scenario.conditions, beam_names,
                  scenario.contact, moment_axes, load_values, stage_names, &load_values_after);
  scenario.solver = read_solver(reader, top);
  if (scenario.solver.linear_solver == LinearSolverKind::petsc && !parallel::available())
    reader.fail(*MapView(reader, *top.get("solver")).get("linear_solver"), kPetscBuildExpected);
  if (scenario.contact.friction_tangent == FrictionTangent::varying &&
      scenario.solver.linear_solver == LinearSolverKind::cholmod) {
    reader.fail(*MapView(reader, *top.get("contact")).get("friction_tangent"), kFrictionTangentExpected);
  }
  if (scenario.contact.normal_updates == NormalUpdates::linearized &&
      scenario.solver.linear_solver == LinearSolverKind::cholmod) {
    reader.fail(*MapView(reader, *top.get("contact")).get("normal_updates"), kLinearizedNormalsExpected);
  }
  scenario.output = read_output(reader, top);
  scenario.branches =
      read_branches(reader, top, stage_names, load_values_after, condition_names, scenario.conditions,
                    beam_names, scenario.contact, top.get("contact").has_value(), moment_axes);
  for (std::size_t c = 0; c < scenario.conditions.size(); ++c) {
    if (scenario.conditions[c].type == ConditionType::load) {
      scenario.conditions[c].moment_axis = moment_axes.axis(static_cast<int>(c));
    }
  }
  choose_linear_solver(scenario);  // after the branches: their stages' own solvers count
  check_stage_solvers(reader, top, scenario);
  // Everything read has been checked with its line; this checks the same again, as for a scenario built in
  // code, so that validate() accepts whatever the reader accepts.
  validate(scenario);
  return scenario;
}

}  // namespace

Scenario parse_scenario(const std::string& yaml_text, const std::string& path) {
  const Reader reader(path);
  // Encoding, a single document and the number of nodes, before yaml-cpp builds its tree.
  check_yaml_input(yaml_text, path);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    reader.fail(error.mark.line >= 0 ? error.mark.line + 1 : 0, "yaml", "valid YAML", one_line(error.msg));
  }
  try {
    return parse_root(reader, root, path);
  } catch (const YAML::Exception& error) {  // not expected: the reader checks node types before use
    reader.fail(error.mark.line >= 0 ? error.mark.line + 1 : 0, "yaml", "a readable scenario",
                one_line(error.msg));
  }
}

Scenario read_scenario(const std::string& path) {
  return parse_scenario(read_scenario_text(path), path);
}

Scenario branch_scenario(const Scenario& main, std::size_t branch) {
  const BranchSpec& spec = main.branches.at(branch);
  Scenario out = main;
  out.stages.resize(static_cast<std::size_t>(spec.from) + 1);
  out.stages.insert(out.stages.end(), spec.stages.begin(), spec.stages.end());
  if (spec.friction) out.contact.friction = *spec.friction;
  out.origin = BranchOrigin{spec.name, spec.from, main.contact.friction};
  out.branches.clear();
  return out;
}

}  // namespace nodus::scenario
