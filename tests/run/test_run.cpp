// The run as a library call (src/nodus/run/run.hpp): the main stages, the branches, stop and resume, as
// `nodus run` does them, checked against the command line's files byte for byte (the command line's own
// guarantees are tested in tests/app/test_resume.cpp).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../app/cli_test_support.hpp"
#include "nodus/run/run.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::run {
namespace {

namespace fs = std::filesystem;
using testing::expect_same_results;
using testing::kBranches;
using testing::kDrag;
using testing::run_nodus;
using testing::scratch;
using testing::write;

/// `nodus run SCENARIO --out DIR -q --jobs 2`: the branches side by side in processes.
fs::path command_line_run(const fs::path& scenario, const std::string& name) {
  const fs::path out = scratch() / name;
  fs::remove_all(out);
  const testing::Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --jobs 2");
  EXPECT_EQ(r.status, 0) << r.err;
  return out;
}

Request request(const fs::path& scenario, const fs::path& out) {
  Request r;
  r.scenario_path = scenario.string();
  r.out = out;
  r.quiet = true;
  return r;
}

TEST(RunLibrary, BranchesInThisProcessGiveTheFilesOfTheCommandLine) {
  const fs::path scenario = write("library_branches.yaml", kDrag + kBranches);
  const fs::path reference = command_line_run(scenario, "library_branches_cli");
  const fs::path out = scratch() / "library_branches";
  fs::remove_all(out);
  const Outcome outcome = run(request(scenario, out));  // no executable: branches one at a time, here
  EXPECT_TRUE(outcome.converged);
  EXPECT_FALSE(outcome.interrupted);
  expect_same_results(reference, out);
  EXPECT_TRUE(fs::exists(out / "branches" / "mu_0.1" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
}

TEST(RunLibrary, BranchesInProcessesOfAGivenExecutable) {
  const fs::path scenario = write("library_processes.yaml", kDrag + kBranches);
  const fs::path reference = command_line_run(scenario, "library_processes_cli");
  const fs::path out = scratch() / "library_processes";
  fs::remove_all(out);
  Request r = request(scenario, out);
  r.branch_executable = NODUS_BINARY;
  r.jobs = 2;
  EXPECT_TRUE(run(r).converged);
  expect_same_results(reference, out);
}

TEST(RunLibrary, StoppedAndResumedGivesTheRunNeverStopped) {
  const fs::path scenario = write("library_resume.yaml", kDrag + kBranches);
  const fs::path reference = command_line_run(scenario, "library_resume_cli");
  const fs::path out = scratch() / "library_resume";
  fs::remove_all(out);
  Request r = request(scenario, out);
  // Stopped inside the main run (step 5 of 11), then inside the first branch (its second step).
  for (const int stop : {5, 8}) {
    r.stop_after_steps = stop;
    const Outcome stopped = run(r);
    EXPECT_TRUE(stopped.interrupted);
    EXPECT_FALSE(stopped.converged);
    EXPECT_FALSE(fs::exists(out / "summary.json"));  // as if killed
    r.resume = true;
  }
  r.stop_after_steps = 0;
  const Outcome finished = run(r);
  EXPECT_TRUE(finished.converged);
  EXPECT_FALSE(finished.already_complete);
  expect_same_results(reference, out);
  // Resumed once more, there is nothing left to do.
  const Outcome again = run(r);
  EXPECT_TRUE(again.already_complete);
  EXPECT_TRUE(again.converged);
}

TEST(RunLibrary, BadRequestsThrowOneLineAndWriteNothing) {
  const fs::path scenario = write("library_bad.yaml", kDrag + kBranches);
  const fs::path out = scratch() / "library_bad";
  fs::remove_all(out);
  Request r = request(scenario, out);
  r.resume = true;
  try {
    run(r);
    ADD_FAILURE() << "a resume without a checkpoint was accepted";
  } catch (const scenario::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("--resume: expected a checkpoint"), std::string::npos) << e.what();
  }
  r.resume = false;
  r.branch = "nonexistent";
  EXPECT_THROW(run(r), scenario::ScenarioError);
  EXPECT_FALSE(fs::exists(out));
}

TEST(RunLibrary, RunsAScenarioBuiltInCode) {
  // The scenario read once and handed over as a value: the same files as from its path.
  const fs::path scenario = write("library_value.yaml", testing::kDrag);
  const fs::path by_path = scratch() / "library_by_path", by_value = scratch() / "library_by_value";
  fs::remove_all(by_path);
  fs::remove_all(by_value);
  EXPECT_TRUE(run(request(scenario, by_path)).converged);
  EXPECT_TRUE(run(scenario::read_scenario(scenario.string()), request(scenario, by_value)).converged);
  expect_same_results(by_path, by_value);
}

}  // namespace
}  // namespace nodus::run
