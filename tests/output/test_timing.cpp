// The time left estimated from an earlier run's timing (RemainingTime::use_profile), and timing.csv's rows.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "nodus/output/progress_line.hpp"
#include "nodus/output/timing_csv.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

/// The knot branch's shape of cost: `release`, 20 steps over 1 s of load time, cheap (0.1 s a step); then
/// `rest`, 20 steps over 40 s, whose first 5 steps cost 6 s each and the rest 0.5 s (the knot slides open,
/// then comes to rest). Load time and wall time [s] of the run's start and of each of its 40 steps.
struct Timing {
  std::vector<double> times{0.0}, walls{0.0};
};

Timing knot_branch(double speed) {
  Timing run;
  for (int k = 1; k <= 40; ++k) {
    run.times.push_back(k <= 20 ? 0.05 * k : 1.0 + 2.0 * (k - 20));
    run.walls.push_back(run.walls.back() + speed * (k <= 20 ? 0.1 : k <= 25 ? 6.0 : 0.5));
  }
  return run;
}

TEST(Progress, AnEarlierRunOfTheSameStepsGivesTheTimeLeftAtThisMachinesSpeed) {
  const Timing earlier = knot_branch(1.0), now = knot_branch(1.7);  // this machine 1.7 times slower
  RemainingTime profiled({1.0, 41.0}, {20, 20}, 0.0), alone({1.0, 41.0}, {20, 20}, 0.0);
  ASSERT_TRUE(profiled.use_profile(earlier.times, earlier.walls));
  double worst_alone = 1.0;  // the largest factor between the run's own estimate and the truth
  for (std::size_t k = 1; k < now.times.size() - 1; ++k) {
    const double wall = now.walls[k] - now.walls[k - 1], truth = now.walls.back() - now.walls[k];
    profiled.step(now.times[k], wall);
    alone.step(now.times[k], wall);
    EXPECT_NEAR(profiled.seconds(), truth, 1e-9 * now.walls.back()) << "after step " << k;
    worst_alone = std::max({worst_alone, alone.seconds() / truth, truth / alone.seconds()});
  }
  // What the profile is for: from the run's own past, `rest`'s first steps are not foreseen in `release`.
  EXPECT_GT(worst_alone, 10.0);
  profiled.step(now.times.back(), 1.0);
  EXPECT_EQ(profiled.seconds(), 0.0);
}

TEST(Progress, AProfileServesARunStartedInsideItAndOtherSteps) {
  // A resumed run from load time 21 s (step 30 of knot_branch), on this machine 2 times slower, taking steps
  // of 4 s where the earlier run took 2 s: W is interpolated linearly in nominal steps between its rows.
  const Timing earlier = knot_branch(1.0);
  RemainingTime left({1.0, 41.0}, {20, 20}, 21.0);
  ASSERT_TRUE(left.use_profile(earlier.times, earlier.walls));
  EXPECT_TRUE(std::isnan(left.seconds()));  // nothing measured yet
  left.step(25.0, 2.0);                     // the earlier run: steps 31 and 32 in 1 s
  EXPECT_NEAR(left.seconds(), 2.0 * 0.5 * 8, 1e-12);
  left.step(26.0, 3.0);  // half of the earlier run's step 33
  const double done = 1.25, ratio = 5.0 / done;
  EXPECT_NEAR(left.seconds(), ratio * 0.5 * 7.5, 1e-12);
}

TEST(Progress, AProfileThatDoesNotCoverTheRunIsNotUsed) {
  const Timing earlier = knot_branch(1.0);
  RemainingTime left({1.0, 41.0}, {20, 20}, 0.0);
  // Stopped before the end of the last stage.
  EXPECT_FALSE(left.use_profile({earlier.times.begin(), earlier.times.end() - 1},
                                {earlier.walls.begin(), earlier.walls.end() - 1}));
  // Of another program: its last stage ends elsewhere.
  std::vector<double> longer = earlier.times;
  longer.back() = 42.0;
  EXPECT_FALSE(left.use_profile(longer, earlier.walls));
  // Started after this run (a branch's timing for the main run).
  RemainingTime main_run({1.0, 41.0}, {20, 20}, 0.0);
  EXPECT_FALSE(main_run.use_profile({1.0, 21.0, 41.0}, {0.0, 1.0, 2.0}));
  // Not a timing: wall time going back.
  std::vector<double> back = earlier.walls;
  back[10] = 0.0;
  EXPECT_FALSE(left.use_profile(earlier.times, back));
  // Then the estimate is the run's own (RemainingTime alone): one nominal step in 2 s, 39 left.
  left.step(0.05, 2.0);
  EXPECT_DOUBLE_EQ(left.seconds(), 78.0);
}

TEST(TimingCsv, RowsReadBackAsWritten) {
  testing::ScratchDir dir;
  const std::filesystem::path path = dir.path() / "timing.csv";
  std::vector<TimingRow> rows(3);
  rows[0] = {0, "twist, then tie", 0.0, 0, 0.0};
  rows[1] = {1, "twist, then tie", 0.125, 7, 0.3456789012345};
  rows[2] = {2, "say \"hi\"", 1.0, 12, 12.5};
  {
    std::ofstream out(path);
    out << kTimingCsvHeader << "\n";
    for (const TimingRow& row : rows) out << timing_csv_row(row) << "\n";
    out << "3,say,1.5";  // a last line cut short by a kill
  }
  EXPECT_EQ(timing_csv_row(rows[1]), "1,\"twist, then tie\",0.125,7,0.3456789012");
  const std::vector<TimingRow> read = read_timing_csv(path);
  ASSERT_EQ(read.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(read[i].step, rows[i].step);
    EXPECT_EQ(read[i].stage, rows[i].stage);
    EXPECT_DOUBLE_EQ(read[i].time, rows[i].time);
    EXPECT_EQ(read[i].newton_iterations, rows[i].newton_iterations);
    EXPECT_NEAR(read[i].wall_seconds, rows[i].wall_seconds, 1e-9 * rows[i].wall_seconds);
  }
}

TEST(TimingCsv, ABadFileIsNamedWithItsLine) {
  testing::ScratchDir dir;
  const auto message = [&](const std::string& text) {
    std::ofstream(dir.path() / "timing.csv") << text;
    try {
      read_timing_csv(dir.path() / "timing.csv");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = (dir.path() / "timing.csv").string();
  EXPECT_EQ(message(""), file + ":1: expected the header " + kTimingCsvHeader + ", got an empty file");
  EXPECT_EQ(message("step,stage\n"),
            file + ":1: expected the header " + kTimingCsvHeader + ", got 'step,stage'");
  EXPECT_EQ(message(std::string(kTimingCsvHeader) + "\n0,a,0,0,0\n1,a,x,2,3\n"),
            file + ":3: expected " + kTimingCsvHeader + " values, got '1,a,x,2,3'");
  EXPECT_THROW(read_timing_csv(dir.path() / "none.csv"), std::runtime_error);
}

}  // namespace
}  // namespace nodus::output
