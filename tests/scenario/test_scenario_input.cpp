// The text of a scenario before it becomes a YAML tree (yaml_input.hpp): the UTF-8 check against an
// independent decoder over every short byte sequence, the line of the offending byte, a second YAML document,
// the node limit counted by hand, and the size limit of the file.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yaml_input.hpp"

namespace nodus::scenario {
namespace {

namespace fs = std::filesystem;

/// Reference: the offset of the first byte that starts a sequence that is not valid, decoded the generic
/// way (the lead byte's high bits give the length, continuation bytes are 10xxxxxx, then the code point is
/// refused if it is overlong, a surrogate or above U+10FFFF [RFC 3629, 3 and 10]), or a control character
/// refused by YAML (C0 but tab, LF, CR; DEL).
std::optional<std::size_t> reference_fault(const std::vector<unsigned char>& bytes) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    const unsigned c = bytes[i];
    std::size_t length = 0;
    std::uint32_t code = 0;
    if ((c & 0x80u) == 0) {
      length = 1, code = c;
    } else if ((c & 0xe0u) == 0xc0u) {
      length = 2, code = c & 0x1fu;
    } else if ((c & 0xf0u) == 0xe0u) {
      length = 3, code = c & 0x0fu;
    } else if ((c & 0xf8u) == 0xf0u) {
      length = 4, code = c & 0x07u;
    } else {
      return i;
    }
    if (i + length > bytes.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      if ((bytes[i + k] & 0xc0u) != 0x80u) return i;
      code = (code << 6) | (bytes[i + k] & 0x3fu);
    }
    const std::uint32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < smallest[length] || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return i;
    if ((code < 0x20 && code != '\t' && code != '\n' && code != '\r') || code == 0x7f) return i;
    i += length;
  }
  return std::nullopt;
}

std::optional<std::size_t> fault_offset(const std::vector<unsigned char>& bytes) {
  const auto fault =
      find_invalid_text(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  if (!fault) return std::nullopt;
  return fault->offset;
}

TEST(YamlInput, Utf8AgreesWithAGenericDecoder) {
  // Every sequence of one and two bytes; three bytes with every lead and second byte and a third byte from
  // the edges of the ranges; four bytes with every lead from 0xf0 and every second byte likewise.
  const unsigned char edges[] = {0x00, 0x09, 0x0a, 0x1f, 0x41, 0x7f, 0x80, 0x8f, 0x90,
                                 0x9f, 0xa0, 0xbf, 0xc0, 0xc2, 0xe0, 0xf4, 0xff};
  int checked = 0;
  const auto check = [&](const std::vector<unsigned char>& bytes) {
    const auto expected = reference_fault(bytes);
    const auto got = fault_offset(bytes);
    if (got != expected) {
      std::string hex;
      for (unsigned char b : bytes) hex += " " + std::to_string(b);
      ADD_FAILURE() << "bytes" << hex << ": reference " << (expected ? std::to_string(*expected) : "valid")
                    << ", find_invalid_text " << (got ? std::to_string(*got) : "valid");
    }
    ++checked;
  };
  for (unsigned a = 0; a < 256; ++a) {
    check({static_cast<unsigned char>(a)});
    for (unsigned b = 0; b < 256; ++b) {
      check({static_cast<unsigned char>(a), static_cast<unsigned char>(b)});
      if (a >= 0xc0)
        for (unsigned char c : edges)
          check({static_cast<unsigned char>(a), static_cast<unsigned char>(b), c});
      if (a >= 0xf0)
        for (unsigned char c : edges)
          for (unsigned char d : edges)
            check({static_cast<unsigned char>(a), static_cast<unsigned char>(b), c, d});
    }
  }
  EXPECT_GT(checked, 1'000'000);
}

TEST(YamlInput, EveryScalarValueEncodedIsAccepted) {
  // U+0080..U+10FFFF without the surrogates, encoded by the bit layout of RFC 3629, section 3.
  std::string text;
  for (std::uint32_t code = 0x80; code <= 0x10ffff; ++code) {
    if (code >= 0xd800 && code <= 0xdfff) continue;
    if (code < 0x800) {
      text += static_cast<char>(0xc0 | (code >> 6));
    } else if (code < 0x10000) {
      text += static_cast<char>(0xe0 | (code >> 12));
      text += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
    } else {
      text += static_cast<char>(0xf0 | (code >> 18));
      text += static_cast<char>(0x80 | ((code >> 12) & 0x3f));
      text += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
    }
    text += static_cast<char>(0x80 | (code & 0x3f));
  }
  const auto fault = find_invalid_text(text);
  EXPECT_FALSE(fault) << "at offset " << fault->offset << ": " << fault->what;
  EXPECT_FALSE(find_invalid_text("tab\there\r\nand 'quotes' ~"));
}

const std::string kGood = "# a comment: caf\xc3\xa9 is UTF-8\n" + std::string(R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 4}
conditions:
  - {name: root, type: clamp, beam: rod, at: start}
stages:
  - name: load
    steps: 2
)");

