#pragma once
/// Generic code over the key declarations (key.hpp): reading a declared scalar key into its field, checking
/// its value (the one check shared by the reader and validate()), and printing it for the key table, the
/// echo and the fingerprint. Internal to the scenario module.

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "nodus/scenario/key.hpp"
#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

/// A number as the key table shows a default: shortest round trip, exponent without padding ("1e-8").
std::string table_number(double value);

/// Whether `value` satisfies the range of the number or integer `key` (the predicate of its declaration).
template <class Owner>
bool in_range(const Key<Owner>& key, double value) {
  return key.ok == nullptr || key.ok(value);
}

/// Whether `value` is admissible for the number or integer `key` in a Scenario: finite, representable() and
/// in range; for an auto key, 0 (auto) too. The one check of a value that the reader and validate() share
/// (the reader reads the word auto as 0, and an explicit number must be in range).
template <class Owner>
bool admissible(const Key<Owner>& key, double value) {
  if (!std::isfinite(value) || !representable(value)) return false;
  if (key.zero_is_auto && value == 0.0) return true;
  return in_range(key, value);
}

/// The value of scalar `key` in `owner`, as the echo prints it ("auto" for an auto key at 0); with
/// `exact`, numbers in full precision (%.17g), for the fingerprint.
template <class Owner>
std::string value_text(const Key<Owner>& key, const Owner& owner, bool exact = false) {
  if (key.number) {
    const double value = owner.*key.number;
    if (key.zero_is_auto && value == 0.0 && !exact) return "auto";
    return exact ? fmt::format("{:.17g}", value) : format_number(value);
  }
  if (key.integer) return std::to_string(owner.*key.integer);
  if (key.boolean) return owner.*key.boolean ? "true" : "false";
  if (key.get_choice) {
    const auto alternatives = split_choices(key.range);
    const int index = key.get_choice(owner);
    if (index < 0 || index >= static_cast<int>(alternatives.size())) return fmt::format("#{}", index);
    return std::string(alternatives[static_cast<std::size_t>(index)]);
  }
  return {};
}

/// The default of `key` as the key table shows it: its declared text, else its value in `defaults`.
template <class Owner>
std::string default_text(const Key<Owner>& key, const Owner& defaults) {
  if (!key.default_text.empty()) return std::string(key.default_text);
  if (key.number) return table_number(defaults.*key.number);
  return value_text(key, defaults);
}

/// If the value of scalar `key` in `owner` is not admissible, what a message shows as "got ..."; else none.
template <class Owner>
std::optional<std::string> inadmissible(const Key<Owner>& key, const Owner& owner) {
  if (key.number) {
    const double value = owner.*key.number;
    if (!admissible(key, value)) return format_number(value);
  } else if (key.integer) {
    const int value = owner.*key.integer;
    if (!admissible(key, static_cast<double>(value))) return std::to_string(value);
  } else if (key.get_choice) {
    const int index = key.get_choice(owner);
    if (index < 0 || index >= static_cast<int>(split_choices(key.range).size()))
      return value_text(key, owner);
  }
  return std::nullopt;
}

/// Reads the value of scalar `key` at `field` into `owner`, or fails with the key's expectation.
template <class Owner>
void read_key(const Reader& reader, const Field& field, const Key<Owner>& key, Owner& owner) {
  if (key.number) {
    if (key.zero_is_auto && is_plain_scalar(field.node) && field.node.Scalar() == "auto") {
      owner.*key.number = 0.0;
      return;
    }
    // An explicit value of an auto key must satisfy the range: 0 is written auto.
    owner.*key.number = reader.number(field, [&key](double v) { return in_range(key, v); });
  } else if (key.integer) {
    owner.*key.integer = reader.integer(field, [&key](int v) { return admissible(key, v); });
  } else if (key.boolean) {
    owner.*key.boolean = reader.boolean(field);
  } else if (key.set_choice) {
    const std::string word = reader.choice(field);
    const auto alternatives = split_choices(key.range);
    for (std::size_t i = 0; i < alternatives.size(); ++i) {
      if (alternatives[i] == word) key.set_choice(owner, static_cast<int>(i));
    }
  }
}

/// The declaration of `path` among `keys`; a programming error if missing.
template <class Owner>
const Key<Owner>& declared(std::span<const Key<Owner>> keys, std::string_view path) {
  for (const Key<Owner>& key : keys) {
    if (key.path == path) return key;
  }
  throw std::logic_error("nodus::scenario: key '" + std::string(path) + "' is not declared");
}

/// Reads every declared scalar key of `keys` that `map` holds into `owner` (a required one must be there),
/// in declaration order; keys absent keep the value `owner` has.
template <class Owner>
void read_keys(const Reader& reader, const MapView& map, std::span<const Key<Owner>> keys, Owner& owner) {
  for (const Key<Owner>& key : keys) {
    if (!key.scalar()) continue;
    const std::string_view leaf = leaf_name(key.path);
    if (key.required()) {
      read_key(reader, map.require(leaf), key, owner);
    } else if (const auto field = map.get(leaf)) {
      read_key(reader, *field, key, owner);
    }
  }
}

}  // namespace nodus::scenario
