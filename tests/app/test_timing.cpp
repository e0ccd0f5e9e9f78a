// timing.csv and the time left estimated from an earlier run's (`nodus run --timing-from`, docs/output.md).

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_test_support.hpp"
#include "nodus/output/progress_reporter.hpp"
#include "nodus/output/timing_csv.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::testing {
namespace {

/// The lines of `text`, without their line ends.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// `line`'s first `n` comma-separated fields (no quotes in these files).
std::string first_fields(const std::string& line, int n) {
  std::size_t end = 0;
  for (int i = 0; i < n && end != std::string::npos; ++i) end = line.find(',', end + (i > 0 ? 1 : 0));
  return line.substr(0, end);
}

fs::path fresh(const std::string& name) {
  const fs::path out = scratch() / name;
  fs::remove_all(out);
  return out;
}

TEST(Timing, ARowPerConvergedStepAfterTheRunsStart) {
  const fs::path scenario = write("timing_rows.yaml", kDrag + kBranches);
  const fs::path out = fresh("timing_rows");
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --jobs 1");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const fs::path& dir : {out, out / "branches" / "mu_0.1"}) {
    SCOPED_TRACE(dir.string());
    const std::vector<std::string> steps = lines_of(read_file(dir / "steps.csv"));
    const std::vector<output::TimingRow> rows = output::read_timing_csv(dir / "timing.csv");
    ASSERT_EQ(rows.size(), steps.size());  // the start row, then one per step (steps.csv: the header)
    const bool branch = dir != out;
    EXPECT_EQ(rows[0].step, branch ? 7 : 0);  // the branch starts from the end of drag, step 7
    EXPECT_EQ(rows[0].stage, branch ? "back" : "press");
    EXPECT_DOUBLE_EQ(rows[0].time, branch ? 2.0 : 0.0);
    EXPECT_EQ(rows[0].wall_seconds, 0.0);
    for (std::size_t i = 1; i < rows.size(); ++i) {
      // step,stage,time,newton_iterations: steps.csv's first four columns.
      EXPECT_EQ(first_fields(output::timing_csv_row(rows[i]), 4), first_fields(steps[i], 4));
      EXPECT_GE(rows[i].wall_seconds, rows[i - 1].wall_seconds);
    }
  }
}

TEST(Timing, AResumedRunGoesOnFromTheInterruptedRunsWallTime) {
  const fs::path scenario = write("timing_resume.yaml", kDrag);
  const fs::path out = fresh("timing_resume");
  const std::string args = "run " + scenario.string() + " --out " + out.string() + " -q";
  ASSERT_EQ(run_nodus(args + " --stop-after-steps 5").status, 3);
  const std::vector<output::TimingRow> before = output::read_timing_csv(out / "timing.csv");
  ASSERT_EQ(before.size(), 1u + 5u);
  ASSERT_EQ(run_nodus(args + " --resume").status, 0);
  const std::vector<output::TimingRow> after = output::read_timing_csv(out / "timing.csv");
  ASSERT_EQ(after.size(), 1u + 11u);
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].step, static_cast<int>(i));
    // Resumed from the end of `press` (step 3): its rows are kept as written, the later ones computed again.
    if (i <= 3) {
      EXPECT_EQ(after[i].wall_seconds, before[i].wall_seconds) << i;
    }
    if (i > 0) {
      EXPECT_GE(after[i].wall_seconds, after[i - 1].wall_seconds) << i;
    }
  }
}