/// The message of the ScenarioError that parse_scenario throws for `text`, or "accepted".
std::string message(const std::string& text) {
  try {
    parse_scenario(text, "s.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "accepted";
}

std::string with_line(std::string text, int line, const std::string& replacement) {
  std::size_t begin = 0;
  for (int i = 1; i < line; ++i) begin = text.find('\n', begin) + 1;
  return text.replace(begin, text.find('\n', begin) - begin, replacement);
}

TEST(YamlInput, BytesThatAreNotUtf8AreRefusedWithTheirLine) {
  ASSERT_EQ(message(kGood), "accepted");
  EXPECT_EQ(message(with_line(kGood, 9,
                              "  - name: lo\xff"
                              "ad")),
            "s.yaml:9: text: expected UTF-8 text without control characters, got the byte 0xff, which is not "
            "UTF-8");
  // Latin-1 "é" in a comment: 0xe9 then a space.
  EXPECT_EQ(message(with_line(kGood, 1, "# caf\xe9 au lait")),
            "s.yaml:1: text: expected UTF-8 text without control characters, got the bytes 0xe9 0x20, which "
            "are not UTF-8");
  // A surrogate (CESU-8) and an overlong "/".
  EXPECT_NE(message(with_line(kGood, 5, "  - {name: \xed\xa0\x80, material: m}")).find("s.yaml:5: text:"),
            std::string::npos);
  EXPECT_NE(message(with_line(kGood, 6, "conditions: # \xc0\xaf")).find("s.yaml:6: text:"),
            std::string::npos);
  EXPECT_NE(message(kGood + "# cut short \xe2\x82")
                .find("s.yaml:11: text: expected UTF-8 text without "
                      "control characters, got the bytes 0xe2 0x82 cut short"),
            std::string::npos);
  std::string nul = with_line(kGood, 10, "    steps: 2");
  nul.insert(nul.find("steps: 2") + 8, 1, '\0');
  EXPECT_EQ(message(nul),
            "s.yaml:10: text: expected UTF-8 text without control characters, got the control "
            "character 0x00");
}

TEST(YamlInput, OnlyOneDocument) {
  EXPECT_EQ(message("---\n" + kGood + "...\n"), "accepted");  // markers around the one document are fine
  EXPECT_EQ(message(kGood + "---\nmaterials: []\n"),
            "s.yaml:11: yaml: expected one YAML document, got a second one ('---' after the first document)");
  EXPECT_EQ(message(kGood + "\n---\n"),
            "s.yaml:12: yaml: expected one YAML document, got a second one ('---' after the first document)");
  // A second document that is not valid YAML is refused as such (at the end of the file, line 13, where
  // the parser misses the closing bracket).
  EXPECT_NE(message(kGood + "...\n--- [1, 2\n").find("s.yaml:13: yaml: expected valid YAML, got "),
            std::string::npos);
}

TEST(YamlInput, NodeLimitCountsEveryValue) {
  // A map, its two keys, a list of three numbers and one scalar: 1 + 2 + 1 + 3 + 1 = 8 nodes.
  const std::string text = "a: [1, 2, 3]\nb: text\n";
  EXPECT_NO_THROW(check_yaml_input(text, "n.yaml", 8));
  try {
    check_yaml_input(text, "n.yaml", 7);
    ADD_FAILURE() << "7 nodes accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "n.yaml:2: yaml: expected at most 7 YAML values (lists, maps and scalars), got more (a scenario "
        "is not a data file)");
  }
}

TEST(YamlInput, ALongListWhereAVectorIsExpectedIsRefusedBeforeTheTree) {
  // 1.5 million numbers where three are expected: more nodes than kMaxScenarioNodes, refused by the event
  // pass on the line of the list before yaml-cpp builds a tree of them (which took ~470 bytes a number).
  std::string list = "[0";
  for (int i = 0; i < 1'500'000; ++i) list += ",0";
  const std::string big = with_line(
      kGood, 5, "  - {name: rod, material: m, radius: 0.1, length: 10, elements: 4, start: " + list + "]}");
  EXPECT_EQ(message(big),
            "s.yaml:5: yaml: expected at most 1000000 YAML values (lists, maps and scalars), got "
            "more (a scenario is not a data file)");
  // Within the limit, the reader's own check of the vector's size.
  std::string small = "[0";
  for (int i = 0; i < 1000; ++i) small += ",0";
  EXPECT_EQ(message(with_line(
                kGood, 5,
                "  - {name: rod, material: m, radius: 0.1, length: 10, elements: 4, start: " + small + "]}")),
            "s.yaml:5: beams[0].start: expected a list of 3 numbers (mm), got a list of 1001 items");
}

TEST(YamlInput, FileSizeIsCheckedBeforeReading) {
  const fs::path dir = fs::temp_directory_path() / ("nodus_yaml_input_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "s.yaml";
  std::ofstream(file) << kGood;
  const auto size = static_cast<std::uintmax_t>(kGood.size());
  EXPECT_EQ(read_scenario_text(file.string(), size), kGood);
  try {
    read_scenario_text(file.string(), size - 1);
    ADD_FAILURE() << "a file over the limit was read";
  } catch (const ScenarioError& e) {
    const std::string text = e.what();
    EXPECT_EQ(text.rfind(file.string() + ":0: file: expected a scenario file of at most " +
                             std::to_string(size - 1) + " bytes",
                         0),
              0u)
        << text;
    EXPECT_TRUE(text.ends_with(", got " + std::to_string(size) + " bytes")) << text;
  }
  // A special file is read up to the limit and no further.
  try {
    read_scenario_text("/dev/zero", 1000);
    ADD_FAILURE() << "/dev/zero was read";
  } catch (const ScenarioError& e) {
    EXPECT_TRUE(std::string(e.what()).ends_with(", got more")) << e.what();
  }
  // The default limit, on a sparse file one byte over it (nothing of it is read).
  const fs::path big = dir / "big.yaml";
  std::ofstream(big) << kGood;
  fs::resize_file(big, kMaxScenarioBytes + 1);
  try {
    read_scenario(big.string());
    ADD_FAILURE() << "a file over kMaxScenarioBytes was read";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()),
              big.string() +
                  ":0: file: expected a scenario file of at most 16777216 bytes (16 MiB), "
                  "got 16777217 bytes");
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nodus::scenario
