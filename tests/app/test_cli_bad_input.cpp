// Bad input that used to get through the command line: bytes that are not UTF-8, a second YAML document, a
// file far too large to be a scenario, and --out naming a file or a path under one. Each gives one line
// (file, line, what was expected), exit status 2, no settings echo before it, and nothing written.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

const std::string kGood = R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 4}
conditions:
  - {name: root, type: clamp, beam: rod, at: start}
stages:
  - name: load
    steps: 2
)";

/// Runs `nodus run FILE --out OUT` without --quiet (so that an echo of the settings would show) and checks
/// the refusal: status 2, exactly the one line `expect` is part of, and `out` not created.
void expect_refused(const fs::path& file, const fs::path& out, const std::string& expect) {
  const Result r = run_nodus("run " + file.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_EQ(r.err.rfind("nodus: ", 0), 0u) << r.err;
}

TEST(CliBadInput, BytesThatAreNotUtf8) {
  std::string text = kGood;
  text.replace(text.find("name: load"), 10,
               "name: lo\xff\xfe"
               "ad");  // line 8
  const fs::path file = write("not_utf8.yaml", text);
  const fs::path out = scratch() / "out_not_utf8";
  fs::remove_all(out);
  expect_refused(
      file, out,
      file.string() +
          ":8: text: expected UTF-8 text without control characters, got the byte 0xff, which is not "
          "UTF-8");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run_nodus("check " + file.string()).status, 2);
}

TEST(CliBadInput, ASecondDocument) {
  const fs::path file = write("two_documents.yaml", kGood + "---\n" + kGood);
  const fs::path out = scratch() / "out_two_documents";
  fs::remove_all(out);
  expect_refused(file, out,
                 file.string() +
                     ":10: yaml: expected one YAML document, got a second one ('---' after the first "
                     "document)");
  EXPECT_FALSE(fs::exists(out));
  // One document between markers is fine.
  EXPECT_EQ(run_nodus("check " + write("one_document.yaml", "---\n" + kGood + "...\n").string()).status, 0);
}

TEST(CliBadInput, AFileFarTooLarge) {
  // 50 MB (sparse: a scenario followed by zero bytes); refused from its size, before it is read.
  const fs::path file = scratch() / "huge.yaml";
  std::ofstream(file) << kGood;
  fs::resize_file(file, 50'000'000);
  const fs::path out = scratch() / "out_huge";
  fs::remove_all(out);
  expect_refused(
      file, out,
      file.string() +
          ":0: file: expected a scenario file of at most 16777216 bytes (16 MiB), got 50000000 bytes");
  EXPECT_FALSE(fs::exists(out));
  fs::remove(file);
}

TEST(CliBadInput, OutIsAFileOrUnderAFile) {
  const fs::path file = write("good_for_out.yaml", kGood);
  const fs::path taken = write("taken.txt", "a file of the user's\n");
  expect_refused(
      file, taken,
      taken.string() +
          ": --out: expected a folder, or a path where one can be created, got an existing file that "
          "is not a folder");
  expect_refused(
      file, taken / "results",
      (taken / "results").string() +
          ": --out: expected a folder, or a path where one can be created, got a path under the file '" +
          taken.string() + "'");
  EXPECT_EQ(nodus::testing::read_file(taken), "a file of the user's\n");
  // With --resume and --branch as well.
  for (const std::string extra : {" --resume", " --branch b", " -q"}) {
    const Result r = run_nodus("run " + file.string() + " --out " + taken.string() + extra);
    EXPECT_EQ(r.status, 2) << extra << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << extra << ": " << r.err;
  }
}

}  // namespace
