// nodus: quasi-static equilibrium of elastic beam assemblies under large deformations.
//
//   nodus run SCENARIO.yaml --out DIR     run a scenario, write results into DIR
//   nodus check SCENARIO.yaml             validate a scenario and print the resolved settings
//   nodus keys                            print the table of scenario keys (markdown)
//
// Exit status: 0 success, 1 internal error, 2 bad input (nothing written), 3 the run stopped without
// converging (the converged steps are kept in DIR).

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/final_nodes_writer.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/output/progress_reporter.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/output/vtk_writer.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace {

constexpr int kBadInput = 2;
constexpr int kNotConverged = 3;

int run(const std::string& scenario_path, const std::filesystem::path& out, bool quiet) {
  nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(scenario_path);
  if (!quiet)
    spdlog::info("scenario {} resolved as:\n{}", scenario_path, nodus::scenario::describe(scenario));
  // Building the model validates what the reader cannot (e.g. a condition that would over-constrain a node);
  // it happens before anything is written.
  nodus::simulation::Simulation sim(std::move(scenario));
  std::filesystem::create_directories(out);

  nodus::output::StepsCsvWriter steps(out);
  nodus::output::VtkSeriesWriter vtk(out, sim.scenario().output.vtk_every, sim.scenario().output.tube_sides);
  nodus::output::FinalNodesWriter final_nodes(out);
  nodus::output::ContactCsvWriter contact_tables(out);
  nodus::output::SummaryWriter summary_writer(out);
  nodus::output::ProgressReporter progress(sim.scenario().output.progress_seconds);
  std::vector<nodus::simulation::StepObserver*> observers{&steps, &vtk, &final_nodes, &contact_tables,
                                                          &summary_writer};
  if (!quiet) observers.push_back(&progress);
  const nodus::simulation::RunSummary summary = sim.run(observers);

  spdlog::info("{} steps, {} Newton iterations, {:.2f} s; results in {}", summary.steps,
               summary.newton_iterations, summary.wall_seconds, out.string());
  if (!summary.converged) {
    spdlog::error("run stopped: {}; the last converged state (load time {:.6g} s) is kept in {}",
                  summary.failure, sim.time(), out.string());
    return kNotConverged;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  nodus::output::use_stderr_logger();
  CLI::App app{"nodus: contact-friction mechanics of elastic beam assemblies (units: mm, N, MPa, s)"};
  app.require_subcommand(1);
  std::string scenario_path;
  std::filesystem::path out;
  bool quiet = false;
  bool verbose = false;

  CLI::App* run_cmd = app.add_subcommand("run", "run a scenario and write its results");
  run_cmd->add_option("scenario", scenario_path, "scenario file (YAML)")->required();
  run_cmd->add_option("--out,-o", out, "output directory (created if missing)")->required();
  run_cmd->add_flag("--quiet,-q", quiet, "no settings echo and no progress lines");
  run_cmd->add_flag("--verbose,-v", verbose, "log every Newton iteration");

  CLI::App* check_cmd = app.add_subcommand("check", "validate a scenario and print the resolved settings");
  check_cmd->add_option("scenario", scenario_path, "scenario file (YAML)")->required();

  app.add_subcommand("keys", "print the table of scenario keys (markdown)");

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
    if (app.got_subcommand("check")) {
      const nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(scenario_path);
      nodus::simulation::Simulation sim(scenario);
      std::fputs(nodus::scenario::describe(scenario).c_str(), stdout);
      return 0;
    }
    return run(scenario_path, out, quiet);
  } catch (const nodus::scenario::ScenarioError& e) {
    std::fprintf(stderr, "nodus: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nodus: error: %s\n", e.what());
    return 1;
  }
}
