#include "nodus/scenario/fingerprint.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "nodus/scenario/describe.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

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
