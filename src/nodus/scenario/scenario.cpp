#include "nodus/scenario/scenario.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/yaml_input.hpp"

namespace nodus::scenario {

namespace {

/// director1 may not be within this |sin angle| of direction.
constexpr double kDirectorParallelTolerance = 1e-6;
/// Nonzero moments of one load must be parallel within this |sin angle|.
constexpr double kMomentAxisTolerance = 1e-9;
/// Upper limit of beams[].elements, so that node indices 2 * elements fit an int with room to spare.
constexpr int kMaxElements = 100'000'000;
/// Names shown in a "the name of a ... (a | b | ...)" message before it is cut short.
constexpr std::size_t kMaxNamesShown = 12;

constexpr std::string_view kDofNames[] = {"x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"};

std::string format_number(double value) {
  return fmt::format("{}", value + 0.0);
}  // + 0.0: no "-0"

std::string format_vec(const Vec3& v) {
  return fmt::format("[{}, {}, {}]", format_number(v.x()), format_number(v.y()), format_number(v.z()));
}

/// Makes a value printable on one line: escapes line breaks, cuts long text.
std::string one_line(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      out += c;
    }
  }
  if (out.size() > 80) out = out.substr(0, 77) + "...";
  return out;
}

bool is_plain_scalar(const YAML::Node& node) {
  return node.IsScalar() && node.Tag() == "?";
}

/// What a message shows as "got ...".
std::string render(const YAML::Node& node) {
  if (!node.IsDefined()) return "nothing";
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "nothing (null)";
    case YAML::NodeType::Scalar:
      if (!is_plain_scalar(node) || node.Scalar().empty()) return one_line("\"" + node.Scalar() + "\"");
      return one_line(node.Scalar());
    case YAML::NodeType::Sequence: {
      const bool short_scalars =
          node.size() <= 6 && std::all_of(node.begin(), node.end(), [](const YAML::Node& item) {
            return item.IsScalar() && item.Scalar().size() <= 20;
          });
      if (!short_scalars) return fmt::format("a list of {} items", node.size());
      std::string out = "[";
      for (std::size_t i = 0; i < node.size(); ++i) out += (i > 0 ? ", " : "") + render(node[i]);
      return one_line(out + "]");
    }
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

int line_of(const YAML::Node& node, int fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : fallback;
}

std::optional<double> parse_number(const YAML::Node& node) {
  if (!is_plain_scalar(node)) return std::nullopt;
  std::string_view text = node.Scalar();
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string_view::npos)
    return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(const YAML::Node& node) {
  if (!is_plain_scalar(node)) return std::nullopt;
  std::string_view text = node.Scalar();
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.find_first_not_of("0123456789-") != std::string_view::npos) return std::nullopt;
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

/// "a | b | c", cut short after kMaxNamesShown names.
std::string name_list(const std::vector<std::string>& names) {
  if (names.empty()) return "none defined";
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < kMaxNamesShown; ++i) out += (i > 0 ? " | " : "") + names[i];
  if (names.size() > kMaxNamesShown) out += " | ...";
  return out;
}

std::vector<std::string_view> split_choices(std::string_view range) {
  std::vector<std::string_view> out;
  while (true) {
    const auto bar = range.find(" | ");
    out.push_back(range.substr(0, bar));
    if (bar == std::string_view::npos) return out;
    range.remove_prefix(bar + 3);
  }
}

std::string_view type_name(ConditionType type) {
  switch (type) {
    case ConditionType::clamp:
      return "clamp";
    case ConditionType::motion:
      return "motion";
    case ConditionType::rigid:
      return "rigid";
    case ConditionType::load:
      return "load";
  }
  return "?";
}

/// A value in the file: the node, its full key path, its pattern in the key table and its line.
struct Field {
  YAML::Node node;
  std::string path;
  std::string pattern;
  int line = 0;
};

