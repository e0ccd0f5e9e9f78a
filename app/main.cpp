// nodus: quasi-static equilibrium of elastic beam assemblies under large deformations.
//
//   nodus run SCENARIO.yaml --out DIR     run a scenario, write results into DIR (its branches side by side,
//                                         --jobs at a time)
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
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "nodus/analysis/knot.hpp"
#include "nodus/output/checkpoint.hpp"
#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/final_nodes_table.hpp"
#include "nodus/output/final_nodes_writer.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/output/progress_reporter.hpp"
#include "nodus/output/stage_end_writer.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/output/vtk_writer.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

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
      "run stopped after {} converged steps, as asked (--stop-after-steps), at load time {:.6g} s; continue "
      "it "
      "with --resume",
      request.stop_after_steps, sim.time());
}

/// What became of one branch.
struct BranchRun {
  nodus::output::BranchOutcome outcome;
  bool interrupted = false;  ///< stopped by --stop-after-steps
  int new_steps = 0;         ///< steps computed here (not read back from a checkpoint)
};

/// Runs branch `b` of `main_scenario` into DIR/branches/NAME from where `start` says, or reads back its
/// outcome if it had finished. `steps_left` > 0 stops it, as if killed, after that many converged steps.
/// Branches share nothing but the main run's checkpoint they read, so several may run at once.
BranchRun run_branch(const RunRequest& request, const nodus::scenario::Scenario& main_scenario, std::size_t b,
                     const BranchStart& start, int steps_left) {
  const nodus::scenario::BranchSpec& branch = main_scenario.branches[b];
  nodus::scenario::Scenario branch_scenario = nodus::scenario::branch_scenario(main_scenario, b);
  const fs::path dir = request.out / "branches" / branch.name;
  BranchRun run;
  nodus::output::BranchOutcome& outcome = run.outcome;
  outcome.name = branch.name;
  outcome.from = main_scenario.stages.at(static_cast<std::size_t>(branch.from)).name;
  outcome.friction = branch_scenario.contact.friction;
  outcome.folder = "branches/" + branch.name;
  if (start.finished) {
    const nodus::output::SummaryData done = nodus::output::read_summary(dir / "summary.json");
    outcome.converged = done.converged;
    outcome.failure = done.failure;
    outcome.steps = done.steps;
    outcome.final_time = done.final_time;
    return run;
  }
  const fs::path from =
      start.own ? start.own->path : branch_start_checkpoint(request.out, main_scenario, branch);
  if (!fs::exists(from)) {
    outcome.failure = fmt::format("not run: the main run did not reach the end of stage '{}'", outcome.from);
    spdlog::error("branch '{}' {}", branch.name, outcome.failure);
    return run;
  }
  nodus::simulation::Simulation branch_sim(std::move(branch_scenario));
  nodus::simulation::SimulationState state = nodus::output::read_checkpoint(from, branch_sim.scenario());
  if (!start.own && (state.progress.stage != branch.from + 1 || state.progress.stage_begun))
    throw std::runtime_error(
        fmt::format("'{}' does not hold the state at the end of stage '{}'", from.string(), outcome.from));
  spdlog::info("branch '{}': {} {}", branch.name, start.own ? "resuming from" : "starting from",
               from.string());
  branch_sim.restore(std::move(state), start.own ? nodus::simulation::StartKind::resumed
                                                 : nodus::simulation::StartKind::branched);
  RunOutputs branch_outputs(dir, branch_sim.scenario(), request.quiet, true, "branch " + branch.name + ": ");
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
               summary.steps, summary.newton_iterations, summary.wall_seconds, dir.string());
  if (!summary.converged)
    spdlog::error("branch '{}' stopped: {}; its last converged state is kept in {}", branch.name,
                  summary.failure, dir.string());
  return run;
}

int run(const RunRequest& request) {
  nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(request.scenario_path);
  if (!request.quiet)
    spdlog::info("scenario {} resolved as:\n{}", request.scenario_path, nodus::scenario::describe(scenario));
  // Building the model validates what the reader cannot (e.g. a condition that would over-constrain a node,
  // in the stages or in a branch); it happens before anything is written.
  nodus::simulation::Simulation sim(std::move(scenario));
  const nodus::scenario::Scenario& main_scenario = sim.scenario();
  const fs::path& out = request.out;
  const auto branch_dir = [&](const nodus::scenario::BranchSpec& b) { return out / "branches" / b.name; };

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
      start.finished = fs::exists(branch_dir(branch) / "summary.json");
      if (start.finished) continue;
      start.own = nodus::output::newest_checkpoint(branch_dir(branch) / "checkpoints");
      const fs::path from = start.own ? start.own->path : branch_start_checkpoint(out, main_scenario, branch);
      if (fs::exists(from)) nodus::output::read_checkpoint(from, branch_scenario);  // checks it
    }
  }

  // From here on, files are written.
  fs::create_directories(out);
  if (resumed) {
    sim.restore(std::move(*resumed), nodus::simulation::StartKind::resumed);
  } else {
    // Branch results of an earlier run must not pass for finished or resumable ones.
    for (const nodus::scenario::BranchSpec& branch : main_scenario.branches) {
      fs::remove(branch_dir(branch) / "summary.json");
      nodus::output::remove_checkpoints(branch_dir(branch) / "checkpoints");
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

  // The branches, side by side on up to `jobs` threads; one at a time when a step count is to stop the run.
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
    spdlog::info("{} branches, {} at a time", count, jobs);
    std::atomic<std::size_t> next{0};
    std::vector<std::exception_ptr> errors(count);
    const auto work = [&] {
      for (std::size_t b = next++; b < count; b = next++) {
        try {
          runs[b] = run_branch(request, main_scenario, b, branch_starts[b], 0);
        } catch (...) {
          errors[b] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> threads;
    for (std::size_t j = 0; j < jobs; ++j) threads.emplace_back(work);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
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
  run_cmd->add_flag("--resume", request.resume,
                    "continue the interrupted run in the output directory from its newest checkpoint");
  request.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run_cmd
      ->add_option("--jobs,-j", request.jobs,
                   "branches run side by side, at most (default: the number of hardware threads); each is "
                   "computed as it would be alone, so the results do not depend on it")
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
