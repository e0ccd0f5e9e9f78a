#pragma once
/// The table of every key of a scenario file: name, type, unit, default, admissible range and a one-line
/// help, gathered in file order from the declarations next to the struct fields (key.hpp, scenario.hpp). It
/// drives the reader's "expected ..." messages, `nodus keys` and the key table of docs/scenario.md (rendered
/// by scenario_keys_markdown()).

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace nodus::scenario {

/// One key of the scenario file, as the table shows it.
struct KeyDoc {
  /// Key pattern: list items are written "[]", free map keys "<condition>",
  /// e.g. "beams[].radius" or "stages[].motions.<condition>.rotation".
  std::string_view path;
  /// number | integer | string | bool | vector (exactly 3 numbers) | list | map | choice
  std::string_view type;
  std::string_view unit;  ///< "mm", "N", "N mm", "MPa", "s", "deg" or empty
  /// The default, "required", or "-" (optional, no default); a scalar key's default is its field's value in
  /// the default-constructed struct.
  std::string default_value;
  /// Admissible values, phrased to follow the type in a message: "> 0" gives "a number > 0 (mm)";
  /// for a choice the alternatives separated by " | ".
  std::string_view range;
  std::string_view help;  ///< one line
};

/// All keys, in file order (parents before their children).
std::span<const KeyDoc> scenario_keys();

/// The entry with this exact pattern; throws std::logic_error if there is none (a programming error).
const KeyDoc& scenario_key(std::string_view path);

/// The pattern of the map that holds this key: "beams[]" for "beams[].radius", "" for top-level keys.
std::string_view parent_pattern(std::string_view path);

/// The last component of a pattern: "radius" for "beams[].radius".
std::string_view leaf_name(std::string_view path);

/// What a message says is expected for this key, e.g. "a number > 0 (mm)".
std::string expected_text(const KeyDoc& key);

}  // namespace nodus::scenario
