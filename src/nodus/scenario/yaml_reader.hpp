#pragma once
/// The typed reading of YAML values with one-line errors: a value's key path and line (Field), the reader
/// that turns values into numbers, integers, booleans, names, choices and vectors or throws
/// "FILE:LINE: KEY: expected WHAT, got VALUE" (Reader), a map's keys checked against the key table (MapView)
/// and the names of items for uniqueness and references (NameTable). Internal to the scenario module.

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

/// Names shown in a "the name of a ... (a | b | ...)" message before it is cut short.
constexpr std::size_t kMaxNamesShown = 12;

/// Every number of a scenario is 0 or of a magnitude in [1e-20, 1e20], so that the products the model forms
/// of a few of them (a radius to the fourth power, a spacing squared, a length over a radius) stay normal
/// doubles: a value beyond (1e308 for a clearance) would build nothing, or hang a yarn's layout.
bool representable(double value);
/// What a message expects of a number beyond that range, after the key's own expectation.
constexpr std::string_view kMagnitudeExpected = "every number 0 or of magnitude 1e-20 to 1e20";

/// A number as the echo and the messages print it (shortest round trip, no "-0").
std::string format_number(double value);
/// "[x, y, z]" with format_number.
std::string format_vec(const Vec3& v);
/// Makes a value printable on one line: escapes line breaks, cuts long text.
std::string one_line(std::string text);
bool is_plain_scalar(const YAML::Node& node);
/// What a message shows as "got ...".
std::string render(const YAML::Node& node);
int line_of(const YAML::Node& node, int fallback);
std::optional<double> parse_number(const YAML::Node& node);
std::optional<long long> parse_integer(const YAML::Node& node);
/// "a | b | c", cut short after kMaxNamesShown names.
std::string name_list(const std::vector<std::string>& names);
std::vector<std::string_view> split_choices(std::string_view range);

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
  /// Fails with the expectation of the key table and the range of every number (representable()).
  [[noreturn]] void fail_magnitude(const Field& field) const {
    fail(field, fmt::format("{}; {}", expected_text(scenario_key(field.pattern)), kMagnitudeExpected));
  }

  template <class Ok>
  double number(const Field& field, Ok ok) const {
    const auto value = parse_number(field.node);
    if (value && !representable(*value)) fail_magnitude(field);
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
      if (!value || !representable(*value)) {
        fail(line_of(field.node[i], field.line), fmt::format("{}[{}]", field.path, i),
             value ? fmt::format("{}; {}", expected_text(scenario_key(field.pattern)), kMagnitudeExpected)
                   : expected_text(scenario_key(field.pattern)),
             render(field.node[i]));
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
  MapView(const Reader& reader, Field field, bool free_keys = false);

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

}  // namespace nodus::scenario
