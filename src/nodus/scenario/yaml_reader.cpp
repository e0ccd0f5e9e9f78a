#include "nodus/scenario/yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace nodus::scenario {

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

bool representable(double value) {
  const double magnitude = std::abs(value);
  return magnitude == 0.0 || (magnitude >= 1e-20 && magnitude <= 1e20);
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

MapView::MapView(const Reader& reader, Field field, bool free_keys)
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

}  // namespace nodus::scenario
