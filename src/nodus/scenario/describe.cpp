#include "nodus/scenario/describe.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

namespace {

/// A name as a YAML scalar: plain when safe, double-quoted otherwise.
std::string yaml_name(const std::string& name) {
  static constexpr std::string_view kReserved[] = {"true", "false", "null", "yes", "no",
                                                   "on",   "off",   "y",    "n",   "~"};
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool simple =
      !name.empty() && (std::isalpha(static_cast<unsigned char>(name.front())) || name.front() == '_') &&
      std::all_of(name.begin(), name.end(),
                  [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-' || c == '.'; }) &&
      std::find(std::begin(kReserved), std::end(kReserved), lower) == std::end(kReserved);
  if (simple) return name;
  std::string out = "\"";
  for (char c : name) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string describe_dofs(const DofMask& mask) {
  if (std::all_of(mask.begin(), mask.end(), [](bool b) { return b; })) return "[all]";
  std::vector<std::string> items;
  if (mask[kX] && mask[kY] && mask[kZ]) {
    items.emplace_back("position");
  } else {
    for (int dof = kX; dof <= kZ; ++dof) {
      if (mask[dof]) items.emplace_back(kDofNames[dof]);
    }
  }
  if (std::all_of(mask.begin() + kG1x, mask.end(), [](bool b) { return b; })) {
    items.emplace_back("directors");
  } else {
    for (int dof = kG1x; dof <= kG2z; ++dof) {
      if (mask[dof]) items.emplace_back(kDofNames[dof]);
    }
  }
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i > 0 ? ", " : "") + items[i];
  return out + "]";
}

std::string describe_names(const Scenario& scenario, const std::vector<int>& conditions) {
  std::string out = "[";
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    out += (i > 0 ? ", " : "") + yaml_name(scenario.conditions[conditions[i]].name);
  }
  return out + "]";
}

/// The items of a list of stages, each line starting with `indent`.
void describe_stages(std::string& out, const Scenario& scenario, const std::vector<StageSpec>& stages,
                     std::string_view indent) {
  const auto line = [&out, indent](std::string_view text) {
    out += indent;
    out += text;
    out += '\n';
  };
  for (const StageSpec& stage : stages) {
    line(fmt::format("  - name: {}", yaml_name(stage.name)));
    line(fmt::format("    steps: {}", stage.steps));
    line(fmt::format("    duration: {}  # s", format_number(stage.duration)));
    if (stage.stabilization > 0.0) {
      line(fmt::format("    stabilization: {}  # N s/mm^2", format_number(stage.stabilization)));
      line(fmt::format("    stabilization_end: {}  # N s/mm^2", format_number(stage.stabilization_end)));
    }
    line(fmt::format("    activate: {}", describe_names(scenario, stage.activate)));
    line(fmt::format("    release: {}", describe_names(scenario, stage.release)));
    const auto beam_list = [&](const std::vector<int>& beams) {
      std::vector<std::string> names;
      for (int b : beams) names.push_back(yaml_name(scenario.beams.at(static_cast<std::size_t>(b)).name));
      return fmt::format("[{}]", fmt::join(names, ", "));
    };
    if (!stage.contact_off.empty()) line(fmt::format("    contact_off: {}", beam_list(stage.contact_off)));
    if (!stage.contact_on.empty()) line(fmt::format("    contact_on: {}", beam_list(stage.contact_on)));
    line(stage.motions.empty() ? "    motions: {}" : "    motions:");
    for (const MotionTarget& motion : stage.motions) {
      line(fmt::format("      {}:", yaml_name(scenario.conditions.at(motion.condition).name)));
      line("        keyframes:  # translation [mm], rotation vector [deg], cumulative since activation");
      for (const Keyframe& frame : motion.keyframes) {
        line(fmt::format("          - {{at: {}, translation: {}, rotation: {}}}", format_number(frame.at),
                         format_vec(frame.translation), format_vec(frame.rotation)));
      }
    }
    line(stage.loads.empty() ? "    loads: {}" : "    loads:  # at stage end: force [N], moment [N mm]");
    for (const LoadTarget& load : stage.loads) {
      line(fmt::format("      {}: {{force: {}, moment: {}}}",
                       yaml_name(scenario.conditions.at(load.condition).name), format_vec(load.force),
                       format_vec(load.moment)));
    }
  }
}

}  // namespace

std::string describe(const Scenario& scenario) {
  std::string out;
  const auto line = [&out](std::string_view text) {
    out += text;
    out += '\n';
  };
  line(fmt::format("# scenario: {}", scenario.path));
  line("units: {length: mm, force: N, stress: MPa, time: s}");

  line("materials:");
  for (const Material& material : scenario.materials) {
    line(fmt::format("  - name: {}", yaml_name(material.name)));
    line(fmt::format("    young_modulus: {}  # MPa", format_number(material.young_modulus)));
    line(fmt::format("    poisson_ratio: {}", format_number(material.poisson_ratio)));
  }

  line("beams:");
  for (const BeamSpec& beam : scenario.beams) {
    line(fmt::format("  - name: {}", yaml_name(beam.name)));
    line(fmt::format("    material: {}", yaml_name(scenario.materials.at(beam.material).name)));
    line(fmt::format("    radius: {}  # mm", format_number(beam.radius)));
    line(fmt::format("    length: {}  # mm", format_number(beam.length)));
    line(fmt::format("    elements: {}  # nodes 0..{}", beam.elements, 2 * beam.elements));
    line(fmt::format("    start: {}  # mm", format_vec(beam.start)));
    line(fmt::format("    direction: {}", format_vec(beam.direction)));
    line(fmt::format("    director1: {}", format_vec(beam.director1)));
    line(fmt::format("    bending_factor: {}", format_number(beam.bending_factor)));
  }

  if (scenario.conditions.empty()) {
    line("conditions: []");
  } else {
    line("conditions:");
  }
  for (const ConditionSpec& condition : scenario.conditions) {
    const BeamSpec& beam = scenario.beams.at(condition.beam);
    line(fmt::format("  - name: {}  # line {}", yaml_name(condition.name), condition.line));
    line(fmt::format("    type: {}", type_name(condition.type)));
    line(fmt::format("    beam: {}", yaml_name(beam.name)));
    if (condition.pivot) line(fmt::format("    pivot: {}  # mm", format_vec(*condition.pivot)));
    if (condition.type == ConditionType::rigid) {
      line(fmt::format("    active: {}", condition.initially_active ? "true" : "false"));
      continue;
    }
    const std::string at = condition.node == 0                   ? std::string("start")
                           : condition.node == 2 * beam.elements ? std::string("end")
                                                                 : std::to_string(condition.node);
    line(fmt::format("    at: {}  # node {}", at, condition.node));
    if (condition.type == ConditionType::load) {
      line(fmt::format("    force: {}  # N", format_vec(condition.force)));
      line(fmt::format("    moment: {}  # N mm", format_vec(condition.moment)));
    } else {
      line(fmt::format("    dofs: {}", describe_dofs(condition.dofs)));
    }
    line(fmt::format("    active: {}", condition.initially_active ? "true" : "false"));
  }

  line("stages:");
  describe_stages(out, scenario, scenario.stages, "");

  const SolverSettings& solver = scenario.solver;
  line("solver:");
  line(fmt::format("  linear_solver: {}",
                   solver.linear_solver == LinearSolverKind::cholmod ? "cholmod" : "umfpack"));
  line(fmt::format("  max_newton_iterations: {}", solver.max_newton_iterations));
  line(fmt::format("  residual_tolerance: {}", format_number(solver.residual_tolerance)));
  line(fmt::format("  increment_tolerance: {}", format_number(solver.increment_tolerance)));
  line(fmt::format("  max_cutbacks: {}", solver.max_cutbacks));
  line(fmt::format("  easy_iterations: {}", solver.easy_iterations));
  line(fmt::format("  line_search: {}", solver.line_search ? "true" : "false"));
  line(fmt::format("  gauss_points: {}", solver.gauss_points));
  line(fmt::format("  fold_stiffness: {}", format_number(solver.fold_stiffness)));

  const OutputSettings& output = scenario.output;
  line("output:");
  line(fmt::format("  vtk_every: {}", output.vtk_every));
  line(fmt::format("  tube_sides: {}", output.tube_sides));
  line(fmt::format("  progress_seconds: {}  # s", format_number(output.progress_seconds)));
  line(fmt::format("  contact_csv: {}", output.contact_csv ? "true" : "false"));
  line(fmt::format("  checkpoint_every: {}", output.checkpoint_every));

  const ContactSettings& contact = scenario.contact;
  line("contact:");
  line(fmt::format("  enabled: {}", contact.enabled ? "true" : "false"));
  line(fmt::format("  self_contact: {}", contact.self_contact ? "true" : "false"));
  std::string beams = "[";
  if (contact.beams.empty()) {
    for (std::size_t i = 0; i < scenario.beams.size(); ++i) {
      beams += (i > 0 ? ", " : "") + yaml_name(scenario.beams[i].name);
    }
    line(fmt::format("  beams: {}]  # all beams", beams));
  } else {
    for (std::size_t i = 0; i < contact.beams.size(); ++i) {
      beams += (i > 0 ? ", " : "") + yaml_name(scenario.beams.at(contact.beams[i]).name);
    }
    line(fmt::format("  beams: {}]", beams));
  }
  const auto or_auto = [&line](std::string_view key, double value, std::string_view unit) {
    line(fmt::format("  {}: {}  # {}", key, value > 0.0 ? format_number(value) : std::string("auto"), unit));
  };
  or_auto("proximity_distance", contact.proximity_distance, "mm");
  or_auto("separation_distance", contact.separation_distance, "mm");
  or_auto("test_point_spacing", contact.test_point_spacing, "mm");
  or_auto("matching_length", contact.matching_length, "mm");
  or_auto("element_spacing", contact.element_spacing, "mm");
  line(fmt::format("  forces: {}", contact.forces ? "true" : "false"));
  or_auto("penalty", contact.penalty, "N/mm");
  or_auto("max_penetration", contact.max_penetration, "mm");
  or_auto("regularization", contact.regularization, "mm");
  line(fmt::format("  friction: {}", format_number(contact.friction)));
  or_auto("max_reversible_slip", contact.max_reversible_slip, "mm");
  line(fmt::format("  friction_tangent: {}",
                   contact.friction_tangent == FrictionTangent::varying ? "varying" : "frozen"));
  line(fmt::format("  particles: {}", contact.facing_particles ? "facing" : "fixed"));
  line(fmt::format("  max_detections: {}", contact.max_detections));
  line(fmt::format("  max_normal_iterations: {}", contact.max_normal_iterations));
  line(fmt::format("  normal_tolerance: {}  # rad", format_number(contact.normal_tolerance)));

  if (!scenario.branches.empty()) {
    line("branches:");
    for (const BranchSpec& branch : scenario.branches) {
      line(fmt::format("  - name: {}", yaml_name(branch.name)));
      line(fmt::format("    from: {}",
                       yaml_name(scenario.stages.at(static_cast<std::size_t>(branch.from)).name)));
      if (branch.friction)
        line(fmt::format("    contact: {{friction: {}}}", format_number(*branch.friction)));
      line("    stages:");
      describe_stages(out, scenario, branch.stages, "    ");
    }
  }
  return out;
}

}  // namespace nodus::scenario