/// Throws the one-line messages "FILE:LINE: KEY: expected WHAT, got VALUE" and reads typed values.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(int line, std::string_view key, std::string_view expected,
                         std::string_view got) const {
    throw ScenarioError(fmt::format("{}:{}: {}: expected {}, got {}", file_, line, key, expected, got));
  }
  [[noreturn]] void fail(const Field& field, std::string_view expected) const {
    fail(field.line, field.path, expected, render(field.node));
  }
  /// Fails with the expectation of the key table.
  [[noreturn]] void fail(const Field& field) const {
    fail(field, expected_text(scenario_key(field.pattern)));
  }

  template <class Ok>
  double number(const Field& field, Ok ok) const {
    const auto value = parse_number(field.node);
    if (!value || !ok(*value)) fail(field);
    return *value;
  }
  double number(const Field& field) const {
    return number(field, [](double) { return true; });
  }

  template <class Ok>
  int integer(const Field& field, Ok ok) const {
    const auto value = parse_integer(field.node);
    if (!value || *value < std::numeric_limits<int>::min() || *value > std::numeric_limits<int>::max() ||
        !ok(static_cast<int>(*value))) {
      fail(field);
    }
    return static_cast<int>(*value);
  }

  bool boolean(const Field& field) const {
    if (is_plain_scalar(field.node)) {
      const std::string& text = field.node.Scalar();
      if (text == "true" || text == "True" || text == "TRUE") return true;
      if (text == "false" || text == "False" || text == "FALSE") return false;
    }
    fail(field);
  }

  /// A non-empty scalar.
  std::string name(const Field& field) const {
    if (!field.node.IsScalar() || field.node.Scalar().empty()) fail(field);
    return field.node.Scalar();
  }

  /// One of the alternatives of the key's range.
  std::string choice(const Field& field) const {
    if (is_plain_scalar(field.node)) {
      for (std::string_view option : split_choices(scenario_key(field.pattern).range)) {
        if (field.node.Scalar() == option) return std::string(option);
      }
    }
    fail(field);
  }

  /// A list of exactly three numbers.
  Vec3 vec(const Field& field) const {
    if (!field.node.IsSequence() || field.node.size() != 3) fail(field);
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
      const auto value = parse_number(field.node[i]);
      if (!value) {
        fail(line_of(field.node[i], field.line), fmt::format("{}[{}]", field.path, i),
             expected_text(scenario_key(field.pattern)), render(field.node[i]));
      }
      out[i] = *value;
    }
    return out;
  }

  /// The items of a list; an optional list may be given as null (empty).
  std::vector<Field> list(const Field& field, bool non_empty) const {
    std::vector<Field> items;
    if (field.node.IsNull() && !non_empty) return items;
    if (!field.node.IsSequence() || (non_empty && field.node.size() == 0)) fail(field);
    for (std::size_t i = 0; i < field.node.size(); ++i) {
      const YAML::Node item = field.node[i];
      items.push_back(
          {item, fmt::format("{}[{}]", field.path, i), field.pattern + "[]", line_of(item, field.line)});
    }
    return items;
  }

 private:
  std::string file_;
};

/// A map of the file: checks for duplicate keys and, unless its keys are free names, for unknown keys.
class MapView {
 public:
  struct Entry {
    std::string key;
    YAML::Node value;
    int line = 0;  ///< line of the key
  };

  /// `free_keys`: the keys are user names (e.g. condition names), their values have pattern
  /// field.pattern + ".<condition>".
  MapView(const Reader& reader, Field field, bool free_keys = false)
      : reader_(reader), field_(std::move(field)), free_keys_(free_keys) {
    std::vector<std::string_view> allowed;
    if (!free_keys_) {
      for (const KeyDoc& key : scenario_keys()) {
        if (parent_pattern(key.path) == field_.pattern) allowed.push_back(leaf_name(key.path));
      }
    }
    const std::string allowed_text = [&] {
      std::string out;
      for (std::size_t i = 0; i < allowed.size(); ++i) out += (i > 0 ? " | " : "") + std::string(allowed[i]);
      return out;
    }();

    const KeyDoc* doc = find_doc(field_.pattern);
    if (field_.node.IsNull() && doc != nullptr && doc->default_value != "required") return;  // empty map
    if (!field_.node.IsMap()) {
      if (doc != nullptr) reader_.fail(field_);
      reader_.fail(field_, "a map with the keys " + allowed_text);
    }
    std::map<std::string, int> seen;
    for (auto it = field_.node.begin(); it != field_.node.end(); ++it) {
      const YAML::Node key = it->first;
      const int line = line_of(key, field_.line);
      if (!key.IsScalar() || key.Scalar().empty()) {
        reader_.fail(line, field_.path.empty() ? "top level" : field_.path, "a key name", render(key));
      }
      const std::string& name = key.Scalar();
      const std::string path = child_path(name);
      if (const auto previous = seen.find(name); previous != seen.end()) {
        reader_.fail(line, path, fmt::format("each key once (first given at line {})", previous->second),
                     "a repeated key");
      }
      if (!free_keys_ && std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        reader_.fail(line, path, "one of the keys " + allowed_text, "an unknown key");
      }
      seen.emplace(name, line);
      entries_.push_back({name, it->second, line});
    }
  }

