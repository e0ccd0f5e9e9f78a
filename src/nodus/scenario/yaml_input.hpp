#pragma once
/// The text of a scenario file before it becomes a YAML tree: its size, its encoding and its shape are
/// checked first, so that bad or oversized input is refused in bounded memory and time. yaml-cpp builds a
/// node tree of several hundred bytes per value (a 50 MB list of numbers took 8 GB and close to a minute),
/// and it passes bytes that are not UTF-8 through unchecked and reads only the first of several documents.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace nodus::scenario {

/// Largest scenario file read [bytes]: 16 MiB. The paper's largest case is a few kB of YAML and a generated
/// scenario of thousands of fibres a few MB; a larger file is a mistake (a wrong path, a data file).
inline constexpr std::uintmax_t kMaxScenarioBytes = std::uintmax_t{16} << 20;

/// Most YAML nodes (scalars, nulls, lists, maps, aliases) in a scenario: 1,000,000, some 30,000 beams with
/// their conditions. Bounds the memory of yaml-cpp's tree (a few hundred MB at the limit).
inline constexpr std::size_t kMaxScenarioNodes = 1'000'000;

/// Where a text is not what a scenario file may hold.
struct TextFault {
  std::size_t offset = 0;  ///< of the first offending byte, from 0
  std::string what;        ///< e.g. "the byte 0xff, which is not UTF-8"
};

/// The first byte of `text` that is not well-formed UTF-8 (Unicode 15, Table 3-7: no overlong forms, no
/// surrogates U+D800..U+DFFF, nothing above U+10FFFF, no sequence cut short), or that is a control character
/// YAML does not allow in a stream (U+0000..U+001F other than tab, line feed and carriage return, and U+007F;
/// YAML 1.2, 5.1); none if the whole text is fine.
std::optional<TextFault> find_invalid_text(std::string_view text);

/// Line (from 1) of the byte at `offset` of `text`.
int line_at(std::string_view text, std::size_t offset);

/// Checks the text of a scenario file before it is parsed into a tree: UTF-8 without control characters
/// (find_invalid_text), one YAML document only, at most `max_nodes` nodes. Reads it as a stream of events
/// (no tree), stopping at the first problem. Throws ScenarioError "PATH:LINE: KEY: expected ..., got ...";
/// YAML syntax errors give "PATH:LINE: yaml: expected valid YAML, got ...".
void check_yaml_input(const std::string& text, const std::string& path,
                      std::size_t max_nodes = kMaxScenarioNodes);

/// The whole content of the scenario file at `path`, at most `max_bytes` bytes: a larger file is refused
/// from its size before it is read (and a special file that grows past the limit while read, once the limit
/// is reached). Throws ScenarioError "PATH:0: file: expected ..., got ...".
std::string read_scenario_text(const std::string& path, std::uintmax_t max_bytes = kMaxScenarioBytes);

}  // namespace nodus::scenario
