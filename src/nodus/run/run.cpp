#include "nodus/run/run.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/folder_lock.hpp"
#include "nodus/output/output_folder.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/persistence/checkpoint_files.hpp"
#include "nodus/run/branches.hpp"
#include "nodus/run/run_outputs.hpp"
#include "nodus/scenario/declared_keys.hpp"
#include "nodus/simulation/simulation.hpp"
#include "nodus/solver/blas_kernels.hpp"

namespace nodus::run {
namespace {

namespace fs = std::filesystem;

std::string describe_position(const persistence::CheckpointInfo& info, const scenario::Scenario& scenario) {
  const auto& stages = scenario.stages;
  const std::string where =
      info.stage_begun
          ? fmt::format("inside stage '{}'", stages.at(static_cast<std::size_t>(info.stage)).name)
      : info.stage == 0
          ? std::string("at the start")
          : fmt::format("at the end of stage '{}'", stages.at(static_cast<std::size_t>(info.stage - 1)).name);
  return fmt::format("step {}, load time {:.6g} s, {}", info.steps, info.time, where);
}

}  // namespace

namespace {

/// run(), the output folder checked.
Outcome run_checked(scenario::Scenario scenario, const Request& request) {
  if (!request.quiet && request.branch.empty())
    spdlog::info("scenario {} resolved as:\n{}", request.scenario_path, scenario::describe(scenario));
  // Building the model validates what the reader cannot (e.g. a condition that would over-constrain a node,
  // in the stages or in a branch); it happens before anything is written.
  simulation::Simulation sim(std::move(scenario));
  const scenario::Scenario& main_scenario = sim.scenario();
  const fs::path& out = request.out;
  if (!request.branch.empty()) return run_one_branch(request, main_scenario);
  if (parallel::size() > 1 && parallel::is_root() &&
      main_scenario.solver.linear_solver != scenario::LinearSolverKind::petsc) {
    const auto keys = scenario::SolverSettings::keys();
    const auto key = std::find_if(keys.begin(), keys.end(),
                                  [](const auto& k) { return k.path == "solver.linear_solver"; });
    spdlog::warn(
        "{} MPI ranks, but solver.linear_solver: {} solves in one process: every rank repeats the whole run "
        "and rank 0 writes it; solver.linear_solver: petsc shares the work among the ranks "
        "(docs/parallel.md)",
        parallel::size(), scenario::value_text(*key, main_scenario.solver));
  }

  // One run at a time in a folder, from before it reads what an earlier run left there to the end (branch
  // processes write under it, and do not take it again). A folder that does not exist yet is taken when it is
  // made, below.
  std::optional<output::FolderLock> lock;  // rank 0's
  const bool taken_early = fs::is_directory(out);
  if (taken_early) lock_output_folder(out, lock);

  // With resume, everything that is read back is read and checked before anything is written.
  std::optional<simulation::SimulationState> resumed;
  std::vector<BranchStart> branch_starts(main_scenario.branches.size());
  if (request.resume) {
    if (fs::exists(out / "summary.json")) {
      const output::SummaryData done = output::read_summary(out / "summary.json");
      spdlog::info("the run in {} is already complete ({}); nothing to resume", out.string(),
                   done.converged ? "converged" : "stopped: " + done.failure);
      Outcome complete;
      complete.converged = done.converged;
      complete.already_complete = true;
      return complete;
    }
    const auto newest = persistence::newest_intact_checkpoint(out / "checkpoints", main_scenario);
    if (!newest)
      throw scenario::ScenarioError(fmt::format(
          "{}: --resume: expected a checkpoint (*.nodus-state) in {}, got none: nothing to resume "
          "(run without --resume to start the run)",
          out.string(), (out / "checkpoints").string()));
    resumed = persistence::read_checkpoint(newest->path, main_scenario);
    spdlog::info("resuming from {} ({})", newest->path.string(), describe_position(*newest, main_scenario));
    for (std::size_t b = 0; b < main_scenario.branches.size(); ++b) {
      const scenario::BranchSpec& branch = main_scenario.branches[b];
      const scenario::Scenario branch_scenario = scenario::branch_scenario(main_scenario, b);
      BranchStart& start = branch_starts[b];
      start.finished = fs::exists(branch_dir(out, branch) / "summary.json");
      if (start.finished) continue;
      start.own =
          persistence::newest_intact_checkpoint(branch_dir(out, branch) / "checkpoints", branch_scenario);
      const fs::path from = start.own ? start.own->path : branch_start_checkpoint(out, main_scenario, branch);
      if (fs::exists(from)) persistence::read_checkpoint(from, branch_scenario);  // checks it
    }
  }

  // From here on, files are written: by rank 0 alone under MPI (the other ranks compute the same states),
  // once every rank has read what it reads.
  parallel::barrier();
  const bool writes = parallel::is_root();
  if (writes) {
    std::error_code error;
    fs::create_directories(out, error);
    if (error) output::throw_write_error("create folder", out, error.value());
  }
  if (!taken_early) lock_output_folder(out, lock);
  if (writes) output::remove_stale_temporary_files(out);  // left by a killed run
  if (resumed) {
    sim.restore(std::move(*resumed), simulation::StartKind::resumed);
  } else if (writes) {
    // Branch results of an earlier run must not pass for finished or resumable ones.
    for (const scenario::BranchSpec& branch : main_scenario.branches) {
      fs::remove(branch_dir(out, branch) / "summary.json");
      persistence::remove_checkpoints(branch_dir(out, branch) / "checkpoints");
    }
  }
  int steps_left = request.stop_after_steps;

  std::optional<RunOutputs> outputs;
  if (writes)
    outputs.emplace(out, main_scenario, request.quiet, main_scenario.branches.empty(), std::string(),
                    request.timing_from.empty() ? fs::path() : request.timing_from / "timing.csv");
  simulation::RunOptions options;
  options.stop_after_steps = steps_left;
  options.cancel = request.cancel;
  // Said once the input has passed every check (bad input gets its one line alone).
  const solver::BlasKernels blas = solver::blas_kernels();
  if (!blas.better.empty())
    spdlog::warn(
        "OpenBLAS took its generic kernels ({}) on this processor, which can run its {} kernels: "
        "factorisations may take twice as long; start nodus with OPENBLAS_CORETYPE={} for them "
        "(docs/performance.md)",
        blas.loaded, blas.better, blas.better);
  const simulation::RunSummary summary = sim.run(outputs ? outputs->observers() : no_observers(), options);
  parallel::barrier();  // rank 0's checkpoints, which the branches start from, are written
  Outcome outcome;
  if (summary.interrupted) {
    if (summary.cancelled && outputs) outputs->save_stopped(sim);
    log_stopped_as_asked(request, sim, summary.cancelled);
    outcome.interrupted = true;
    outcome.cancelled = summary.cancelled;
    return outcome;
  }
  if (steps_left > 0) steps_left -= summary.new_steps;
  spdlog::info("{} steps, {} Newton iterations, {:.2f} s; results in {}", summary.steps,
               summary.newton_iterations, summary.wall_seconds, out.string());
  outcome.converged = summary.converged;
  if (!summary.converged)
    spdlog::error("run stopped: {}; the last converged state (load time {:.6g} s) is kept in {}",
                  summary.failure, sim.time(), out.string());

  if (main_scenario.branches.empty()) return outcome;

  // The branches, side by side in up to `jobs` processes; one at a time, in this process, when a step count
  // is to stop the run or no executable is given for the processes.
  const std::size_t count = main_scenario.branches.size();
  const std::size_t jobs = request.stop_after_steps > 0 || request.branch_executable.empty()
                               ? 1
                               : std::min(count, static_cast<std::size_t>(std::max(1, request.jobs)));
  std::vector<BranchRun> runs(count);
  if (jobs <= 1) {
    for (std::size_t b = 0; b < count; ++b) {
      runs[b] = run_branch(request, main_scenario, b, branch_starts[b], steps_left);
      if (runs[b].interrupted) {
        outcome.converged = false;
        outcome.interrupted = true;
        outcome.cancelled = runs[b].cancelled;
        return outcome;
      }
      if (steps_left > 0) steps_left -= runs[b].new_steps;
    }
  } else {
    std::vector<std::size_t> todo;
    for (std::size_t b = 0; b < count; ++b) {
      bool runnable = false;
      runs[b] = settled_branch(request, main_scenario, b, branch_starts[b], runnable);
      if (runnable) todo.push_back(b);
    }
    if (!todo.empty())
      spdlog::info("{} branches to run, {} at a time, each in its own process", todo.size(),
                   std::min(jobs, todo.size()));
    if (!run_branch_processes(request, main_scenario, todo, branch_starts, jobs, runs)) {
      const std::string cause = request.cancel_cause ? request.cancel_cause() : std::string("cancel");
      spdlog::error(
          "run stopped by {}: the branch processes saved their last converged states; continue the "
          "run with --resume",
          cause);
      outcome.converged = false;
      outcome.interrupted = outcome.cancelled = true;
      return outcome;
    }
  }
  std::vector<output::BranchOutcome> outcomes;
  for (BranchRun& r : runs) {
    outcome.converged = outcome.converged && r.outcome.converged;
    outcomes.push_back(std::move(r.outcome));
  }
  if (!writes) return outcome;
  // The main run's summary, written last: it lists the branches and marks the whole run as finished.
  output::SummaryData data = *outputs->summary().data();
  data.branches = std::move(outcomes);
  output::write_summary(out / "summary.json", data);
  return outcome;
}

}  // namespace

namespace {

/// The folders named on the command line, before the scenario is read and echoed.
void check_folders(const Request& request) {
  output::check_output_folder(request.out);
  if (!request.timing_from.empty() && !fs::is_directory(request.timing_from))
    throw scenario::ScenarioError(fmt::format(
        "{}: --timing-from: expected the output folder of an earlier run, got {}",
        request.timing_from.string(), fs::exists(request.timing_from) ? "a file" : "nothing there"));
}

}  // namespace

Outcome run(const Request& request) {
  check_folders(request);
  return run_checked(scenario::read_scenario(request.scenario_path), request);
}

Outcome run(scenario::Scenario scenario, const Request& request) {
  check_folders(request);
  return run_checked(std::move(scenario), request);
}

}  // namespace nodus::run