  int line() const { return field_.line; }
  const Field& field() const { return field_; }
  const std::vector<Entry>& entries() const { return entries_; }

  Field field_of(const Entry& entry) const {
    return {entry.value, child_path(entry.key), child_pattern(entry.key), entry.line};
  }

  std::optional<Field> get(std::string_view key) const {
    for (const Entry& entry : entries_) {
      if (entry.key == key) return field_of(entry);
    }
    return std::nullopt;
  }

  /// The value of a required key; a missing key is reported at the line of the map.
  Field require(std::string_view key) const {
    if (auto found = get(key)) return *found;
    const std::string pattern = child_pattern(std::string(key));
    reader_.fail(field_.line, child_path(std::string(key)), expected_text(scenario_key(pattern)),
                 "nothing (missing key)");
  }

 private:
  static const KeyDoc* find_doc(std::string_view pattern) {
    for (const KeyDoc& key : scenario_keys()) {
      if (key.path == pattern) return &key;
    }
    return nullptr;
  }
  std::string child_path(const std::string& key) const {
    return field_.path.empty() ? key : field_.path + "." + key;
  }
  std::string child_pattern(const std::string& key) const {
    if (free_keys_) return field_.pattern + ".<condition>";
    return field_.pattern.empty() ? key : field_.pattern + "." + key;
  }

  const Reader& reader_;
  Field field_;
  bool free_keys_ = false;
  std::vector<Entry> entries_;
};

/// Index of a named item, for uniqueness checks and references.
struct NameTable {
  std::vector<std::string> names;
  std::map<std::string, std::pair<int, int>> index_and_line;

  void add(const Reader& reader, const Field& field, const std::string& name, std::string_view what) {
    if (const auto found = index_and_line.find(name); found != index_and_line.end()) {
      reader.fail(
          field, fmt::format("a name unique among {} (already used at line {})", what, found->second.second));
    }
    index_and_line.emplace(name, std::pair{static_cast<int>(names.size()), field.line});
    names.push_back(name);
  }
  std::optional<int> find(const std::string& name) const {
    const auto found = index_and_line.find(name);
    if (found == index_and_line.end()) return std::nullopt;
    return found->second.first;
  }
};

/// The unit vector orthogonal to `direction` (unit) made from the coordinate axis least parallel to it.
Vec3 default_director(const Vec3& direction) {
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(direction[i]) < std::abs(direction[axis])) axis = i;
  }
  Vec3 director = Vec3::Unit(axis);
  director -= director.dot(direction) * direction;
  return director.normalized();
}

/// |sin| of the angle between two nonzero vectors.
double sin_angle(const Vec3& a, const Vec3& b) {
  return a.cross(b).norm() / (a.norm() * b.norm());
}

void read_units(const Reader& reader, const MapView& top) {
  const auto units = top.get("units");
  if (!units) return;
  const MapView map(reader, *units);
  for (const MapView::Entry& entry : map.entries()) reader.choice(map.field_of(entry));
}

std::vector<Material> read_materials(const Reader& reader, const MapView& top, NameTable& names) {
  std::vector<Material> materials;
  for (const Field& item : reader.list(top.require("materials"), true)) {
    const MapView map(reader, item);
    Material material;
    const Field name = map.require("name");
    material.name = reader.name(name);
    names.add(reader, name, material.name, "materials");
    material.young_modulus = reader.number(map.require("young_modulus"), [](double v) { return v > 0.0; });
    material.poisson_ratio =
        reader.number(map.require("poisson_ratio"), [](double v) { return v >= 0.0 && v < 0.5; });
    materials.push_back(material);
  }
  return materials;
}

