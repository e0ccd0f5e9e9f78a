// Signals end a run cleanly: SIGTERM or SIGINT stops `nodus run` at the end of the Newton iteration under
// way, saves the last converged state as its newest checkpoint, says so in one line and exits with 128 + the
// signal's number; --resume then leaves exactly the files of the run never stopped (the reference: the same
// scenario in one go). A second signal ends the process at once. Branch processes stop with their run.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;

using nodus::testing::expect_same_results;
using nodus::testing::long_drag;
using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

/// `nodus run SCENARIO --out OUT -q [extra]` started in a process of its own, stderr into `err`.
pid_t start_nodus(const fs::path& scenario, const fs::path& out, const fs::path& err,
                  const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {NODUS_BINARY, "run", scenario.string(), "--out", out.string(), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

/// Data rows of a CSV file (0 if it does not exist yet).
std::size_t rows(const fs::path& csv) {
  const std::string text = nodus::testing::read_file(csv);
  std::size_t lines = 0;
  for (const char c : text) lines += c == '\n';
  return lines > 0 ? lines - 1 : 0;
}

/// Waits until `csv` has more than `count` data rows (at most 60 s).
bool wait_for_rows(const fs::path& csv, std::size_t count) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (rows(csv) <= count) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

/// The number after `before` in `text`, or -1.
long number_after(const std::string& text, const std::string& before) {
  const auto at = text.find(before);
  return at == std::string::npos ? -1 : std::stol(text.substr(at + before.size()));
}

TEST(Signals, StopAtTheLastConvergedStepAndResumeToTheUninterruptedRun) {
  const fs::path scenario = write("long_drag.yaml", long_drag());
  const fs::path reference = scratch() / "long_drag_ref";
  fs::remove_all(reference);
  const Result full = run_nodus("run " + scenario.string() + " --out " + reference.string() + " -q");
  ASSERT_EQ(full.status, 0) << full.err;

  for (const int signal : {SIGTERM, SIGINT}) {
    const std::string name = signal == SIGTERM ? "SIGTERM" : "SIGINT";
    SCOPED_TRACE(name);
    const fs::path out = scratch() / ("long_drag_" + name);
    const fs::path err = scratch() / ("long_drag_" + name + ".err");
    fs::remove_all(out);
    const pid_t pid = start_nodus(scenario, out, err);
    ASSERT_TRUE(wait_for_rows(out / "steps.csv", 20)) << nodus::testing::read_file(err);
    kill(pid, signal);
    const int status = wait_for(pid);
    const std::string said = nodus::testing::read_file(err);
    ASSERT_TRUE(WIFEXITED(status)) << said;
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal) << said;
    // One line, naming the signal and the step whose state is saved; that step is the last of steps.csv.
    const long step = number_after(said, "run stopped by " + name + " at step ");
    EXPECT_GT(step, 20) << said;
    EXPECT_EQ(static_cast<long>(rows(out / "steps.csv")), step) << said;
    EXPECT_NE(said.find("its last converged state is saved: continue it with --resume"), std::string::npos);
    EXPECT_TRUE(fs::exists(out / "checkpoints" / "latest.nodus-state"));
    EXPECT_FALSE(fs::exists(out / "summary.json"));

    const Result resumed = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --resume");
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_NE(resumed.err.find("(step " + std::to_string(step) + ", "), std::string::npos) << resumed.err;
    expect_same_results(reference, out);
  }
}

TEST(Signals, ASecondSignalEndsTheRunAtOnce) {
  const fs::path scenario = write("long_drag_twice.yaml", long_drag());
  const fs::path out = scratch() / "long_drag_twice";
  const fs::path err = scratch() / "long_drag_twice.err";
  fs::remove_all(out);
  const pid_t pid = start_nodus(scenario, out, err);
  ASSERT_TRUE(wait_for_rows(out / "steps.csv", 5)) << nodus::testing::read_file(err);
  // Two different signals, so that the second is not merged with the first while it is pending.
  kill(pid, SIGINT);
  kill(pid, SIGTERM);
  const int status = wait_for(pid);
  const std::string said = nodus::testing::read_file(err);
  ASSERT_TRUE(WIFSIGNALED(status)) << said;
  EXPECT_TRUE(WTERMSIG(status) == SIGTERM || WTERMSIG(status) == SIGINT) << WTERMSIG(status);
}

TEST(Signals, BranchProcessesStopWithTheirRunAndResume) {
  // Two branches side by side, each 300 steps; the run is stopped while both run.
  std::string branches = nodus::testing::kBranches;
  for (std::size_t at = branches.find("steps: 3\n"); at != std::string::npos;
       at = branches.find("steps: 3\n", at + 1))
    branches.replace(at, 9, "steps: 300\n");
  const fs::path scenario = write("branches_long.yaml", nodus::testing::kDrag + branches);
  const fs::path reference = scratch() / "branches_long_ref";
  fs::remove_all(reference);
  const Result full = run_nodus("run " + scenario.string() + " --out " + reference.string() + " -q --jobs 2");
  ASSERT_EQ(full.status, 0) << full.err;

  const fs::path out = scratch() / "branches_long";
  const fs::path err = scratch() / "branches_long.err";
  fs::remove_all(out);
  const pid_t pid = start_nodus(scenario, out, err, {"--jobs", "2"});
  ASSERT_TRUE(wait_for_rows(out / "branches" / "same" / "steps.csv", 10)) << nodus::testing::read_file(err);
  ASSERT_TRUE(wait_for_rows(out / "branches" / "mu_0.1" / "steps.csv", 10)) << nodus::testing::read_file(err);
  kill(pid, SIGTERM);
  const int status = wait_for(pid);
  const std::string said = nodus::testing::read_file(err);
  ASSERT_TRUE(WIFEXITED(status)) << said;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << said;
  EXPECT_NE(said.find("run stopped by SIGTERM: the branch processes saved their last converged states"),
            std::string::npos)
      << said;
  for (const char* branch : {"same", "mu_0.1"}) {
    EXPECT_NE(said.find(std::string("branch '") + branch + "' stopped by SIGTERM at step "),
              std::string::npos)
        << said;
    EXPECT_TRUE(fs::exists(out / "branches" / branch / "checkpoints" / "latest.nodus-state")) << branch;
  }
  const Result resumed =
      run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --jobs 2 --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  expect_same_results(reference, out);
}

}  // namespace

