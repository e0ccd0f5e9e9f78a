#pragma once
/// A scenario run as `nodus run` does it, as a library call: the main stages with their output files and
/// checkpoints, then the branches (side by side, each in a process of its own, or one after the other in this
/// process), a resume from the newest checkpoints, or one branch alone. The command line only parses its
/// arguments into a Request and maps the Outcome onto an exit status.
///
/// Guarantees (tested in tests/app/test_resume.cpp and tests/run/): a run stopped after any step and resumed
/// leaves the files of the run never stopped, byte for byte; branches side by side leave the files of
/// branches one at a time.

#include <filesystem>
#include <functional>
#include <string>

#include "nodus/scenario/scenario.hpp"

namespace nodus::run {

/// What to run, and how.
struct Request {
  /// The scenario file: read by run(); also handed to the branch processes.
  std::string scenario_path;
  std::filesystem::path out;  ///< output folder (created if missing)
  bool quiet = false;         ///< no settings echo, no progress lines
  bool resume = false;        ///< continue from the newest checkpoints in `out`
  /// For tests: stop as if killed after this many converged steps (0: never); branches then run one at a
  /// time in this process.
  int stop_after_steps = 0;
  int jobs = 1;        ///< branches run side by side, at most
  std::string branch;  ///< run only this branch (the main run has reached its `from` stage)
  bool verbose = false;
  /// The output folder of an earlier run of the same scenario (or of one with the same stages): the progress
  /// lines estimate the time left from its timing.csv (and a branch from its branch's). Empty: from `out`'s
  /// own, left there by an earlier run, if any.
  std::filesystem::path timing_from;
  /// The nodus executable that runs a branch in a process of its own (`EXE run SCENARIO --out DIR --branch
  /// NAME`). Empty: branches run in this process, one at a time, whatever `jobs` says (what a library caller
  /// such as Python gets by default; the results are the same).
  std::filesystem::path branch_executable;
  /// Asked after every Newton iteration, every step and while branch processes run: true stops the run at
  /// its last converged state, which is saved as its newest checkpoint (--resume goes on from it; branch
  /// processes are sent SIGTERM and do the same). SIGTERM and SIGINT for `nodus run`, Ctrl-C in Python.
  /// Empty: never.
  std::function<bool()> cancel;
  /// What stopped the run when `cancel` said so, for the message ("SIGTERM"); empty: "cancel".
  std::function<std::string()> cancel_cause;
};

/// How a run ended.
struct Outcome {
  bool converged = false;    ///< the main run and every branch completed
  bool interrupted = false;  ///< stopped by stop_after_steps or by Request::cancel
  /// Nothing was computed: the run in `out` had already finished (resume).
  bool already_complete = false;
  bool cancelled = false;  ///< stopped by Request::cancel
};

/// Runs `request.scenario_path` (see above). Bad input (the scenario, the out folder, --resume without a
/// checkpoint, a checkpoint of another scenario, an unknown branch) throws scenario::ScenarioError with one
/// line before anything is written; other failures throw std::runtime_error.
Outcome run(const Request& request);

/// Runs `scenario` (already read; its path is scenario.path) as run(request) would.
Outcome run(scenario::Scenario scenario, const Request& request);

}  // namespace nodus::run