std::vector<BeamSpec> read_beams(const Reader& reader, const MapView& top, const NameTable& materials,
                                 NameTable& names) {
  std::vector<BeamSpec> beams;
  for (const Field& item : reader.list(top.require("beams"), true)) {
    const MapView map(reader, item);
    BeamSpec beam;
    const Field name = map.require("name");
    beam.name = reader.name(name);
    names.add(reader, name, beam.name, "beams");

    const Field material = map.require("material");
    const auto material_index = materials.find(reader.name(material));
    if (!material_index) {
      reader.fail(material, fmt::format("the name of a material ({})", name_list(materials.names)));
    }
    beam.material = *material_index;

    beam.radius = reader.number(map.require("radius"), [](double v) { return v > 0.0; });
    beam.length = reader.number(map.require("length"), [](double v) { return v > 0.0; });
    const Field elements = map.require("elements");
    beam.elements = reader.integer(elements, [](int v) { return v >= 1; });
    if (beam.elements > kMaxElements) {
      reader.fail(elements,
                  fmt::format("{}, at most {}", expected_text(scenario_key(elements.pattern)), kMaxElements));
    }
    if (const auto start = map.get("start")) beam.start = reader.vec(*start);

    if (const auto direction = map.get("direction")) {
      const Vec3 value = reader.vec(*direction);
      const double norm = value.stableNorm();
      if (!(norm > 0.0)) reader.fail(*direction);
      beam.direction = value / norm;
    }
    if (const auto director1 = map.get("director1")) {
      Vec3 value = reader.vec(*director1);
      const double norm = value.stableNorm();
      if (!(norm > 0.0) || sin_angle(beam.direction, value / norm) < kDirectorParallelTolerance) {
        reader.fail(*director1);
      }
      value /= norm;
      value -= value.dot(beam.direction) * beam.direction;
      beam.director1 = value.normalized();
    } else {
      beam.director1 = default_director(beam.direction);
    }
    if (const auto factor = map.get("bending_factor")) {
      beam.bending_factor = reader.number(*factor, [](double v) { return v > 0.0; });
    }
    beams.push_back(beam);
  }
  return beams;
}

/// The nine dofs selected by a list of dof items.
DofMask read_dofs(const Reader& reader, const Field& field) {
  DofMask mask{};
  const std::vector<Field> items = reader.list(field, true);
  const std::string expected =
      "one of all | position | directors | x | y | z | g1x | g1y | g1z | g2x | g2y | g2z";
  for (const Field& item : items) {
    const std::string text = is_plain_scalar(item.node) ? item.node.Scalar() : std::string();
    if (text == "all") {
      mask.fill(true);
    } else if (text == "position") {
      mask[kX] = mask[kY] = mask[kZ] = true;
    } else if (text == "directors") {
      for (int dof = kG1x; dof <= kG2z; ++dof) mask[dof] = true;
    } else {
      const auto* found = std::find(std::begin(kDofNames), std::end(kDofNames), text);
      if (found == std::end(kDofNames)) reader.fail(item, expected);
      mask[found - std::begin(kDofNames)] = true;
    }
  }
  return mask;
}

/// Checks that every nonzero moment of each load keeps the axis of the first nonzero one.
class MomentAxes {
 public:
  void check(const Reader& reader, int condition, const Vec3& moment, const Field& field) {
    if (moment.squaredNorm() == 0.0) return;
    const auto found = first_.find(condition);
    if (found == first_.end()) {
      first_.emplace(condition, std::pair{moment, fmt::format("{} (line {})", field.path, field.line)});
      return;
    }
    if (sin_angle(found->second.first, moment) >= kMomentAxisTolerance) {
      reader.fail(field, fmt::format("a moment parallel to {} given at {} (moment axis must stay fixed)",
                                     format_vec(found->second.first), found->second.second));
    }
  }

  /// The direction of the first nonzero moment of `condition` (unit); none if it had none.
  std::optional<Vec3> axis(int condition) const {
    const auto found = first_.find(condition);
    if (found == first_.end()) return std::nullopt;
    return found->second.first.normalized();
  }

 private:
  std::map<int, std::pair<Vec3, std::string>> first_;
};

