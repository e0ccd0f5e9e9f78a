#pragma once
/// The branches of a run (scenario key `branches`): each starts from the main run's checkpoint at the end of
/// its `from` stage and writes into OUT/branches/NAME. They run one after the other in this process, or side
/// by side, each in a process of its own (`nodus run --branch NAME`): a process of its own computes a branch
/// exactly as this process would, whatever runs beside it; threads would not (the sparse solvers' round-off
/// depends on how the memory of concurrent threads is laid out).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include "nodus/output/folder_lock.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/persistence/checkpoint_files.hpp"
#include "nodus/run/run.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::run {

/// Where a branch starts when the run resumes: finished (its summary.json exists), from its own newest
/// checkpoint, or from the main run's checkpoint of its `from` stage.
struct BranchStart {
  bool finished = false;
  std::optional<persistence::CheckpointInfo> own;  ///< its newest checkpoint, when it has one
};

/// What became of one branch.
struct BranchRun {
  output::BranchOutcome outcome;
  bool interrupted = false;  ///< stopped by stop_after_steps or Request::cancel
  bool cancelled = false;    ///< stopped by Request::cancel
  int new_steps = 0;         ///< steps computed here (not read back from a checkpoint)
};

/// OUT/branches/NAME.
std::filesystem::path branch_dir(const std::filesystem::path& out, const scenario::BranchSpec& branch);
/// The checkpoint a branch starts from: the main run's at the end of its `from` stage.
std::filesystem::path branch_start_checkpoint(const std::filesystem::path& out,
                                              const scenario::Scenario& scenario,
                                              const scenario::BranchSpec& branch);

/// Takes the output folder `dir` for this run (rank 0 locks it; every rank throws the refusal together) and
/// puts the lock into `lock`. Throws scenario::ScenarioError if another process holds it.
void lock_output_folder(const std::filesystem::path& dir, std::optional<output::FolderLock>& lock);

/// Logs the message of a run stopped by stop_after_steps, or by Request::cancel when `cancelled`.
void log_stopped_as_asked(const Request& request, const simulation::Simulation& sim, bool cancelled);

/// Branch `b`'s outcome as far as it is known without running it: its name, start and friction; if it has
/// finished (its summary.json exists), how it ended; if its start checkpoint is missing (the main run did not
/// reach its `from` stage), why it is not run. `runnable` says whether it is left to run.
BranchRun settled_branch(const Request& request, const scenario::Scenario& main_scenario, std::size_t b,
                         const BranchStart& start, bool& runnable);

/// Runs branch `b` in this process from where `start` says, or reads back its outcome if it had finished.
/// `steps_left` > 0 stops it, as if killed, after that many converged steps.
BranchRun run_branch(const Request& request, const scenario::Scenario& main_scenario, std::size_t b,
                     const BranchStart& start, int steps_left);

/// Request::branch alone: from the main run's checkpoint at the end of its `from` stage (with resume: from
/// its own newest checkpoint, or nothing if it has finished).
Outcome run_one_branch(const Request& request, const scenario::Scenario& main_scenario);

/// Runs the branches listed in `todo`, each in a process of Request::branch_executable, at most `jobs` at a
/// time, and fills in their outcomes from the summary.json each writes. Returns false when Request::cancel
/// stopped them (each process is sent SIGTERM and waited for; their checkpoints let the run resume).
bool run_branch_processes(const Request& request, const scenario::Scenario& main_scenario,
                          const std::vector<std::size_t>& todo, const std::vector<BranchStart>& starts,
                          std::size_t jobs, std::vector<BranchRun>& runs);

}  // namespace nodus::run