TEST(Timing, ALaterRunEstimatesItsTimeLeftFromAnEarlierRun) {
  const fs::path scenario = write("timing_later.yaml", kDrag + kBranches);
  const fs::path first = fresh("timing_first"), second = fresh("timing_second");
  const std::string run = "run " + scenario.string() + " --out ";
  const Result r1 = run_nodus(run + first.string() + " --jobs 1");
  ASSERT_EQ(r1.status, 0) << r1.err;
  EXPECT_EQ(r1.err.find("the time left is estimated from the timing"), std::string::npos) << r1.err;

  // Again into the same folder: its own timing.csv, left by the first run.
  const Result again = run_nodus(run + first.string() + " --jobs 1");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("the time left is estimated from the timing of an earlier run (" +
                           (first / "timing.csv").string() + ")"),
            std::string::npos)
      << again.err;
  EXPECT_NE(again.err.find("branch mu_0.1: the time left is estimated from the timing of an earlier run (" +
                           (first / "branches" / "mu_0.1" / "timing.csv").string() + ")"),
            std::string::npos)
      << again.err;

  // Into another folder, named; the branches side by side in processes of their own are told too.
  const Result named = run_nodus(run + second.string() + " --jobs 2 --timing-from " + first.string());
  ASSERT_EQ(named.status, 0) << named.err;
  EXPECT_NE(named.err.find("branch same: the time left is estimated from the timing of an earlier run (" +
                           (first / "branches" / "same" / "timing.csv").string() + ")"),
            std::string::npos)
      << named.err;
  expect_same_results(first, second);

  // The timing of other stages is said not to serve, and the run goes on.
  const fs::path other = write("timing_other.yaml", kDrag);
  const fs::path third = fresh("timing_third");
  const Result mismatch = run_nodus("run " + other.string() + " --out " + third.string() + " --timing-from " +
                                    (first / "branches" / "same").string());
  ASSERT_EQ(mismatch.status, 0) << mismatch.err;
  EXPECT_NE(
      mismatch.err.find((first / "branches" / "same" / "timing.csv").string() +
                        " is not the timing of a run of these stages from load time 0 s to 4 s; the time "
                        "left is estimated from this run alone"),
      std::string::npos)
      << mismatch.err;
}

TEST(Timing, AMissingFolderIsBadInput) {
  const fs::path scenario = write("timing_missing.yaml", kDrag);
  const fs::path out = fresh("timing_missing");
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " --timing-from " +
                             (scratch() / "no_such_run").string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, "nodus: " + (scratch() / "no_such_run").string() +
                       ": --timing-from: expected the output folder of an earlier run, got nothing there\n");
  EXPECT_FALSE(fs::exists(out));
}

// scripts/example.sh gives an example the timing kept in examples/timing/NAME: it must be of the example's
// stages, for the main run and each branch (regenerate it as examples/timing/README.md says, if this fails).
TEST(Timing, TheTimingKeptForTheExamplesServesTheirRunsAndBranches) {
  const fs::path examples = fs::path(NODUS_SOURCE_DIR) / "examples";
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(examples / "timing"))
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  EXPECT_NE(std::find(names.begin(), names.end(), "monofilament_knot"), names.end());  // the flagship's
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const scenario::Scenario main = scenario::read_scenario((examples / (name + ".yaml")).string());
    const fs::path kept = examples / "timing" / name;
    output::RemainingTime main_left = output::remaining_time(main, 0.0);
    EXPECT_TRUE(output::use_timing(main_left, main, output::read_timing_csv(kept / "timing.csv")));
    for (std::size_t b = 0; b < main.branches.size(); ++b) {
      const scenario::Scenario branch = scenario::branch_scenario(main, b);
      const double start = scenario::stage_end_time(main, main.branches[b].from);  // where the branch starts
      const std::vector<output::TimingRow> rows =
          output::read_timing_csv(kept / "branches" / main.branches[b].name / "timing.csv");
      ASSERT_FALSE(rows.empty());
      EXPECT_NEAR(rows.front().time, start, 1e-9) << main.branches[b].name;
      output::RemainingTime left = output::remaining_time(branch, start);
      EXPECT_TRUE(output::use_timing(left, branch, rows)) << main.branches[b].name;
    }
  }
}

}  // namespace
}  // namespace nodus::testing