std::vector<ConditionSpec> read_conditions(const Reader& reader, const MapView& top,
                                           const NameTable& beam_names, const std::vector<BeamSpec>& beams,
                                           NameTable& names, MomentAxes& moment_axes) {
  std::vector<ConditionSpec> conditions;
  const auto list = top.get("conditions");
  if (!list) return conditions;
  for (const Field& item : reader.list(*list, false)) {
    const MapView map(reader, item);
    ConditionSpec condition;
    condition.line = map.line();
    const Field name = map.require("name");
    condition.name = reader.name(name);
    names.add(reader, name, condition.name, "conditions");

    const std::string type = reader.choice(map.require("type"));
    condition.type = type == "clamp"    ? ConditionType::clamp
                     : type == "motion" ? ConditionType::motion
                     : type == "rigid"  ? ConditionType::rigid
                                        : ConditionType::load;

    const Field beam = map.require("beam");
    const auto beam_index = beam_names.find(reader.name(beam));
    if (!beam_index) reader.fail(beam, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
    condition.beam = *beam_index;

    const auto pivot = map.get("pivot");
    if (pivot) {
      if (condition.type != ConditionType::motion && condition.type != ConditionType::rigid)
        reader.fail(*pivot,
                    fmt::format("no pivot on a {} condition (pivot is for motion and rigid conditions)",
                                type_name(condition.type)));
      condition.pivot = reader.vec(*pivot);
    }
    if (condition.type == ConditionType::rigid) {  // the whole beam, all dofs
      for (const char* key : {"at", "dofs", "force", "moment"})
        if (const auto value = map.get(key))
          reader.fail(*value,
                      fmt::format("no {} on a rigid condition (it moves every node of its beam)", key));
      condition.dofs.fill(true);
      if (const auto active = map.get("active")) condition.initially_active = reader.boolean(*active);
      conditions.push_back(condition);
      continue;
    }

    const Field at = map.require("at");
    const int last_node = 2 * beams[condition.beam].elements;
    const std::string at_text = is_plain_scalar(at.node) ? at.node.Scalar() : std::string();
    if (at_text == "start") {
      condition.node = 0;
    } else if (at_text == "end") {
      condition.node = last_node;
    } else {
      const auto node = parse_integer(at.node);
      if (!node || *node < 0 || *node > last_node) {
        reader.fail(at, fmt::format("one of start | end | an integer in [0, {}] (beam {}: elements {})",
                                    last_node, beams[condition.beam].name, beams[condition.beam].elements));
      }
      condition.node = static_cast<int>(*node);
    }

    const auto dofs = map.get("dofs");
    if (condition.type == ConditionType::load) {
      if (dofs) reader.fail(*dofs, "no dofs on a load condition (dofs are for clamp and motion conditions)");
    } else {
      condition.dofs =
          dofs ? read_dofs(reader, *dofs) : DofMask{true, true, true, true, true, true, true, true, true};
    }

    if (const auto active = map.get("active")) condition.initially_active = reader.boolean(*active);

    for (const char* key : {"force", "moment"}) {
      const auto value = map.get(key);
      if (!value) continue;
      if (condition.type != ConditionType::load) {
        reader.fail(*value, fmt::format("no {} on a {} condition ({} is for load conditions only)", key,
                                        type_name(condition.type), key));
      }
      if (std::string_view(key) == "force") {
        condition.force = reader.vec(*value);
      } else {
        condition.moment = reader.vec(*value);
        moment_axes.check(reader, static_cast<int>(conditions.size()), condition.moment, *value);
      }
    }
    conditions.push_back(condition);
  }
  return conditions;
}

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

/// The value (force, moment) each load has, by condition.
using LoadValues = std::map<int, std::pair<Vec3, Vec3>>;

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
                                   std::vector<LoadValues>* after_each = nullptr) {
  std::vector<StageSpec> stages;
  for (const Field& item : reader.list(list, true)) {
    const MapView map(reader, item);
    StageSpec stage;
    const Field name = map.require("name");
    stage.name = reader.name(name);
    stage_names.add(reader, name, stage.name, "stages");
    stage.steps = reader.integer(map.require("steps"), [](int v) { return v >= 1; });
    if (const auto duration = map.get("duration")) {
      stage.duration = reader.number(*duration, [](double v) { return v > 0.0; });
    }
    if (const auto value = map.get("stabilization")) {
      stage.stabilization = reader.number(*value, [](double v) { return v >= 0.0; });
    }
    stage.stabilization_end = stage.stabilization;
    if (const auto value = map.get("stabilization_end")) {
      stage.stabilization_end = reader.number(*value, [](double v) { return v >= 0.0; });
      if (stage.stabilization_end > 0.0 && stage.stabilization == 0.0)
        reader.fail(*value, "0 when stabilization is 0 (the decay is geometric from stabilization)");
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

/// Whether a branch name can be a folder name: letters, digits, '_', '.', '-', not starting with '.'.
bool is_folder_name(const std::string& name) {
  return !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == '-';
  });
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

SolverSettings read_solver(const Reader& reader, const MapView& top) {
  SolverSettings solver;
  const auto field = top.get("solver");
  if (!field) return solver;
  const MapView map(reader, *field);
  if (const auto value = map.get("linear_solver")) {
    solver.linear_solver =
        reader.choice(*value) == "umfpack" ? LinearSolverKind::umfpack : LinearSolverKind::cholmod;
  }
  const auto at_least = [](int minimum) { return [minimum](int v) { return v >= minimum; }; };
  const auto positive = [](double v) { return v > 0.0; };
  const auto non_negative = [](double v) { return v >= 0.0; };
  if (const auto value = map.get("max_newton_iterations")) {
    solver.max_newton_iterations = reader.integer(*value, at_least(1));
  }
  if (const auto value = map.get("residual_tolerance"))
    solver.residual_tolerance = reader.number(*value, positive);
  if (const auto value = map.get("increment_tolerance")) {
    solver.increment_tolerance = reader.number(*value, positive);
  }
  if (const auto value = map.get("max_cutbacks")) solver.max_cutbacks = reader.integer(*value, at_least(0));
  if (const auto value = map.get("easy_iterations"))
    solver.easy_iterations = reader.integer(*value, at_least(1));
  if (const auto value = map.get("line_search")) solver.line_search = reader.boolean(*value);
  if (const auto value = map.get("gauss_points")) {
    solver.gauss_points = reader.integer(*value, [](int v) { return v >= 1 && v <= 5; });
  }
  if (const auto value = map.get("fold_stiffness"))
    solver.fold_stiffness = reader.number(*value, non_negative);
  return solver;
}

OutputSettings read_output(const Reader& reader, const MapView& top) {
  OutputSettings output;
  const auto field = top.get("output");
  if (!field) return output;
  const MapView map(reader, *field);
  if (const auto value = map.get("vtk_every"))
    output.vtk_every = reader.integer(*value, [](int v) { return v >= 0; });
  if (const auto value = map.get("tube_sides")) {
    output.tube_sides = reader.integer(*value, [](int v) { return v >= 3; });
  }
  if (const auto value = map.get("progress_seconds")) {
    output.progress_seconds = reader.number(*value, [](double v) { return v >= 0.0; });
  }
  if (const auto value = map.get("contact_csv")) output.contact_csv = reader.boolean(*value);
  if (const auto value = map.get("checkpoint_every"))
    output.checkpoint_every = reader.integer(*value, [](int v) { return v >= 0; });
  return output;
}

ContactSettings read_contact(const Reader& reader, const MapView& top, const NameTable& beam_names) {
  ContactSettings contact;
  const auto field = top.get("contact");
  if (!field) return contact;
  const MapView map(reader, *field);
  contact.enabled = true;
  if (const auto value = map.get("enabled")) contact.enabled = reader.boolean(*value);
  if (const auto value = map.get("self_contact")) contact.self_contact = reader.boolean(*value);
  if (const auto value = map.get("beams")) {
    for (const Field& item : reader.list(*value, true)) {
      const auto index = beam_names.find(item.node.IsScalar() ? item.node.Scalar() : std::string());
      if (!index) reader.fail(item, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
      if (std::find(contact.beams.begin(), contact.beams.end(), *index) != contact.beams.end()) {
        reader.fail(item, "each beam once in contact.beams");
      }
      contact.beams.push_back(*index);
    }
  }

  // A length (or the penalty) is > 0, or auto (absent, or the word auto), which leaves it at 0. Returns the
  // field of an explicit value.
  const auto length = [&](std::string_view key, double& out) -> std::optional<Field> {
    const auto value = map.get(key);
    if (!value || (is_plain_scalar(value->node) && value->node.Scalar() == "auto")) return std::nullopt;
    out = reader.number(*value, [](double v) { return v > 0.0; });
    return value;
  };
  const auto proximity = length("proximity_distance", contact.proximity_distance);
  const auto separation = length("separation_distance", contact.separation_distance);
  const auto spacing = length("test_point_spacing", contact.test_point_spacing);
  const auto matching = length("matching_length", contact.matching_length);
  length("element_spacing", contact.element_spacing);
  if (spacing && matching && contact.matching_length < contact.test_point_spacing) {
    reader.fail(*matching, ">= test_point_spacing (successive matching intervals must overlap)");
  }
  if (proximity && separation && contact.separation_distance <= contact.proximity_distance) {
    reader.fail(*separation, "> proximity_distance (neighbouring parts of a beam would be paired)");
  }

  // Contact mechanics (Sect. 5-6).
  if (const auto value = map.get("forces")) contact.forces = reader.boolean(*value);
  length("penalty", contact.penalty);
  length("max_penetration", contact.max_penetration);
  length("regularization", contact.regularization);
  if (const auto value = map.get("friction")) {
    contact.friction = reader.number(*value, [](double v) { return v >= 0.0; });
  }
  length("max_reversible_slip", contact.max_reversible_slip);
  if (const auto value = map.get("friction_tangent")) {
    contact.friction_tangent =
        reader.choice(*value) == "varying" ? FrictionTangent::varying : FrictionTangent::frozen;
  }
  if (const auto value = map.get("particles")) contact.facing_particles = reader.choice(*value) == "facing";
  const auto at_least_one = [](int v) { return v >= 1; };
  if (const auto value = map.get("max_detections")) {
    contact.max_detections = reader.integer(*value, at_least_one);
  }
  if (const auto value = map.get("max_normal_iterations")) {
    contact.max_normal_iterations = reader.integer(*value, at_least_one);
  }
  if (const auto value = map.get("normal_tolerance")) {
    contact.normal_tolerance = reader.number(*value, [](double v) { return v > 0.0; });
  }
  return contact;
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
  scenario.materials = read_materials(reader, top, material_names);
  scenario.beams = read_beams(reader, top, material_names, beam_names);
  MomentAxes moment_axes;
  scenario.conditions =
      read_conditions(reader, top, beam_names, scenario.beams, condition_names, moment_axes);

  scenario.contact = read_contact(reader, top, beam_names);
  LoadValues load_values = initial_load_values(scenario.conditions);
  std::vector<LoadValues> load_values_after;
  NameTable stage_names;
  scenario.stages =
      read_stages(reader, top.require("stages"), condition_names, scenario.conditions, beam_names,
                  scenario.contact, moment_axes, load_values, stage_names, &load_values_after);
  scenario.solver = read_solver(reader, top);
  // CHOLMOD reads one triangle of the tangent: the varying friction tangent, not symmetric, needs LU. Asked
  // for explicitly rather than switched on behind the user's back, so that the file says which solver runs.
  if (scenario.contact.friction_tangent == FrictionTangent::varying &&
      scenario.solver.linear_solver != LinearSolverKind::umfpack) {
    reader.fail(
        *MapView(reader, *top.get("contact")).get("friction_tangent"),
        "frozen with solver.linear_solver: cholmod (the varying tangent is not symmetric and needs LU: "
        "set solver.linear_solver: umfpack)");
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
  return scenario;
}

// ---- describe ----

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

std::string state_fingerprint_text(const Scenario& scenario, int stages_run) {
  Scenario made = scenario;
  made.path.clear();
  made.output = OutputSettings{};
  made.branches.clear();
  for (ConditionSpec& condition : made.conditions) condition.line = 0;
  if (made.contact.beams.empty()) {  // all beams, as the run resolves it
    for (std::size_t b = 0; b < made.beams.size(); ++b) made.contact.beams.push_back(static_cast<int>(b));
  }
  made.stages.resize(
      static_cast<std::size_t>(std::clamp(stages_run, 0, static_cast<int>(made.stages.size()))));
  std::string suffix;
  if (scenario.origin) {
    // Up to the end of stage `from` the state is the parent's, made with the parent's friction.
    made.contact.friction = scenario.origin->parent_friction;
    if (stages_run > scenario.origin->from + 1) {
      suffix = fmt::format("# branch: from the end of stage {}, contact.friction {}\n", scenario.origin->from,
                           format_number(scenario.contact.friction));
    }
  }
  return describe(made) + suffix;
}

std::uint64_t fingerprint_hash(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace nodus::scenario
