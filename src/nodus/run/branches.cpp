#include "nodus/run/branches.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/output/folder_lock.hpp"
#include "nodus/output/output_folder.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/run/run_outputs.hpp"

namespace nodus::run {
namespace {

namespace fs = std::filesystem;

/// How a finished branch ended, from its summary.json.
void read_finished(const fs::path& summary, output::BranchOutcome& outcome) {
  const output::SummaryData done = output::read_summary(summary);
  outcome.converged = done.converged;
  outcome.failure = done.failure;
  outcome.steps = done.steps;
  outcome.final_time = done.final_time;
}

}  // namespace

fs::path branch_dir(const fs::path& out, const scenario::BranchSpec& branch) {
  return out / "branches" / branch.name;
}

fs::path branch_start_checkpoint(const fs::path& out, const scenario::Scenario& scenario,
                                 const scenario::BranchSpec& branch) {
  return out / "checkpoints" /
         persistence::checkpoint_file_name(branch.from,
                                           scenario.stages.at(static_cast<std::size_t>(branch.from)).name);
}

void lock_output_folder(const fs::path& dir, std::optional<output::FolderLock>& lock) {
  std::string refused;
  if (parallel::is_root()) {
    try {
      lock.emplace(dir);
    } catch (const scenario::ScenarioError& e) {
      refused = e.what();
    }
  }
  if (!parallel::root_value(refused.empty()))
    throw scenario::ScenarioError(refused.empty() ? dir.string() + ": --out: held by another run" : refused);
}

void log_stopped_as_asked(const Request& request, const simulation::Simulation& sim, bool cancelled) {
  if (cancelled) {
    const std::string cause = request.cancel_cause ? request.cancel_cause() : std::string();
    spdlog::error(
        "{}stopped by {} at step {}, load time {:.6g} s; its last converged state is saved: continue it with "
        "--resume",
        sim.scenario().origin ? fmt::format("branch '{}' ", sim.scenario().origin->name)
                              : std::string("run "),
        cause.empty() ? "cancel" : cause, sim.steps(), sim.time());
    return;
  }
  spdlog::error(
      "run stopped after {} converged steps, as asked (--stop-after-steps), at load time {:.6g} s; "
      "continue it with --resume",
      request.stop_after_steps, sim.time());
}

BranchRun settled_branch(const Request& request, const scenario::Scenario& main_scenario, std::size_t b,
                         const BranchStart& start, bool& runnable) {
  const scenario::BranchSpec& branch = main_scenario.branches[b];
  BranchRun run;
  output::BranchOutcome& outcome = run.outcome;
  outcome.name = branch.name;
  outcome.from = main_scenario.stages.at(static_cast<std::size_t>(branch.from)).name;
  outcome.friction = scenario::branch_scenario(main_scenario, b).contact.friction;
  outcome.folder = "branches/" + branch.name;
  runnable = false;
  if (start.finished) {
    read_finished(branch_dir(request.out, branch) / "summary.json", outcome);
  } else if (!start.own && !fs::exists(branch_start_checkpoint(request.out, main_scenario, branch))) {
    outcome.failure = fmt::format("not run: the main run did not reach the end of stage '{}'", outcome.from);
    spdlog::error("branch '{}' {}", branch.name, outcome.failure);
  } else {
    runnable = true;
  }
  return run;
}

BranchRun run_branch(const Request& request, const scenario::Scenario& main_scenario, std::size_t b,
                     const BranchStart& start, int steps_left) {
  bool runnable = false;
  BranchRun run = settled_branch(request, main_scenario, b, start, runnable);
  if (!runnable) return run;
  const scenario::BranchSpec& branch = main_scenario.branches[b];
  output::BranchOutcome& outcome = run.outcome;
  const fs::path from =
      start.own ? start.own->path : branch_start_checkpoint(request.out, main_scenario, branch);
  simulation::Simulation branch_sim(scenario::branch_scenario(main_scenario, b));
  simulation::SimulationState state = persistence::read_checkpoint(from, branch_sim.scenario());
  if (!start.own && (state.progress.stage != branch.from + 1 || state.progress.stage_begun))
    throw std::runtime_error(
        fmt::format("'{}' does not hold the state at the end of stage '{}'", from.string(), outcome.from));
  parallel::barrier();  // every rank has read its start before rank 0 writes the branch's files
  spdlog::info("branch '{}': {} {}", branch.name, start.own ? "resuming from" : "starting from",
               from.string());
  branch_sim.restore(std::move(state),
                     start.own ? simulation::StartKind::resumed : simulation::StartKind::branched);
  std::optional<RunOutputs> branch_outputs;  // rank 0 alone writes, under MPI
  if (parallel::is_root())
    branch_outputs.emplace(
        branch_dir(request.out, branch), branch_sim.scenario(), request.quiet, true,
        "branch " + branch.name + ": ",
        request.timing_from.empty() ? fs::path() : branch_dir(request.timing_from, branch) / "timing.csv");
  simulation::RunOptions options;
  options.stop_after_steps = steps_left;
  options.cancel = request.cancel;
  const simulation::RunSummary summary =
      branch_sim.run(branch_outputs ? branch_outputs->observers() : no_observers(), options);
  run.new_steps = summary.new_steps;
  if (summary.interrupted) {
    run.interrupted = true;
    run.cancelled = summary.cancelled;
    if (summary.cancelled && branch_outputs) branch_outputs->save_stopped(branch_sim);
    log_stopped_as_asked(request, branch_sim, summary.cancelled);
    return run;
  }
  outcome.converged = summary.converged;
  outcome.failure = summary.failure;
  outcome.steps = summary.steps;
  outcome.final_time = branch_sim.time();
  spdlog::info("branch '{}': {} steps, {} Newton iterations, {:.2f} s; results in {}", branch.name,
               summary.steps, summary.newton_iterations, summary.wall_seconds,
               branch_dir(request.out, branch).string());
  if (!summary.converged)
    spdlog::error("branch '{}' stopped: {}; its last converged state is kept in {}", branch.name,
                  summary.failure, branch_dir(request.out, branch).string());
  return run;
}

Outcome run_one_branch(const Request& request, const scenario::Scenario& main_scenario) {
  const auto& branches = main_scenario.branches;
  const auto found = std::find_if(branches.begin(), branches.end(),
                                  [&](const scenario::BranchSpec& b) { return b.name == request.branch; });
  if (found == branches.end()) {
    std::string names;
    for (const scenario::BranchSpec& b : branches) names += (names.empty() ? "" : " | ") + b.name;
    throw scenario::ScenarioError(
        fmt::format("{}: --branch: expected the name of a branch of the scenario ({}), got {}",
                    request.scenario_path, names.empty() ? "it has none" : names, request.branch));
  }
  const auto b = static_cast<std::size_t>(found - branches.begin());
  const fs::path dir = branch_dir(request.out, *found);
  // A branch run by hand takes the run's folder as a run does; one that a run started (NODUS_RUN_PARENT, its
  // parent) writes under the folder its run holds.
  const char* parent = std::getenv("NODUS_RUN_PARENT");
  const bool started_by_run = parent != nullptr && std::atol(parent) == static_cast<long>(getppid());
  std::optional<output::FolderLock> lock;
  if (!started_by_run && fs::is_directory(request.out)) lock_output_folder(request.out, lock);
  if (parallel::is_root()) output::remove_stale_temporary_files(dir);  // left by a killed run
  BranchStart start;
  if (request.resume) {
    start.finished = fs::exists(dir / "summary.json");
    if (!start.finished)
      start.own = persistence::newest_intact_checkpoint(dir / "checkpoints",
                                                        scenario::branch_scenario(main_scenario, b));
  } else if (parallel::is_root()) {
    fs::remove(dir / "summary.json");
    persistence::remove_checkpoints(dir / "checkpoints");
  }
  parallel::barrier();  // every rank has looked before rank 0 writes
  const BranchRun run = run_branch(request, main_scenario, b, start, request.stop_after_steps);
  Outcome outcome;
  outcome.interrupted = run.interrupted;
  outcome.cancelled = run.cancelled;
  outcome.converged = !run.interrupted && run.outcome.converged;
  return outcome;
}

bool run_branch_processes(const Request& request, const scenario::Scenario& main_scenario,
                          const std::vector<std::size_t>& todo, const std::vector<BranchStart>& starts,
                          std::size_t jobs, std::vector<BranchRun>& runs) {
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  const auto finish = [&](pid_t pid, int status) {
    const std::size_t b = running.at(pid);
    running.erase(pid);
    const scenario::BranchSpec& branch = main_scenario.branches[b];
    output::BranchOutcome& outcome = runs[b].outcome;
    const fs::path summary = branch_dir(request.out, branch) / "summary.json";
    if (fs::exists(summary)) {
      read_finished(summary, outcome);
    } else {
      outcome.failure = WIFEXITED(status)
                            ? fmt::format("its process exited with status {}", WEXITSTATUS(status))
                            : fmt::format("its process was killed by signal {}", WTERMSIG(status));
      spdlog::error("branch '{}': {}", branch.name, outcome.failure);
    }
  };
  while (next < todo.size() || !running.empty()) {
    if (request.cancel && request.cancel()) {
      for (const auto& [pid, b] : running) kill(pid, SIGTERM);
      for (const auto& [pid, b] : running) {
        int status = 0;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
      }
      return false;
    }
    if (next < todo.size() && running.size() < jobs) {
      const std::size_t b = todo[next++];
      std::vector<std::string> args = {"nodus",
                                       "run",
                                       request.scenario_path,
                                       "--out",
                                       request.out.string(),
                                       "--branch",
                                       main_scenario.branches[b].name,
                                       "--jobs",
                                       "1"};
      if (starts[b].own) args.emplace_back("--resume");
      if (request.quiet) args.emplace_back("--quiet");
      if (request.verbose) args.emplace_back("--verbose");
      if (!request.timing_from.empty()) {
        args.emplace_back("--timing-from");
        args.push_back(request.timing_from.string());
      }
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      // A process of its own, not a rank of this one's MPI job (this one may have started MPI as a
      // singleton).
      std::vector<std::string> environment = parallel::environment_for_another_program();
      // The branch process takes the stop this run forwards to it as the first, not a second, signal.
      std::erase_if(environment, [](const std::string& e) { return e.starts_with("NODUS_RUN_PARENT="); });
      environment.push_back(fmt::format("NODUS_RUN_PARENT={}", getpid()));
      std::vector<char*> envp;
      for (std::string& e : environment) envp.push_back(e.data());
      envp.push_back(nullptr);
      pid_t pid = 0;
      const int error =
          posix_spawn(&pid, request.branch_executable.c_str(), nullptr, nullptr, argv.data(), envp.data());
      if (error != 0)
        throw std::runtime_error(fmt::format("could not start the process of branch '{}': {}",
                                             main_scenario.branches[b].name, std::strerror(error)));
      running[pid] = b;
      continue;
    }
    // Only our own children are waited for (a library caller may have others): each is polled, then a short
    // sleep; branches last seconds to hours.
    bool reaped = false;
    for (auto it = running.begin(); it != running.end() && !reaped; ++it) {
      int status = 0;
      const pid_t pid = waitpid(it->first, &status, WNOHANG);
      if (pid < 0 && errno == EINTR) break;
      if (pid < 0)
        throw std::runtime_error(fmt::format("waiting for the branch processes: {}", std::strerror(errno)));
      if (pid == it->first) {
        finish(pid, status);
        reaped = true;
      }
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

}  // namespace nodus::run
