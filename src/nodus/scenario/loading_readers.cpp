#include "nodus/scenario/section_readers.hpp"

#include "nodus/scenario/declared_keys.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace nodus::scenario {

namespace {

std::vector<int> read_condition_names(const Reader& reader, const std::optional<Field>& field,
                                      const NameTable& condition_names, std::string_view list_name) {
  std::vector<int> out;
  if (!field) return out;
  for (const Field& item : reader.list(*field, false)) {
    const auto index = condition_names.find(item.node.IsScalar() ? item.node.Scalar() : std::string());
    if (!index)
      reader.fail(item, fmt::format("the name of a condition ({})", name_list(condition_names.names)));
    if (std::find(out.begin(), out.end(), *index) != out.end()) {
      reader.fail(item, fmt::format("each condition once in {}", list_name));
    }
    out.push_back(*index);
  }
  return out;
}

/// The names of the conditions of one type, for messages.
std::vector<std::string> names_of_type(const std::vector<ConditionSpec>& conditions, ConditionType type) {
  std::vector<std::string> out;
  for (const ConditionSpec& condition : conditions) {
    if (condition.type == type) out.push_back(condition.name);
  }
  return out;
}

/// The condition a key of stages[].motions or stages[].loads names; it must have the given type (a motion
/// target may also name a rigid condition).
int target_condition(const Reader& reader, const MapView::Entry& entry, const std::string& path,
                     const NameTable& condition_names, const std::vector<ConditionSpec>& conditions,
                     ConditionType type) {
  std::vector<std::string> names = names_of_type(conditions, type);
  if (type == ConditionType::motion) {
    const std::vector<std::string> rigid = names_of_type(conditions, ConditionType::rigid);
    names.insert(names.end(), rigid.begin(), rigid.end());
  }
  const std::string expected =
      fmt::format("the name of a {} condition ({})",
                  type == ConditionType::motion ? std::string_view("motion or rigid") : type_name(type),
                  name_list(names));
  const auto index = condition_names.find(entry.key);
  if (!index) reader.fail(entry.line, path, expected, entry.key);
  const ConditionType found = conditions[*index].type;
  if (found != type && !(type == ConditionType::motion && found == ConditionType::rigid)) {
    reader.fail(entry.line, path, expected,
                fmt::format("{} (a {} condition)", entry.key, type_name(conditions[*index].type)));
  }
  return *index;
}

MotionTarget read_motion_target(const Reader& reader, const Field& field, int condition) {
  const MapView map(reader, field);
  MotionTarget target;
  target.condition = condition;
  const auto translation = map.get("translation");
  const auto rotation = map.get("rotation");
  const auto keyframes = map.get("keyframes");
  if (!keyframes) {
    Keyframe frame;
    if (translation) frame.translation = reader.vec(*translation);
    if (rotation) frame.rotation = reader.vec(*rotation);
    target.keyframes.push_back(frame);
    return target;
  }
  for (const auto& other : {translation, rotation}) {
    if (other) {
      reader.fail(*other, fmt::format("no {} next to keyframes (give either the short or the long form)",
                                      leaf_name(other->path)));
    }
  }
  const std::vector<Field> items = reader.list(*keyframes, true);
  double previous = 0.0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView frame_map(reader, items[i]);
    Keyframe frame;
    const Field at = frame_map.require("at");
    frame.at = reader.number(at);
    if (!(frame.at > previous && frame.at <= 1.0)) {
      if (i == 0) reader.fail(at);
      reader.fail(at, fmt::format("a number in ({}, 1]: greater than the at of the previous keyframe",
                                  format_number(previous)));
    }
    if (i + 1 == items.size() && frame.at != 1.0) reader.fail(at, "1 for the last keyframe");
    previous = frame.at;
    if (const auto value = frame_map.get("translation")) frame.translation = reader.vec(*value);
    if (const auto value = frame_map.get("rotation")) frame.rotation = reader.vec(*value);
    target.keyframes.push_back(frame);
  }
  return target;
}

