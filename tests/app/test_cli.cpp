// The command line: bad input gives one line naming file, line and key, exit status 2 and nothing written;
// a good scenario writes every result file.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

const char* kGood = R"(materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: m, radius: 0.1, length: 10, elements: 4}
conditions:
  - {name: root, type: clamp, beam: rod, at: start}
  - {name: tip, type: load, beam: rod, at: end}
stages:
  - name: load
    steps: 2
    loads:
      tip: {force: [0, -0.001, 0]}
)";

TEST(Cli, BadInputWritesNothing) {
  struct Case {
    std::string name, text, expect;
  };
  std::string negative_radius = kGood;
  negative_radius.replace(negative_radius.find("radius: 0.1"), 11, "radius: -0.1");
  std::string unknown_condition = kGood;
  unknown_condition.replace(unknown_condition.find("tip: {force"), 3, "top");
  const Case cases[] = {
      {"negative_radius.yaml", negative_radius, ":4: beams[0].radius: expected"},
      {"unknown_condition.yaml", unknown_condition, ":12: stages[0].loads"},
      {"not_yaml.yaml", "materials: [unclosed\n  - {\n", "not_yaml.yaml:"},
  };
  for (const Case& c : cases) {
    const fs::path file = write(c.name, c.text);
    const fs::path out = scratch() / ("out_" + c.name);
    fs::remove_all(out);
    const Result r = run_nodus("run " + file.string() + " --out " + out.string() + " -q");
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  const Result missing = run_nodus("run " + (scratch() / "absent.yaml").string() + " --out " +
                                   (scratch() / "out_absent").string());
  EXPECT_EQ(missing.status, 2);
  EXPECT_FALSE(fs::exists(scratch() / "out_absent"));
}

TEST(Cli, GoodScenarioWritesEveryResult) {
  const fs::path file = write("good.yaml", kGood);
  const fs::path out = scratch() / "out_good";
  fs::remove_all(out);
  const Result r = run_nodus("run " + file.string() + " --out " + out.string() + " -q");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"summary.json", "steps.csv", "final_nodes.csv", "result.pvd"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  std::ifstream steps(out / "steps.csv");
  std::string line;
  int rows = 0;
  while (std::getline(steps, line)) ++rows;
  EXPECT_EQ(rows, 3);  // header + 2 steps
}

}  // namespace
