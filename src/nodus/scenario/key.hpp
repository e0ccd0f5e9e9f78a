#pragma once
/// The declaration of a key of the scenario file, made once next to the struct field it fills (the idea of
/// deal.II's ParameterHandler: the struct that reads parameters declares them). Each settings struct of
/// scenario.hpp has a static keys() listing its keys in file order. From these declarations come the reader
/// (scalar keys are read into their fields by generic code), validate(), the key table of `nodus keys` and
/// docs/scenario.md (keys.hpp), the resolved-settings echo and the checkpoint fingerprint.
///
/// A scalar key (number, integer, bool, choice) points at its field; its default is the field's value in a
/// default-constructed struct, so the table cannot drift from the code. A structural key (a list, a map, a
/// name that refers to another item, a vector) carries its documentation only; its own reader fills it.

#include <string_view>

namespace nodus::scenario {

/// What a key's value is in the file.
enum class KeyType { number, integer, boolean, choice, string, vector, list, map };

/// The word the key table uses for a type: number, integer, bool, choice, string, vector, list, map.
std::string_view key_type_name(KeyType type);

/// Predicates of the admissible values of number and integer keys (an integer is passed as a double).
namespace ranges {
inline bool positive(double v) {
  return v > 0.0;
}
inline bool non_negative(double v) {
  return v >= 0.0;
}
inline bool at_least_one(double v) {
  return v >= 1.0;
}
inline bool at_least_three(double v) {
  return v >= 3.0;
}
inline bool below_one_half(double v) {  // [0, 0.5)
  return v >= 0.0 && v < 0.5;
}
inline bool one_to_five(double v) {
  return v >= 1.0 && v <= 5.0;
}
inline bool fraction(double v) {  // (0, 1]
  return v > 0.0 && v <= 1.0;
}
inline bool proper_fraction(double v) {  // (0, 1)
  return v > 0.0 && v < 1.0;
}
}  // namespace ranges

/// One key of the file, filling (if scalar) a field of `Owner`.
template <class Owner>
struct Key {
  /// Key pattern: list items are written "[]", free map keys "<condition>", e.g. "beams[].radius".
  std::string_view path;
  KeyType type = KeyType::map;
  std::string_view unit;  ///< "mm", "N", "N mm", "MPa", "s", "deg", "rad" or empty
  /// Admissible values in words, phrased to follow the type in a message ("> 0" gives "a number > 0 (mm)");
  /// for a choice the alternatives separated by " | " (the field holds the index of one).
  std::string_view range;
  bool (*ok)(double) = nullptr;  ///< number, integer: the predicate of `range`; null: any finite value
  std::string_view help;         ///< one line
  double Owner::*number = nullptr;
  int Owner::*integer = nullptr;
  bool Owner::*boolean = nullptr;
  int (*get_choice)(const Owner&) = nullptr;  ///< choice: the index of the alternative the field holds
  void (*set_choice)(Owner&, int) = nullptr;
  /// The default as the table shows it where it is not the field's default value: "required", "auto",
  /// "true" (contact.enabled, when the section is present), or the default of a structural key.
  std::string_view default_text;
  bool zero_is_auto = false;  ///< number: the word auto reads as 0, and 0 means auto

  /// Whether generic code reads, checks and prints this key through its field.
  bool scalar() const { return number || integer || boolean || set_choice; }
  bool required() const { return default_text == "required"; }

  /// A structural key: documentation only.
  static constexpr Key doc(std::string_view path, KeyType type, std::string_view unit,
                           std::string_view default_text, std::string_view range, std::string_view help) {
    Key key;
    key.path = path;
    key.type = type;
    key.unit = unit;
    key.range = range;
    key.help = help;
    key.default_text = default_text;
    return key;
  }
  static constexpr Key real(std::string_view path, double Owner::*field, std::string_view unit,
                            std::string_view range, bool (*ok)(double), std::string_view help) {
    Key key = doc(path, KeyType::number, unit, {}, range, help);
    key.ok = ok;
    key.number = field;
    return key;
  }
  static constexpr Key whole(std::string_view path, int Owner::*field, std::string_view range,
                             bool (*ok)(double), std::string_view help) {
    Key key = doc(path, KeyType::integer, {}, {}, range, help);
    key.ok = ok;
    key.integer = field;
    return key;
  }
  static constexpr Key flag(std::string_view path, bool Owner::*field, std::string_view help) {
    Key key = doc(path, KeyType::boolean, {}, {}, {}, help);
    key.boolean = field;
    return key;
  }
  static constexpr Key choice(std::string_view path, std::string_view alternatives, int (*get)(const Owner&),
                              void (*set)(Owner&, int), std::string_view help) {
    Key key = doc(path, KeyType::choice, {}, {}, alternatives, help);
    key.get_choice = get;
    key.set_choice = set;
    return key;
  }

  /// The same key with the default shown as `text`.
  constexpr Key shown_default(std::string_view text) const {
    Key key = *this;
    key.default_text = text;
    return key;
  }
  constexpr Key or_auto() const {
    Key key = shown_default("auto");
    key.zero_is_auto = true;
    return key;
  }
};

}  // namespace nodus::scenario