/// stages[].contact_off or contact_on: names of beams that take part in contact.
std::vector<int> read_contact_beams(const Reader& reader, const std::optional<Field>& field,
                                    const NameTable& beam_names, const ContactSettings& contact,
                                    std::string_view list_name) {
  std::vector<int> out;
  if (!field) return out;
  if (!contact.enabled) reader.fail(*field, "no contact_off or contact_on without a contact section");
  for (const Field& item : reader.list(*field, false)) {
    const auto index = beam_names.find(item.node.IsScalar() ? item.node.Scalar() : std::string());
    if (!index) reader.fail(item, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
    if (!contact.beams.empty() &&
        std::find(contact.beams.begin(), contact.beams.end(), *index) == contact.beams.end())
      reader.fail(item, "a beam listed in contact.beams");
    if (std::find(out.begin(), out.end(), *index) != out.end())
      reader.fail(item, fmt::format("each beam once in {}", list_name));
    out.push_back(*index);
  }
  return out;
}

/// Whether a branch name can be a folder name: letters, digits, '_', '.', '-', not starting with '.'.
bool is_folder_name(const std::string& name) {
  return !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == '-';
  });
}

}  // namespace

/// The values the loads start with: their initial values.
LoadValues initial_load_values(const std::vector<ConditionSpec>& conditions) {
  LoadValues load_values;
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    if (conditions[i].type == ConditionType::load) {
      load_values[static_cast<int>(i)] = {conditions[i].force, conditions[i].moment};
    }
  }
  return load_values;
}

/// A list of stages (`stages`, or a branch's `stages`: `list` then has the pattern "stages" and its own
/// path). `load_values`: the value of each load at the start of the first stage, updated stage by stage;
/// `after_each`, if given, receives them after each stage. `stage_names` receives the names.
std::vector<StageSpec> read_stages(const Reader& reader, const Field& list, const NameTable& condition_names,
                                   const std::vector<ConditionSpec>& conditions, const NameTable& beam_names,
                                   const ContactSettings& contact, MomentAxes& moment_axes,
                                   LoadValues& load_values, NameTable& stage_names,
                                   std::vector<LoadValues>* after_each) {
  std::vector<StageSpec> stages;
  for (const Field& item : reader.list(list, true)) {
    const MapView map(reader, item);
    StageSpec stage;
    const Field name = map.require("name");
    stage.name = reader.name(name);
    stage_names.add(reader, name, stage.name, "stages");
    read_keys(reader, map, StageSpec::keys(), stage);
    if (const auto value = map.get("particles"); value && !contact.enabled)
      reader.fail(*value, kStageParticlesExpected);
    if (const auto value = map.get("stabilization_end")) {
      if (stage.stabilization_end > 0.0 && stage.stabilization == 0.0)
        reader.fail(*value, kStabilizationEndExpected);
    } else {
      stage.stabilization_end = stage.stabilization;
    }

    stage.activate = read_condition_names(reader, map.get("activate"), condition_names, "activate");
    const auto release = map.get("release");
    stage.release = read_condition_names(reader, release, condition_names, "release");
    for (std::size_t i = 0; i < stage.release.size(); ++i) {
      if (std::find(stage.activate.begin(), stage.activate.end(), stage.release[i]) != stage.activate.end()) {
        const std::vector<Field> items = reader.list(*release, false);
        reader.fail(items[i], "a condition that is not also in activate of the same stage");
      }
      if (conditions[static_cast<std::size_t>(stage.release[i])].type == ConditionType::rigid) {
        const std::vector<Field> items = reader.list(*release, false);
        reader.fail(items[i],
                    "a condition that is not rigid (a tool beam stays where its motion puts it; "
                    "take it out of contact with contact_off)");
      }
      const ConditionSpec& released = conditions[static_cast<std::size_t>(stage.release[i])];
      if (released.type == ConditionType::bind)
        reader.fail(reader.list(*release, false)[i], kReleaseBindExpected);
      if (released.bodies.size() > 1 && released.type != ConditionType::load)
        reader.fail(reader.list(*release, false)[i], kReleaseOnSeveralBodiesExpected);
    }
    const auto off = map.get("contact_off");
    stage.contact_off = read_contact_beams(reader, off, beam_names, contact, "contact_off");
    stage.contact_on = read_contact_beams(reader, map.get("contact_on"), beam_names, contact, "contact_on");
    for (std::size_t i = 0; i < stage.contact_off.size(); ++i)
      if (std::find(stage.contact_on.begin(), stage.contact_on.end(), stage.contact_off[i]) !=
          stage.contact_on.end())
        reader.fail(reader.list(*off, false)[i], "a beam that is not also in contact_on of the same stage");

    if (const auto motions = map.get("motions")) {
      const MapView targets(reader, *motions, true);
      for (const MapView::Entry& entry : targets.entries()) {
        const Field field = targets.field_of(entry);
        const int condition =
            target_condition(reader, entry, field.path, condition_names, conditions, ConditionType::motion);
        stage.motions.push_back(read_motion_target(reader, field, condition));
      }
    }

    if (const auto loads = map.get("loads")) {
      const MapView targets(reader, *loads, true);
      for (const MapView::Entry& entry : targets.entries()) {
        const Field field = targets.field_of(entry);
        const int condition =
            target_condition(reader, entry, field.path, condition_names, conditions, ConditionType::load);
        const MapView values(reader, field);
        auto& [force, moment] = load_values[condition];
        if (const auto value = values.get("force")) force = reader.vec(*value);
        if (const auto value = values.get("moment")) {
          moment = reader.vec(*value);
          moment_axes.check(reader, condition, moment, *value);
        }
        stage.loads.push_back({condition, force, moment});
      }
    }
    stages.push_back(std::move(stage));
    if (after_each) after_each->push_back(load_values);
  }
  return stages;
}

