// nodus: quasi-static equilibrium of elastic beam assemblies under large deformations.
//
//   nodus run SCENARIO.yaml --out DIR     run a scenario, write results into DIR (its branches side by side,
//                                         --jobs at a time, each in a process of its own: nodus run --branch)
//   nodus run SCENARIO.yaml --out DIR --resume
//                                         continue an interrupted run from its newest checkpoint in DIR
//   nodus check SCENARIO.yaml             validate a scenario and print the resolved settings
//   nodus keys                            print the table of scenario keys (markdown)
//   nodus knot NODES.csv                  knot type and smallest self-distance of a beam in a nodal table
//
// Exit status: 0 success, 1 internal error, 2 bad input (nothing written; also a checkpoint of another
// scenario, and --resume without a checkpoint), 3 the run (or a branch) stopped without converging (the
// converged steps are kept in DIR) or was stopped by --stop-after-steps.

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "nodus/analysis/knot.hpp"
#include "nodus/output/checkpoint.hpp"
#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/final_nodes_table.hpp"
#include "nodus/output/final_nodes_writer.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/output/output_folder.hpp"
#include "nodus/output/progress_reporter.hpp"
#include "nodus/output/stage_end_writer.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/output/vtk_writer.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

constexpr int kBadInput = 2;
constexpr int kNotConverged = 3;

/// What `nodus run` was asked to do.
struct RunRequest {
  std::string scenario_path;
  fs::path out;
  bool quiet = false;
  bool resume = false;
  int stop_after_steps = 0;  ///< for tests: stop as if killed after this many converged steps (0: never)
  int jobs = 1;              ///< branches run side by side, at most
  std::string branch;        ///< --branch: run only this branch (the main run has reached its `from` stage)
  bool verbose = false;
};

/// The output writers of one run (the main run, or a branch) into `dir`.
class RunOutputs {
 public:
  RunOutputs(const fs::path& dir, const nodus::scenario::Scenario& scenario, bool quiet, bool write_summary,
             std::string label = {})
      : steps_(dir),
        vtk_(dir, scenario.output.vtk_every, scenario.output.tube_sides),
        final_nodes_(dir),
        contact_tables_(dir),
        stage_ends_(dir),
        summary_(dir, write_summary),
        checkpoints_(dir, scenario.output.checkpoint_every),
        progress_(scenario.output.progress_seconds, std::move(label)) {
    // The checkpoint comes after the files of its step, so that they are complete up to it.
    observers_ = {&steps_, &vtk_, &final_nodes_, &contact_tables_, &stage_ends_, &summary_, &checkpoints_};
    if (!quiet) observers_.push_back(&progress_);
  }
  const std::vector<nodus::simulation::StepObserver*>& observers() const { return observers_; }
  const nodus::output::SummaryWriter& summary() const { return summary_; }

 private:
  nodus::output::StepsCsvWriter steps_;
  nodus::output::VtkSeriesWriter vtk_;
  nodus::output::FinalNodesWriter final_nodes_;
  nodus::output::ContactCsvWriter contact_tables_;
  nodus::output::StageEndWriter stage_ends_;
  nodus::output::SummaryWriter summary_;
  nodus::output::CheckpointWriter checkpoints_;
  nodus::output::ProgressReporter progress_;
  std::vector<nodus::simulation::StepObserver*> observers_;
};

std::string describe_position(const nodus::output::CheckpointInfo& info,
                              const nodus::scenario::Scenario& scenario) {
  const auto& stages = scenario.stages;
  const std::string where =
      info.stage_begun
          ? fmt::format("inside stage '{}'", stages.at(static_cast<std::size_t>(info.stage)).name)
      : info.stage == 0
          ? std::string("at the start")
          : fmt::format("at the end of stage '{}'", stages.at(static_cast<std::size_t>(info.stage - 1)).name);
  return fmt::format("step {}, load time {:.6g} s, {}", info.steps, info.time, where);
}

/// The checkpoint a branch starts from: the main run's at the end of its `from` stage.
fs::path branch_start_checkpoint(const fs::path& out, const nodus::scenario::Scenario& scenario,
                                 const nodus::scenario::BranchSpec& branch) {
  return out / "checkpoints" /
         nodus::output::checkpoint_file_name(branch.from,
                                             scenario.stages.at(static_cast<std::size_t>(branch.from)).name);
}

