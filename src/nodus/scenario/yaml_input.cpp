#include "nodus/scenario/yaml_input.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

namespace {

[[noreturn]] void fail(const std::string& path, int line, std::string_view key, std::string_view expected,
                       std::string_view got) {
  throw ScenarioError(fmt::format("{}:{}: {}: expected {}, got {}", path, line, key, expected, got));
}

std::string hex_bytes(std::string_view text, std::size_t offset, std::size_t count) {
  std::string out;
  for (std::size_t k = 0; k < count && offset + k < text.size(); ++k)
    out += fmt::format("{}0x{:02x}", k > 0 ? " " : "", static_cast<unsigned char>(text[offset + k]));
  return out;
}

int line_of(const YAML::Mark& mark) {
  return mark.line >= 0 ? mark.line + 1 : 0;
}

/// Raised inside the event handler to stop the parse at the first problem.
struct Stop {
  int line;
  std::string expected, got;
};

/// Counts the nodes of one document as the parser reports them, stopping past `max_nodes`.
class NodeCounter : public YAML::EventHandler {
 public:
  explicit NodeCounter(std::size_t max_nodes) : max_nodes_(max_nodes) {}

  void OnDocumentStart(const YAML::Mark& mark) override { start_ = mark; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    count(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnMapEnd() override {}

  const YAML::Mark& start() const { return start_; }

 private:
  void count(const YAML::Mark& mark) {
    if (++nodes_ > max_nodes_)
      throw Stop{line_of(mark), fmt::format("at most {} YAML values (lists, maps and scalars)", max_nodes_),
                 "more (a scenario is not a data file)"};
  }

  std::size_t max_nodes_;
  std::size_t nodes_ = 0;
  YAML::Mark start_ = YAML::Mark::null_mark();
};

}  // namespace

std::optional<TextFault> find_invalid_text(std::string_view text) {
  const std::size_t n = text.size();
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
        return TextFault{i, fmt::format("the control character 0x{:02x}", c)};
      ++i;
      continue;
    }
    // Well-formed sequences [Unicode 15, Table 3-7]: the lead byte fixes the length and the range of the
    // second byte; further bytes are 0x80..0xbf.
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xbf;
    if (c >= 0xc2 && c <= 0xdf) {
      length = 2;
    } else if (c == 0xe0) {
      length = 3, low = 0xa0;  // no overlong form
    } else if ((c >= 0xe1 && c <= 0xec) || c == 0xee || c == 0xef) {
      length = 3;
    } else if (c == 0xed) {
      length = 3, high = 0x9f;  // no surrogate
    } else if (c == 0xf0) {
      length = 4, low = 0x90;  // no overlong form
    } else if (c >= 0xf1 && c <= 0xf3) {
      length = 4;
    } else if (c == 0xf4) {
      length = 4, high = 0x8f;  // nothing above U+10FFFF
    } else {
      return TextFault{i, fmt::format("the byte 0x{:02x}, which is not UTF-8", c)};
    }
    for (std::size_t k = 1; k < length; ++k) {
      if (i + k >= n)
        return TextFault{i, fmt::format("the bytes {} cut short by the end of the file, which is not UTF-8",
                                        hex_bytes(text, i, k))};
      const unsigned char next = byte(i + k);
      if (next < (k == 1 ? low : 0x80) || next > (k == 1 ? high : 0xbf))
        return TextFault{i, fmt::format("the bytes {}, which are not UTF-8", hex_bytes(text, i, k + 1))};
    }
    i += length;
  }
  return std::nullopt;
}

int line_at(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

void check_yaml_input(const std::string& text, const std::string& path, std::size_t max_nodes) {
  if (const auto fault = find_invalid_text(text))
    fail(path, line_at(text, fault->offset), "text", "UTF-8 text without control characters", fault->what);
  std::istringstream stream(text);
  try {
    YAML::Parser parser(stream);
    NodeCounter first(max_nodes);
    parser.HandleNextDocument(first);
    NodeCounter second(max_nodes);
    if (parser.HandleNextDocument(second)) {
      // The second document's start: its "---" line when it has one.
      const int line = second.start().line >= 0 ? line_of(second.start()) : line_at(text, text.size());
      fail(path, line, "yaml", "one YAML document", "a second one ('---' after the first document)");
    }
  } catch (const Stop& stop) {
    fail(path, stop.line, "yaml", stop.expected, stop.got);
  } catch (const YAML::Exception& error) {
    std::string message = error.msg;
    std::replace(message.begin(), message.end(), '\n', ' ');
    fail(path, line_of(error.mark), "yaml", "valid YAML", message);
  }
}

std::string read_scenario_text(const std::string& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) fail(path, 0, "file", "a readable file", "cannot open: a directory");
  constexpr std::uintmax_t kMiB = 1 << 20;
  const std::string too_big =
      fmt::format("a scenario file of at most {} bytes{}", max_bytes,
                  max_bytes % kMiB == 0 ? fmt::format(" ({} MiB)", max_bytes / kMiB) : std::string());
  if (fs::is_regular_file(path, error)) {
    const std::uintmax_t size = fs::file_size(path, error);
    if (!error && size > max_bytes) fail(path, 0, "file", too_big, fmt::format("{} bytes", size));
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, 0, "file", "a readable file", std::string("cannot open: ") + std::strerror(errno));
  // Read in pieces up to one byte past the limit: a file that grew, or a special file (a pipe, /dev/zero),
  // is refused without reading more.
  std::string text;
  char buffer[1 << 16];
  while (file) {
    file.read(buffer, sizeof buffer);
    text.append(buffer, static_cast<std::size_t>(file.gcount()));
    if (text.size() > max_bytes) fail(path, 0, "file", too_big, "more");
  }
  if (file.bad()) fail(path, 0, "file", "a readable file", "cannot read it");
  return text;
}

}  // namespace nodus::scenario