std::vector<BranchSpec> read_branches(const Reader& reader, const MapView& top, const NameTable& stage_names,
                                      const std::vector<LoadValues>& load_values_after,
                                      const NameTable& condition_names,
                                      const std::vector<ConditionSpec>& conditions,
                                      const NameTable& beam_names, const ContactSettings& contact,
                                      bool has_contact_section, MomentAxes& moment_axes) {
  std::vector<BranchSpec> branches;
  const auto list = top.get("branches");
  if (!list) return branches;
  NameTable branch_names;
  for (const Field& item : reader.list(*list, false)) {
    const MapView map(reader, item);
    BranchSpec branch;
    branch.line = map.line();
    const Field name = map.require("name");
    branch.name = reader.name(name);
    if (!is_folder_name(branch.name)) {
      reader.fail(name,
                  "a name of letters, digits, _ . - not starting with . (it names the output folder "
                  "DIR/branches/NAME)");
    }
    branch_names.add(reader, name, branch.name, "branches");

    const Field from = map.require("from");
    const auto stage = stage_names.find(reader.name(from));
    if (!stage)
      reader.fail(from, fmt::format("the name of a stage of stages ({})", name_list(stage_names.names)));
    branch.from = *stage;

    if (const auto overrides = map.get("contact")) {
      if (!has_contact_section) {
        reader.fail(*overrides, "no contact override in a scenario without a contact section");
      }
      const MapView values(reader, *overrides);
      if (const auto value = values.get("friction")) {
        branch.friction = reader.number(*value, [](double v) { return v >= 0.0; });
      }
    }

    const Field stages = map.require("stages");
    LoadValues load_values = load_values_after.at(static_cast<std::size_t>(branch.from));
    NameTable own_stage_names;
    branch.stages =
        read_stages(reader, Field{stages.node, stages.path, "stages", stages.line}, condition_names,
                    conditions, beam_names, contact, moment_axes, load_values, own_stage_names);
    branches.push_back(std::move(branch));
  }
  return branches;
}

}  // namespace nodus::scenario