/// Where a branch starts when the run resumes: finished (its summary.json exists), from its own newest
/// checkpoint, or from the main run's checkpoint of its `from` stage.
struct BranchStart {
  bool finished = false;
  std::optional<nodus::output::CheckpointInfo> own;  ///< its newest checkpoint, when it has one
};

/// The message of a run stopped by --stop-after-steps.
void stopped_as_asked(const RunRequest& request, const nodus::simulation::Simulation& sim) {
  spdlog::error(
      "run stopped after {} converged steps, as asked (--stop-after-steps), at load time {:.6g} s; "
      "continue it with --resume",
      request.stop_after_steps, sim.time());
}

/// What became of one branch.
struct BranchRun {
  nodus::output::BranchOutcome outcome;
  bool interrupted = false;  ///< stopped by --stop-after-steps
  int new_steps = 0;         ///< steps computed here (not read back from a checkpoint)
};

fs::path branch_dir(const RunRequest& request, const nodus::scenario::BranchSpec& branch) {
  return request.out / "branches" / branch.name;
}

/// How a finished branch ended, from its summary.json.
void read_finished(const fs::path& summary, nodus::output::BranchOutcome& outcome) {
  const nodus::output::SummaryData done = nodus::output::read_summary(summary);
  outcome.converged = done.converged;
  outcome.failure = done.failure;
  outcome.steps = done.steps;
  outcome.final_time = done.final_time;
}

/// Branch `b`'s outcome as far as it is known without running it: its name, start and friction; if it has
/// finished (its summary.json exists), how it ended; if its start checkpoint is missing (the main run did not
/// reach its `from` stage), why it is not run. `runnable` says whether it is left to run.
BranchRun settled_branch(const RunRequest& request, const nodus::scenario::Scenario& main_scenario,
                         std::size_t b, const BranchStart& start, bool& runnable) {
  const nodus::scenario::BranchSpec& branch = main_scenario.branches[b];
  BranchRun run;
  nodus::output::BranchOutcome& outcome = run.outcome;
  outcome.name = branch.name;
  outcome.from = main_scenario.stages.at(static_cast<std::size_t>(branch.from)).name;
  outcome.friction = nodus::scenario::branch_scenario(main_scenario, b).contact.friction;
  outcome.folder = "branches/" + branch.name;
  runnable = false;
  if (start.finished) {
    read_finished(branch_dir(request, branch) / "summary.json", outcome);
  } else if (!start.own && !fs::exists(branch_start_checkpoint(request.out, main_scenario, branch))) {
    outcome.failure = fmt::format("not run: the main run did not reach the end of stage '{}'", outcome.from);
    spdlog::error("branch '{}' {}", branch.name, outcome.failure);
  } else {
    runnable = true;
  }
  return run;
}

/// Runs branch `b` of `main_scenario` into DIR/branches/NAME from where `start` says, or reads back its
/// outcome if it had finished. `steps_left` > 0 stops it, as if killed, after that many converged steps.
BranchRun run_branch(const RunRequest& request, const nodus::scenario::Scenario& main_scenario, std::size_t b,
                     const BranchStart& start, int steps_left) {
  bool runnable = false;
  BranchRun run = settled_branch(request, main_scenario, b, start, runnable);
  if (!runnable) return run;
  const nodus::scenario::BranchSpec& branch = main_scenario.branches[b];
  nodus::output::BranchOutcome& outcome = run.outcome;
  const fs::path from =
      start.own ? start.own->path : branch_start_checkpoint(request.out, main_scenario, branch);
  nodus::simulation::Simulation branch_sim(nodus::scenario::branch_scenario(main_scenario, b));
  nodus::simulation::SimulationState state = nodus::output::read_checkpoint(from, branch_sim.scenario());
  if (!start.own && (state.progress.stage != branch.from + 1 || state.progress.stage_begun))
    throw std::runtime_error(
        fmt::format("'{}' does not hold the state at the end of stage '{}'", from.string(), outcome.from));
  spdlog::info("branch '{}': {} {}", branch.name, start.own ? "resuming from" : "starting from",
               from.string());
  branch_sim.restore(std::move(state), start.own ? nodus::simulation::StartKind::resumed
                                                 : nodus::simulation::StartKind::branched);
  RunOutputs branch_outputs(branch_dir(request, branch), branch_sim.scenario(), request.quiet, true,
                            "branch " + branch.name + ": ");
  const nodus::simulation::RunSummary summary = branch_sim.run(branch_outputs.observers(), {steps_left});
  run.new_steps = summary.new_steps;
  if (summary.interrupted) {
    run.interrupted = true;
    stopped_as_asked(request, branch_sim);
    return run;
  }
  outcome.converged = summary.converged;
  outcome.failure = summary.failure;
  outcome.steps = summary.steps;
  outcome.final_time = branch_sim.time();
  spdlog::info("branch '{}': {} steps, {} Newton iterations, {:.2f} s; results in {}", branch.name,
               summary.steps, summary.newton_iterations, summary.wall_seconds,
               branch_dir(request, branch).string());
  if (!summary.converged)
    spdlog::error("branch '{}' stopped: {}; its last converged state is kept in {}", branch.name,
                  summary.failure, branch_dir(request, branch).string());
  return run;
}

