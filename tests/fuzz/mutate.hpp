#pragma once
/// Seeded mutations of a scenario's YAML text, as a user's typing mistakes make them: a value replaced (by
/// 0, a negative, NaN, an infinity, 1e308, a huge integer, a string, an empty list, another value of the
/// file, the value scaled by 1e6 or 1e-6), a line deleted, duplicated or swapped with the next, two values
/// swapped, a key replaced by another key of the file, the text cut short. Comments are left alone.

#include <cstdint>
#include <random>
#include <string>

namespace nodus::fuzz {

struct Mutant {
  std::string text;
  std::string what;  ///< "LINE: KIND 'OLD' -> 'NEW'", for the report
};

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}
  /// One mutation of `text`; the same seed gives the same sequence of mutants.
  Mutant mutate(const std::string& text);

 private:
  std::mt19937_64 rng_;
};

}  // namespace nodus::fuzz
