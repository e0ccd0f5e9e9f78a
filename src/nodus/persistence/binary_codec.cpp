#include "nodus/persistence/binary_codec.hpp"

#include "nodus/persistence/checkpoint_files.hpp"

#include <fmt/format.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::persistence {

void bad_file(const std::filesystem::path& path, std::string_view expected, std::string_view got) {
  throw scenario::ScenarioError(
      fmt::format("{}: checkpoint: expected {}, got {}", path.string(), expected, got));
}

void damaged_file(const std::filesystem::path& path, std::string_view expected, std::string_view got) {
  throw DamagedFile(fmt::format("{}: checkpoint: expected {}, got {}", path.string(), expected, got));
}

}  // namespace nodus::persistence
