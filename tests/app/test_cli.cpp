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

// OpenMP threads wait passively unless the user has chosen (app/main.cpp: nodus sets OMP_WAIT_POLICY and
// starts itself again, since libgomp reads it before main).
TEST(Cli, OpenMpThreadsWaitPassivelyUnlessTheUserChose) {
  const fs::path scenario = write("wait_policy.yaml", nodus::testing::kDrag);
  const auto policy_line = [&](const std::string& environment) {
    const fs::path err = scratch() / "wait_policy.txt";
    const std::string cmd = "env -u OMP_WAIT_POLICY -u NODUS_SET_OMP_WAIT_POLICY " + environment + " " +
                            NODUS_BINARY + " run " + scenario.string() + " --out " +
                            (scratch() / "wait_policy").string() +
                            " --quiet --verbose --stop-after-steps 1 2> " + err.string() + " > /dev/null";
    EXPECT_NE(std::system(cmd.c_str()), -1);
    const std::string text = nodus::testing::read_file(err);
    const std::size_t at = text.find("OpenMP wait policy:");
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(policy_line(""), "OpenMP wait policy: OMP_WAIT_POLICY=PASSIVE (set by nodus)");
  EXPECT_EQ(policy_line("OMP_WAIT_POLICY=ACTIVE"), "OpenMP wait policy: OMP_WAIT_POLICY=ACTIVE");
  // What libgomp itself read when it was loaded (OMP_DISPLAY_ENV makes it print its settings on stderr).
  const auto libgomp_policy = [&](const std::string& environment) {
    const fs::path err = scratch() / "wait_policy_libgomp.txt";
    const std::string cmd = "env -u OMP_WAIT_POLICY -u NODUS_SET_OMP_WAIT_POLICY OMP_DISPLAY_ENV=TRUE " +
                            environment + " " + NODUS_BINARY + " keys 2> " + err.string() + " > /dev/null";
    EXPECT_NE(std::system(cmd.c_str()), -1);
    const std::string text = nodus::testing::read_file(err);
    const std::size_t at = text.rfind("OMP_WAIT_POLICY = ");
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(libgomp_policy(""), "OMP_WAIT_POLICY = 'PASSIVE'");
  EXPECT_EQ(libgomp_policy("OMP_WAIT_POLICY=ACTIVE"), "OMP_WAIT_POLICY = 'ACTIVE'");
}

// The OPENBLAS_CORETYPE this processor can run where OpenBLAS takes its generic kernels: "SkylakeX" with
// AVX-512 (F, CD, BW, DQ, VL), "Haswell" with AVX2 and FMA, else none (asked of the processor here, not of
// nodus).
namespace {
std::string processor_coretype() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? "Haswell" : "";
}
}  // namespace

// Where OpenBLAS took its generic "Prescott" kernels on a processor that has AVX2 (or AVX-512), a run says
// which OPENBLAS_CORETYPE would serve it better; with kernels that match the processor it says nothing.
// OPENBLAS_CORETYPE forces OpenBLAS's choice, OPENBLAS_VERBOSE=2 makes it print it ("Core: NAME").
TEST(Cli, SaysWhenOpenBlasTookItsGenericKernels) {
  const fs::path scenario = write("blas_kernels.yaml", nodus::testing::kDrag);
  const auto run_with = [&](const std::string& core) {
    const fs::path err = scratch() / "blas_kernels.txt";
    const std::string cmd = "env OPENBLAS_VERBOSE=2 OPENBLAS_CORETYPE=" + core + " " + NODUS_BINARY +
                            " run " + scenario.string() + " --out " + (scratch() / "blas_kernels").string() +
                            " --quiet --stop-after-steps 1 2> " + err.string() + " > /dev/null";
    EXPECT_NE(std::system(cmd.c_str()), -1);
    return nodus::testing::read_file(err);
  };
  const std::string generic = run_with("Prescott");
  if (generic.find("Core: Prescott") == std::string::npos)
    GTEST_SKIP() << "the BLAS is not OpenBLAS (or prints nothing)";
  const std::string coretype = processor_coretype();
  if (coretype.empty()) {
    EXPECT_EQ(generic.find("OPENBLAS_CORETYPE="), std::string::npos) << generic;
    return;
  }
  const std::string advice = "OPENBLAS_CORETYPE=" + coretype;
  EXPECT_NE(generic.find(advice), std::string::npos) << generic;
  const std::string matched = run_with("Haswell");
  EXPECT_NE(matched.find("Core: Haswell"), std::string::npos) << matched;
  EXPECT_EQ(matched.find("OPENBLAS_CORETYPE="), std::string::npos) << matched;
}

// `nodus kernels --coretype` prints the OPENBLAS_CORETYPE that scripts/example.sh starts nodus with: the
// processor's kernels where OpenBLAS took its generic ones, nothing where its choice already matches.
TEST(Cli, KernelsNamesTheCoreTypeForScripts) {
  const auto kernels_with = [&](const std::string& core, const std::string& flag) {
    const fs::path out = scratch() / "kernels.txt";
    const fs::path err = scratch() / "kernels_err.txt";
    const std::string cmd = "env OPENBLAS_VERBOSE=2 OPENBLAS_CORETYPE=" + core + " " + NODUS_BINARY +
                            " kernels " + flag + " > " + out.string() + " 2> " + err.string();
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return std::make_pair(nodus::testing::read_file(out), nodus::testing::read_file(err));
  };
  const auto [generic, generic_log] = kernels_with("Prescott", "--coretype");
  if (generic_log.find("Core: Prescott") == std::string::npos)
    GTEST_SKIP() << "the BLAS is not OpenBLAS (or prints nothing)";
  const std::string advice = processor_coretype();
  EXPECT_EQ(generic, advice + "\n");
  const auto [line, line_log] = kernels_with("Prescott", "");
  EXPECT_NE(line.find("OpenBLAS kernels: Prescott"), std::string::npos) << line;
  if (advice.empty()) return;
  EXPECT_NE(line.find("OPENBLAS_CORETYPE=" + advice), std::string::npos) << line;
  const auto [matched, matched_log] = kernels_with(advice, "--coretype");
  EXPECT_NE(matched_log.find("Core: " + advice), std::string::npos) << matched_log;
  EXPECT_EQ(matched, "\n");
}