/// `nodus run --branch NAME`: only that branch, from the main run's checkpoint at the end of its `from` stage
/// (with --resume: from its own newest checkpoint, or nothing if it has finished). Exit status as for a run.
int run_one_branch(const RunRequest& request, const nodus::scenario::Scenario& main_scenario) {
  const auto& branches = main_scenario.branches;
  const auto found =
      std::find_if(branches.begin(), branches.end(),
                   [&](const nodus::scenario::BranchSpec& b) { return b.name == request.branch; });
  if (found == branches.end()) {
    std::string names;
    for (const nodus::scenario::BranchSpec& b : branches) names += (names.empty() ? "" : " | ") + b.name;
    throw nodus::scenario::ScenarioError(
        fmt::format("{}: --branch: expected the name of a branch of the scenario ({}), got {}",
                    request.scenario_path, names.empty() ? "it has none" : names, request.branch));
  }
  const auto b = static_cast<std::size_t>(found - branches.begin());
  const fs::path dir = branch_dir(request, *found);
  nodus::output::remove_stale_temporary_files(dir);  // left by a killed run
  BranchStart start;
  if (request.resume) {
    start.finished = fs::exists(dir / "summary.json");
    if (!start.finished) start.own = nodus::output::newest_checkpoint(dir / "checkpoints");
  } else {
    fs::remove(dir / "summary.json");
    nodus::output::remove_checkpoints(dir / "checkpoints");
  }
  const BranchRun run = run_branch(request, main_scenario, b, start, request.stop_after_steps);
  return !run.interrupted && run.outcome.converged ? 0 : kNotConverged;
}

/// Runs the branches listed in `todo` side by side, each in its own process (`nodus run --branch NAME`), at
/// most `jobs` at a time, and fills in their outcomes from the summary.json each writes. A process of its own
/// computes a branch exactly as the main process would after the main run, whatever runs beside it; threads
/// would not (the sparse solvers' round-off depends on how the memory of concurrent threads is laid out).
void run_branch_processes(const RunRequest& request, const nodus::scenario::Scenario& main_scenario,
                          const std::vector<std::size_t>& todo, const std::vector<BranchStart>& starts,
                          std::size_t jobs, std::vector<BranchRun>& runs) {
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  const auto finish = [&](pid_t pid, int status) {
    const std::size_t b = running.at(pid);
    running.erase(pid);
    const nodus::scenario::BranchSpec& branch = main_scenario.branches[b];
    nodus::output::BranchOutcome& outcome = runs[b].outcome;
    const fs::path summary = branch_dir(request, branch) / "summary.json";
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
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      pid_t pid = 0;
      const int error = posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ);
      if (error != 0)
        throw std::runtime_error(fmt::format("could not start the process of branch '{}': {}",
                                             main_scenario.branches[b].name, std::strerror(error)));
      running[pid] = b;
      continue;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0)
      throw std::runtime_error(fmt::format("waiting for the branch processes: {}", std::strerror(errno)));
    if (running.count(pid)) finish(pid, status);
  }
}

