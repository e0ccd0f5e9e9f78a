#include "nodus/scenario/keys.hpp"

#include <cctype>
#include <stdexcept>
#include <string>

#include "nodus/scenario/declared_keys.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

namespace {

/// The rows of `keys`, each followed (depth first) by the keys of the item or map it holds.
template <class Owner>
void append(std::vector<KeyDoc>& out, std::span<const Key<Owner>> keys);

/// The keys inside the list or map `path`: those of the struct its items fill.
void append_children(std::vector<KeyDoc>& out, std::string_view path) {
  if (path == "materials") append(out, Material::keys());
  if (path == "beams") append(out, BeamSpec::keys());
  if (path == "bodies") append(out, BodySpec::keys());
  if (path == "yarns") append(out, YarnSpec::keys());
  if (path == "conditions") append(out, ConditionSpec::keys());
  if (path == "stages") append(out, StageSpec::keys());
  if (path == "stages[].motions") append(out, MotionTarget::keys());
  if (path == "stages[].motions.<condition>.keyframes") append(out, Keyframe::keys());
  if (path == "stages[].loads") append(out, LoadTarget::keys());
  if (path == "solver") append(out, SolverSettings::keys());
  if (path == "output") append(out, OutputSettings::keys());
  if (path == "contact") append(out, ContactSettings::keys());
  if (path == "branches") append(out, BranchSpec::keys());
}

template <class Owner>
void append(std::vector<KeyDoc>& out, std::span<const Key<Owner>> keys) {
  const Owner defaults{};
  for (const Key<Owner>& key : keys) {
    out.push_back(
        {key.path, key_type_name(key.type), key.unit, default_text(key, defaults), key.range, key.help});
    append_children(out, key.path);
  }
}

const std::vector<KeyDoc>& all_keys() {
  static const std::vector<KeyDoc> keys = [] {
    std::vector<KeyDoc> out;
    append(out, Scenario::keys());
    return out;
  }();
  return keys;
}

std::string type_phrase(std::string_view type) {
  if (type == "number") return "a number";
  if (type == "integer") return "an integer";
  if (type == "string") return "a string";
  if (type == "bool") return "true or false";
  if (type == "vector") return "a list of 3 numbers";
  if (type == "list") return "a list";
  if (type == "map") return "a map";
  return std::string(type);
}

/// Markdown table cell: "|" must be escaped.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string table_number(double value) {
  std::string text = format_number(value);
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  std::string sign;
  if (exponent.front() == '-' || exponent.front() == '+') {
    if (exponent.front() == '-') sign = "-";
    exponent.erase(0, 1);
  }
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e + 1) + sign + exponent;
}

std::string_view key_type_name(KeyType type) {
  switch (type) {
    case KeyType::number:
      return "number";
    case KeyType::integer:
      return "integer";
    case KeyType::boolean:
      return "bool";
    case KeyType::choice:
      return "choice";
    case KeyType::string:
      return "string";
    case KeyType::vector:
      return "vector";
    case KeyType::list:
      return "list";
    case KeyType::map:
      return "map";
  }
  return "?";
}

std::span<const KeyDoc> scenario_keys() {
  return all_keys();
}

const KeyDoc& scenario_key(std::string_view path) {
  for (const KeyDoc& key : all_keys()) {
    if (key.path == path) return key;
  }
  throw std::logic_error("nodus::scenario: key '" + std::string(path) + "' is missing from the key table");
}

std::string_view parent_pattern(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? std::string_view{} : path.substr(0, dot);
}

std::string_view leaf_name(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

std::string expected_text(const KeyDoc& key) {
  std::string text;
  if (key.type == "choice") {
    text = key.range.find('|') == std::string_view::npos ? "exactly " : "one of ";
    text += key.range;
  } else {
    text = type_phrase(key.type);
    if (!key.range.empty()) {
      // Comparisons, intervals and "of ..." read as a continuation, anything else after a comma.
      const char first = key.range.front();
      const bool continues = first == '<' || first == '>' || first == '=' || first == '[' || first == '(' ||
                             std::isdigit(static_cast<unsigned char>(first)) ||
                             key.range.starts_with("in ") || key.range.starts_with("of ") ||
                             key.range.starts_with("with ") || key.range.starts_with("from ") ||
                             key.range.starts_with("naming ") || key.range.starts_with("not ") ||
                             key.range.starts_with("unique ") || key.range.starts_with("parallel ");
      text += continues ? " " : ", ";
      text += key.range;
    }
  }
  if (!key.unit.empty()) {
    text += " (";
    text += key.unit;
    text += ")";
  }
  return text;
}

std::string scenario_keys_markdown() {
  std::string out =
      "| Key | Type | Unit | Default | Range | Description |\n"
      "|-----|------|------|---------|-------|-------------|\n";
  for (const KeyDoc& key : all_keys()) {
    out += "| `";
    out += key.path;
    out += "` | ";
    out += key.type;
    out += " | ";
    out += cell(key.unit.empty() ? "-" : key.unit);
    out += " | ";
    out += cell(key.default_value);
    out += " | ";
    out += cell(key.range.empty() ? "-" : key.range);
    out += " | ";
    out += cell(key.help);
    out += " |\n";
  }
  return out;
}

}  // namespace nodus::scenario
