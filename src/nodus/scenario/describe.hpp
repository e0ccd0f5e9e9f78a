#pragma once
/// The resolved-settings echo of a scenario (MFEM style): every setting, defaults included, as YAML-like text
/// that reads back as the same scenario.

#include <string>

namespace nodus::scenario {

struct Scenario;

/// The resolved settings, as YAML-like text, for echoing at start.
std::string describe(const Scenario& scenario);

}  // namespace nodus::scenario