int run(const RunRequest& request) {
  nodus::output::check_output_folder(request.out);
  nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(request.scenario_path);
  if (!request.quiet && request.branch.empty())
    spdlog::info("scenario {} resolved as:\n{}", request.scenario_path, nodus::scenario::describe(scenario));
  // Building the model validates what the reader cannot (e.g. a condition that would over-constrain a node,
  // in the stages or in a branch); it happens before anything is written.
  nodus::simulation::Simulation sim(std::move(scenario));
  const nodus::scenario::Scenario& main_scenario = sim.scenario();
  const fs::path& out = request.out;
  if (!request.branch.empty()) return run_one_branch(request, main_scenario);

  // With --resume, everything that is read back is read and checked before anything is written.
  std::optional<nodus::simulation::SimulationState> resumed;
  std::vector<BranchStart> branch_starts(main_scenario.branches.size());
  if (request.resume) {
    if (fs::exists(out / "summary.json")) {
      const nodus::output::SummaryData done = nodus::output::read_summary(out / "summary.json");
      spdlog::info("the run in {} is already complete ({}); nothing to resume", out.string(),
                   done.converged ? "converged" : "stopped: " + done.failure);
      return done.converged ? 0 : kNotConverged;
    }
    const auto newest = nodus::output::newest_checkpoint(out / "checkpoints");
    if (!newest)
      throw nodus::scenario::ScenarioError(fmt::format(
          "{}: --resume: expected a checkpoint (*.nodus-state) in {}, got none: nothing to resume "
          "(run without --resume to start the run)",
          out.string(), (out / "checkpoints").string()));
    resumed = nodus::output::read_checkpoint(newest->path, main_scenario);
    spdlog::info("resuming from {} ({})", newest->path.string(), describe_position(*newest, main_scenario));
    for (std::size_t b = 0; b < main_scenario.branches.size(); ++b) {
      const nodus::scenario::BranchSpec& branch = main_scenario.branches[b];
      const nodus::scenario::Scenario branch_scenario = nodus::scenario::branch_scenario(main_scenario, b);
      BranchStart& start = branch_starts[b];
      start.finished = fs::exists(branch_dir(request, branch) / "summary.json");
      if (start.finished) continue;
      start.own = nodus::output::newest_checkpoint(branch_dir(request, branch) / "checkpoints");
      const fs::path from = start.own ? start.own->path : branch_start_checkpoint(out, main_scenario, branch);
      if (fs::exists(from)) nodus::output::read_checkpoint(from, branch_scenario);  // checks it
    }
  }

  // From here on, files are written.
  fs::create_directories(out);
  nodus::output::remove_stale_temporary_files(out);  // left by a killed run
  if (resumed) {
    sim.restore(std::move(*resumed), nodus::simulation::StartKind::resumed);
  } else {
    // Branch results of an earlier run must not pass for finished or resumable ones.
    for (const nodus::scenario::BranchSpec& branch : main_scenario.branches) {
      fs::remove(branch_dir(request, branch) / "summary.json");
      nodus::output::remove_checkpoints(branch_dir(request, branch) / "checkpoints");
    }
  }
  int steps_left = request.stop_after_steps;

  RunOutputs outputs(out, main_scenario, request.quiet, main_scenario.branches.empty());
  const nodus::simulation::RunSummary summary = sim.run(outputs.observers(), {steps_left});
  if (summary.interrupted) {
    stopped_as_asked(request, sim);
    return kNotConverged;
  }
  if (steps_left > 0) steps_left -= summary.new_steps;
  spdlog::info("{} steps, {} Newton iterations, {:.2f} s; results in {}", summary.steps,
               summary.newton_iterations, summary.wall_seconds, out.string());
  bool all_converged = summary.converged;
  if (!summary.converged)
    spdlog::error("run stopped: {}; the last converged state (load time {:.6g} s) is kept in {}",
                  summary.failure, sim.time(), out.string());

  if (main_scenario.branches.empty()) return all_converged ? 0 : kNotConverged;

  // The branches, side by side in up to `jobs` processes; one at a time, in this process, when a step count
  // is to stop the run.
  const std::size_t count = main_scenario.branches.size();
  const std::size_t jobs =
      request.stop_after_steps > 0 ? 1 : std::min(count, static_cast<std::size_t>(request.jobs));
  std::vector<BranchRun> runs(count);
  if (jobs <= 1) {
    for (std::size_t b = 0; b < count; ++b) {
      runs[b] = run_branch(request, main_scenario, b, branch_starts[b], steps_left);
      if (runs[b].interrupted) return kNotConverged;
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
    run_branch_processes(request, main_scenario, todo, branch_starts, jobs, runs);
  }
  std::vector<nodus::output::BranchOutcome> outcomes;
  for (BranchRun& r : runs) {
    all_converged = all_converged && r.outcome.converged;
    outcomes.push_back(std::move(r.outcome));
  }
  // The main run's summary, written last: it lists the branches and marks the whole run as finished.
  nodus::output::SummaryData data = *outputs.summary().data();
  data.branches = std::move(outcomes);
  nodus::output::write_summary(out / "summary.json", data);
  return all_converged ? 0 : kNotConverged;
}

/// `nodus knot`: the knot type and the smallest self-distance of a beam's centreline in a nodal table.
int knot(const std::string& path, const std::string& beam, double separation) {
  const nodus::output::TableCurve c = nodus::output::read_table_curve(path, beam);
  const nodus::analysis::KnotInvariant k = nodus::analysis::knot_invariant(c.points);
  const nodus::analysis::SelfDistance d = nodus::analysis::min_self_distance(c.points, c.s, separation);
  const std::string name = k.is_unknot() ? "unknot" : k.is_trefoil() ? "trefoil" : "another knot";
  std::printf("%s: beam %s, %zu nodes\n", path.c_str(), c.beam.c_str(), c.points.size());
  std::printf("knot: Alexander polynomial %s (%s; determinant %lld; %d crossings in the projection used)\n",
              k.to_string().c_str(), name.c_str(), static_cast<long long>(k.determinant()), k.crossings);
  if (std::isfinite(d.distance))
    std::printf(
        "smallest distance %.6f mm, between s = %.4f and %.4f mm (points at least %g mm apart along "
        "the beam; node polyline)\n",
        d.distance, d.s1, d.s2, separation);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  nodus::output::use_stderr_logger();
  CLI::App app{"nodus: contact-friction mechanics of elastic beam assemblies (units: mm, N, MPa, s)"};
  app.require_subcommand(1);
  RunRequest request;
  std::string& scenario_path = request.scenario_path;
  bool verbose = false;

  CLI::App* run_cmd = app.add_subcommand("run", "run a scenario and write its results");
  run_cmd->add_option("scenario", scenario_path, "scenario file (YAML)")->required();
  run_cmd->add_option("--out,-o", request.out, "output directory (created if missing)")->required();
  run_cmd->add_flag("--quiet,-q", request.quiet, "no settings echo and no progress lines");
  run_cmd->add_flag("--verbose,-v", verbose, "log every Newton iteration");
  run_cmd->add_option(
      "--branch", request.branch,
      "run only this branch, from the main run's checkpoint at the end of its `from` stage (with "
      "--resume: from its own newest checkpoint); the main stages must have been run");
  run_cmd->add_flag("--resume", request.resume,
                    "continue the interrupted run in the output directory from its newest checkpoint");
  request.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run_cmd
      ->add_option("--jobs,-j", request.jobs,
                   "branches run side by side, each in its own process, at most (default: the number of "
                   "hardware threads); the results do not depend on it")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  run_cmd
      ->add_option("--stop-after-steps", request.stop_after_steps,
                   "for testing: stop the run as if it were killed after N converged steps (after the "
                   "checkpoint then due), exit status 3; branches then run one at a time")
      ->check(CLI::PositiveNumber);

  CLI::App* check_cmd = app.add_subcommand("check", "validate a scenario and print the resolved settings");
  check_cmd->add_option("scenario", scenario_path, "scenario file (YAML)")->required();

  app.add_subcommand("keys", "print the table of scenario keys (markdown)");

  std::string nodes_path, knot_beam;
  double separation = 1.2;
  CLI::App* knot_cmd = app.add_subcommand(
      "knot",
      "knot type (Alexander polynomial, the curve closed far away) and smallest self-distance of a beam");
  knot_cmd->add_option("nodes", nodes_path, "nodal table (final_nodes.csv or stages/NNN_STAGE_nodes.csv)")
      ->required();
  knot_cmd->add_option("--beam", knot_beam, "beam name (default: the first beam of the table)");
  knot_cmd
      ->add_option("--separation", separation,
                   "smallest distance between points at least this far apart along the beam [mm]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }
  if (verbose) spdlog::set_level(spdlog::level::debug);
  request.verbose = verbose;

  try {
    if (app.got_subcommand("keys")) {
      std::fputs(nodus::scenario::scenario_keys_markdown().c_str(), stdout);
      return 0;
    }
    if (app.got_subcommand("knot")) {
      try {
        return knot(nodes_path, knot_beam, separation);
      } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "nodus: %s\n", e.what());
        return kBadInput;
      }
    }
    if (app.got_subcommand("check")) {
      const nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(scenario_path);
      nodus::simulation::Simulation sim(scenario);
      std::fputs(nodus::scenario::describe(scenario).c_str(), stdout);
      return 0;
    }
    return run(request);
  } catch (const nodus::scenario::ScenarioError& e) {
    std::fprintf(stderr, "nodus: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nodus: error: %s\n", e.what());
    return 1;
  }
}
