#include "nodus/scenario/describe.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <span>
#include <type_traits>

#include <fmt/format.h>

#include "nodus/scenario/declared_keys.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yaml_reader.hpp"
#include "nodus/scenario/yarn.hpp"

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

/// The declared keys of one section or list item, "INDENT KEY: VALUE  # UNIT" each, in declaration order.
/// `hook`, if given, sees every key first: it returns true where it printed the key itself (or left it out on
/// purpose); structural keys are printed by the hook or not at all.
template <class Owner>
void describe_keys(std::string& out, std::span<const Key<Owner>> keys, const Owner& owner,
                   std::string_view indent,
                   const std::function<bool(const Key<std::type_identity_t<Owner>>&)>& hook = {}) {
  for (const Key<Owner>& key : keys) {
    if (hook && hook(key)) continue;
    if (!key.scalar()) continue;
    out += fmt::format("{}{}: {}", indent, leaf_name(key.path), value_text(key, owner));
    if (!key.unit.empty()) out += fmt::format("  # {}", key.unit);
    out += '\n';
  }
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
    const std::string item_indent = std::string(indent) + "    ";
    describe_keys(out, StageSpec::keys(), stage, item_indent, [&](const Key<StageSpec>& key) {
      // The drag's keys only where there is a drag, a stage's own line search, linear solver and particles
      // only where it has them.
      if (key.path == "stages[].line_search") return stage.line_search == StageSwitch::solver;
      if (key.path == "stages[].linear_solver") return !stage.linear_solver;
      if (key.path == "stages[].particles") return stage.particles == StageParticles::contact;
      return key.number &&
             (key.number == &StageSpec::stabilization || key.number == &StageSpec::stabilization_end) &&
             stage.stabilization <= 0.0;
    });
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
    describe_keys(out, Material::keys(), material, "    ");
  }

  // The beams of the file; those the yarns made are shown as their yarns.
  const std::vector<bool> from_yarns = beams_made_by_yarns(scenario);
  line(std::find(from_yarns.begin(), from_yarns.end(), false) == from_yarns.end() ? "beams: []" : "beams:");
  for (std::size_t b = 0; b < scenario.beams.size(); ++b) {
    if (from_yarns[b]) continue;
    const BeamSpec& beam = scenario.beams[b];
    line(fmt::format("  - name: {}", yaml_name(beam.name)));
    describe_keys(out, BeamSpec::keys(), beam, "    ", [&](const Key<BeamSpec>& key) {
      const std::string_view leaf = leaf_name(key.path);
      if (leaf == "material")
        line(fmt::format("    material: {}", yaml_name(scenario.materials.at(beam.material).name)));
      if (leaf == "elements")
        line(fmt::format("    elements: {}  # nodes 0..{}", beam.elements, 2 * beam.elements));
      if (leaf == "start") line(fmt::format("    start: {}  # mm", format_vec(beam.start)));
      if (leaf == "direction") line(fmt::format("    direction: {}", format_vec(beam.direction)));
      if (leaf == "director1") line(fmt::format("    director1: {}", format_vec(beam.director1)));
      return leaf != "radius" && leaf != "length" && leaf != "bending_factor";  // those: the generic line
    });
  }

  if (!scenario.yarns.empty()) line("yarns:");
  for (const YarnSpec& yarn : scenario.yarns) {
    const int fibres = yarn.rovings * yarn.fibres_per_roving;
    line(fmt::format(
        "  - name: {}  # made beams {} .. {} ({}), bodies {}", yaml_name(yarn.name),
        yaml_name(yarn_beam_name(yarn.name, 0, 0)),
        yaml_name(yarn_beam_name(yarn.name, yarn.rovings - 1, yarn.fibres_per_roving - 1)), fibres,
        yarn.bodies
            ? fmt::format("{} .. {} ({})", yaml_name(yarn_body_name(yarn.name, 0, false)),
                          yaml_name(yarn_body_name(yarn.name, yarn.rovings - 1, true)), 2 * yarn.rovings)
            : std::string("none")));
    describe_keys(out, YarnSpec::keys(), yarn, "    ", [&](const Key<YarnSpec>& key) {
      const std::string_view leaf = leaf_name(key.path);
      if (leaf == "material")
        line(fmt::format("    material: {}", yaml_name(scenario.materials.at(yarn.material).name)));
      if (leaf == "elements")
        line(fmt::format("    elements: {}  # per fibre, nodes 0..{}", yarn.elements, 2 * yarn.elements));
      if (leaf == "start") line(fmt::format("    start: {}  # mm", format_vec(yarn.start)));
      if (leaf == "direction") line(fmt::format("    direction: {}", format_vec(yarn.direction)));
      if (leaf == "clearance")
        line(fmt::format("    clearance: {}  # mm{}", format_number(yarn.gap()),
                         yarn.clearance ? "" : " (default: 0.01 fibre_radius)"));
      if (leaf == "tie" && yarn.tie <= 0.0) {
        line("    tie: auto  # 1e-10");
        return true;
      }
      return !key.scalar() || leaf == "elements";
    });
  }

  // The file's own bodies (a yarn's are echoed by its yarn).
  const std::vector<bool> made = bodies_made_by_yarns(scenario);
  if (std::find(made.begin(), made.end(), false) != made.end()) line("bodies:");
  for (std::size_t b = 0; b < scenario.bodies.size(); ++b) {
    if (made[b]) continue;
    const BodySpec& body = scenario.bodies[b];
    line(fmt::format("  - name: {}  # line {}", yaml_name(body.name), body.line));
    describe_keys(out, BodySpec::keys(), body, "    ", [&](const Key<BodySpec>& key) {
      const std::string_view leaf = leaf_name(key.path);
      if (leaf == "beams") {
        std::string names;
        for (const SectionRef& section : body.sections)
          names += (names.empty() ? "" : ", ") +
                   yaml_name(scenario.beams.at(static_cast<std::size_t>(section.beam)).name);
        line(fmt::format("    beams: [{}]", names));
      }
      if (leaf == "at")
        line(fmt::format("    at: {}",
                         !body.sections.empty() && body.sections.front().node == 0 ? "start" : "end"));
      if (leaf == "penalty" && body.penalty <= 0.0) {
        line("    penalty: auto  # 1e3");
        return true;
      }
      if (leaf == "tie" && body.tie <= 0.0) {
        line("    tie: auto  # 1e-10");
        return true;
      }
      return !key.scalar();
    });
  }

  if (scenario.conditions.empty()) {
    line("conditions: []");
  } else {
    line("conditions:");
  }
  for (const ConditionSpec& condition : scenario.conditions) {
    const BeamSpec& beam = scenario.beams.at(condition.beam);
    line(fmt::format("  - name: {}  # line {}", yaml_name(condition.name), condition.line));
    const bool rigid = condition.type == ConditionType::rigid, load = condition.type == ConditionType::load;
    const bool on_bodies = !condition.bodies.empty();
    describe_keys(out, ConditionSpec::keys(), condition, "    ", [&](const Key<ConditionSpec>& key) {
      const std::string_view leaf = leaf_name(key.path);
      if (on_bodies && (leaf == "beam" || leaf == "at")) return true;
      if (leaf == "bodies" && on_bodies) {
        std::string names;
        for (int b : condition.bodies)
          names +=
              (names.empty() ? "" : ", ") + yaml_name(scenario.bodies.at(static_cast<std::size_t>(b)).name);
        line(fmt::format("    bodies: [{}]", names));
      }
      if (leaf == "dofs" && on_bodies) {
        if (!load) {
          constexpr const char* kNames[] = {"x", "y", "z", "rx", "ry", "rz"};
          std::string dofs;
          for (std::size_t d = 0; d < 6; ++d)
            if (condition.body_dofs[d]) dofs += (dofs.empty() ? "" : ", ") + std::string(kNames[d]);
          line(fmt::format("    dofs: [{}]", dofs));
        }
        return true;
      }
      if (leaf == "beam") line(fmt::format("    beam: {}", yaml_name(beam.name)));
      if (leaf == "pivot" && condition.pivot)
        line(fmt::format("    pivot: {}  # mm", format_vec(*condition.pivot)));
      if (leaf == "at" && !rigid) {
        const std::string at = condition.node == 0                   ? std::string("start")
                               : condition.node == 2 * beam.elements ? std::string("end")
                                                                     : std::to_string(condition.node);
        line(fmt::format("    at: {}  # node {}", at, condition.node));
      }
      if (leaf == "dofs" && !rigid && !load) line(fmt::format("    dofs: {}", describe_dofs(condition.dofs)));
      if (leaf == "force" && load) line(fmt::format("    force: {}  # N", format_vec(condition.force)));
      if (leaf == "moment" && load) line(fmt::format("    moment: {}  # N mm", format_vec(condition.moment)));
      return !key.scalar();  // type and active: the generic line
    });
  }

  line("stages:");
  describe_stages(out, scenario, scenario.stages, "");

  line("solver:");
  describe_keys(out, SolverSettings::keys(), scenario.solver, "  ", [&](const Key<SolverSettings>& key) {
    if (key.path == "solver.linear_solver" && !scenario.solver.linear_solver_reason.empty()) {
      line(fmt::format("  linear_solver: {}  # {}", value_text(key, scenario.solver),
                       scenario.solver.linear_solver_reason));
      return true;
    }
    if (key.path != "solver.petsc_options") return false;
    if (!scenario.solver.petsc_options.empty())
      line(fmt::format("  petsc_options: {}", yaml_name(scenario.solver.petsc_options)));
    return true;
  });
  line("output:");
  describe_keys(out, OutputSettings::keys(), scenario.output, "  ");
  line("contact:");
  describe_keys(out, ContactSettings::keys(), scenario.contact, "  ", [&](const Key<ContactSettings>& key) {
    if (key.path != "contact.beams") return false;
    const ContactSettings& contact = scenario.contact;
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
    return true;
  });
  if (!scenario.contact.friction_pairs.empty()) {
    const auto names = [&](const std::vector<int>& list) {
      std::string text = "[";
      for (std::size_t i = 0; i < list.size(); ++i)
        text += (i > 0 ? ", " : "") + yaml_name(scenario.beams.at(static_cast<std::size_t>(list[i])).name);
      return text + "]";
    };
    line("  friction_pairs:");
    for (const FrictionPair& pair : scenario.contact.friction_pairs)
      line(fmt::format("    - {{beams: {}{}, friction: {}}}", names(pair.beams),
                       pair.with.empty() ? std::string() : ", with: " + names(pair.with),
                       format_number(pair.friction)));
  }

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