namespace {

// One run at a time in a folder: a second run into it, of the same scenario or another, resumed or not, is
// refused with status 2 and one line naming the folder and the process writing into it, and changes nothing;
// once the first is killed (kill -9: the kernel releases its lock), --resume goes on to the files of the run
// never stopped.
TEST(OneRunAtATime, ASecondRunIntoTheFolderIsRefused) {
  const fs::path scenario = write("long_drag_locked.yaml", long_drag());
  const fs::path other = write("other_locked.yaml", nodus::testing::kDrag);
  const fs::path reference = scratch() / "long_drag_locked_ref";
  fs::remove_all(reference);
  ASSERT_EQ(run_nodus("run " + scenario.string() + " --out " + reference.string() + " -q").status, 0);

  const fs::path out = scratch() / "long_drag_locked";
  fs::remove_all(out);
  const pid_t first = start_nodus(scenario, out, scratch() / "long_drag_locked.err");
  ASSERT_TRUE(wait_for_rows(out / "steps.csv", 5));
  const std::string expected =
      "nodus: " + out.string() +
      ": --out: expected a folder no other run is writing into, got one that process " +
      std::to_string(first) +
      " is writing into (let it end, stop it, or choose another "
      "folder)\n";
  for (const std::string& args : {"run " + scenario.string() + " --out " + out.string() + " -q",
                                  "run " + scenario.string() + " --out " + out.string() + " -q --resume",
                                  "run " + other.string() + " --out " + out.string() + " -q"}) {
    SCOPED_TRACE(args);
    const Result second = run_nodus(args);
    EXPECT_EQ(second.status, 2) << second.err;
    EXPECT_EQ(second.err, expected);
  }
  kill(first, SIGKILL);
  wait_for(first);
  const Result resumed = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  expect_same_results(reference, out);
}

}  // namespace
