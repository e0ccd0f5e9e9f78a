// nodus: quasi-static equilibrium of elastic beam assemblies under large deformations.
//
//   nodus run SCENARIO.yaml --out DIR     run a scenario, write results into DIR (its branches side by side,
//                                         --jobs at a time, each in a process of its own: nodus run --branch)
//   nodus run SCENARIO.yaml --out DIR --resume
//                                         continue an interrupted run from its newest checkpoint in DIR
//   mpirun -n N nodus run SCENARIO.yaml --out DIR [-ksp_view ...]
//                                         the same on N MPI ranks (solver.linear_solver: petsc; PETSc's own
//                                         -ksp_*, -pc_*, -mat_*, -mg_*, -sub_* options go to PETSc;
//                                         docs/parallel.md)
//   nodus check SCENARIO.yaml             validate a scenario and print the resolved settings
//   nodus keys                            print the table of scenario keys (markdown)
//   nodus knot NODES.csv                  knot type and smallest self-distance of a beam in a nodal table
//                                         (--yarn NAME: of each fibre, of their mean and between fibres)
//   nodus view DIR [--out FILE.html]      one self-contained HTML page showing the run in DIR (result.h5)
//                                         and its branches in 3D (default DIR/view.html; docs/view.md)
//
// Exit status: 0 success, 1 internal error, 2 bad input (nothing written; also a checkpoint of another
// scenario, and --resume without a checkpoint), 3 the run (or a branch) stopped without converging (the
// converged steps are kept in DIR) or was stopped by --stop-after-steps, 4 an output file could not be
// written (the message names it and the system's reason; the run resumes once that is removed), 128 + the
// signal's number (143, 130) a run stopped by SIGTERM or SIGINT at the end of a Newton iteration, its last
// converged state saved as its newest checkpoint (a second signal ends it at once).

//
// The command line only parses and prints: a run is nodus::run::run (src/nodus/run/run.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>
#include <unistd.h>

#include <csignal>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "nodus/analysis/knot.hpp"
#include "nodus/output/atomic_file.hpp"
#include "nodus/output/final_nodes_table.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/output/result_h5.hpp"
#include "nodus/output/view_page.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/persistence/checkpoint_files.hpp"
#include "nodus/run/run.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "nodus/solver/blas_kernels.hpp"
#include "nodus/version.hpp"

namespace {

constexpr int kBadInput = 2;
constexpr int kNotConverged = 3;
constexpr int kWriteFailed = 4;

/// OpenMP threads that wait for work by spinning (libgomp's default, for nodus's parallel regions and the
/// OpenMP OpenBLAS under CHOLMOD alike) keep their cores busy between regions; when another process wants one
/// of those cores, both crawl: a 27-fibre factorisation took 12.0 s instead of 2.65 s (docs/performance.md).
/// libgomp reads OMP_WAIT_POLICY once, when it is loaded, before main(): so, unless the user has set it (to
/// anything), nodus sets it to PASSIVE and starts itself again. Returns whether it was set here. (Profilers
/// such as valgrind follow the exec only with --trace-children=yes: set OMP_WAIT_POLICY before them.)
bool prefer_passive_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return std::getenv("NODUS_SET_OMP_WAIT_POLICY") != nullptr;
  if (::setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0 || ::setenv("NODUS_SET_OMP_WAIT_POLICY", "1", 1) != 0)
    return false;
  ::execv("/proc/self/exe", argv);
  // Not reached unless the exec failed: libgomp keeps the policy it read at load, so say nothing was set.
  ::unsetenv("OMP_WAIT_POLICY");
  ::unsetenv("NODUS_SET_OMP_WAIT_POLICY");
  return false;
}

/// `nodus kernels`: OpenBLAS's kernels and the OPENBLAS_CORETYPE that would serve this processor better (it
/// is read when OpenBLAS is loaded, before main(), so only whoever starts nodus can set it:
/// scripts/example.sh does). `coretype_only`: that value alone, or an empty line.
std::string kernels_lines(bool coretype_only) {
  const nodus::solver::BlasKernels k = nodus::solver::blas_kernels();
  if (coretype_only) return k.better + "\n";
  if (k.loaded.empty()) return "the BLAS is not OpenBLAS: nothing to choose\n";
  if (k.better.empty()) return fmt::format("OpenBLAS kernels: {}\n", k.loaded);
  return fmt::format(
      "OpenBLAS kernels: {} (its generic ones); this processor can run its {} kernels: start nodus with "
      "OPENBLAS_CORETYPE={} (factorisations up to twice as fast, docs/performance.md)\n",
      k.loaded, k.better, k.better);
}

/// The knot type of `curve` as one line.
std::string knot_line(const std::vector<Eigen::Vector3d>& curve) {
  const nodus::analysis::KnotInvariant k = nodus::analysis::knot_invariant(curve);
  const std::string name = k.is_unknot() ? "unknot" : k.is_trefoil() ? "trefoil" : "another knot";
  return fmt::format("Alexander polynomial {} ({}; determinant {}; {} crossings in the projection used)",
                     k.to_string(), name, k.determinant(), k.crossings);
}

/// `nodus knot`: the knot type and the smallest self-distance of each beam's centreline in a nodal table;
/// for several beams (the fibres of a yarn) also the knot type of their mean centreline and the smallest
/// distance between each two of them.
int knot(const std::string& path, std::vector<std::string> beams, const std::string& yarn,
         double separation) {
  if (!yarn.empty()) {
    for (const std::string& name : nodus::output::read_table_beams(path))
      if (name.rfind(yarn + ".", 0) == 0) beams.push_back(name);
    if (beams.empty())
      throw std::invalid_argument(fmt::format(
          "{}: expected the fibres {}.rK.fJ of yarn {} in the table, got none", path, yarn, yarn));
  }
  if (beams.empty()) beams.push_back("");  // the first beam of the table
  std::vector<nodus::output::TableCurve> curves;
  for (const std::string& beam : beams) curves.push_back(nodus::output::read_table_curve(path, beam));
  for (const nodus::output::TableCurve& c : curves) {
    const nodus::analysis::SelfDistance d = nodus::analysis::min_self_distance(c.points, c.s, separation);
    std::printf("%s: beam %s, %zu nodes\n", path.c_str(), c.beam.c_str(), c.points.size());
    std::printf("knot: %s\n", knot_line(c.points).c_str());
    if (std::isfinite(d.distance))
      std::printf(
          "smallest distance %.6f mm, between s = %.4f and %.4f mm (points at least %g mm apart along "
          "the beam; node polyline)\n",
          d.distance, d.s1, d.s2, separation);
  }
  if (curves.size() < 2) return 0;
  std::vector<std::vector<Eigen::Vector3d>> points;
  for (const nodus::output::TableCurve& c : curves) {
    if (c.points.size() != curves.front().points.size())
      throw std::invalid_argument(fmt::format(
          "{}: expected beams of equal numbers of nodes (the fibres of a yarn), got {} and {} nodes", path,
          curves.front().points.size(), c.points.size()));
    points.push_back(c.points);
  }
  const std::vector<Eigen::Vector3d> mean = nodus::analysis::mean_curve(points);
  std::printf("mean centreline of the %zu beams: knot: %s\n", curves.size(), knot_line(mean).c_str());
  for (std::size_t i = 0; i < curves.size(); ++i)
    for (std::size_t j = i + 1; j < curves.size(); ++j) {
      const nodus::analysis::CurveDistance d =
          nodus::analysis::min_distance_between(curves[i].points, curves[i].s, curves[j].points, curves[j].s);
      std::printf("smallest distance %.6f mm between beams %s (s = %.4f mm) and %s (s = %.4f mm)\n",
                  d.distance, curves[i].beam.c_str(), d.s1, curves[j].beam.c_str(), d.s2);
    }
  return 0;
}

/// The signal, SIGTERM or SIGINT, that asked the run to stop; 0: none yet.
volatile std::sig_atomic_t stop_signal = 0;

/// In a branch process (NODUS_RUN_PARENT, set by the run that started it): the run's process id; else 0.
pid_t parent_run = 0;

/// The first SIGTERM or SIGINT asks the run to stop at the end of the Newton iteration under way; a second
/// one ends the process at once, by the signal, unless it comes from the run that started this branch
/// process: that run forwards its stop to its branch processes, which a Ctrl-C in a terminal or a batch
/// scheduler's SIGTERM reaches directly too.
extern "C" void on_stop_signal(int signal, siginfo_t* info, void*) {
  if (stop_signal == 0) {
    stop_signal = signal;
    return;
  }
  if (parent_run != 0 && info != nullptr && info->si_pid == parent_run) return;
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void catch_stop_signals() {
  if (const char* parent = std::getenv("NODUS_RUN_PARENT"))
    parent_run = static_cast<pid_t>(std::atol(parent));
  struct sigaction action = {};
  action.sa_sigaction = on_stop_signal;
  action.sa_flags = SA_SIGINFO | SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
}

/// Whether a stop signal has reached this process, or under MPI any rank (every rank asks at the same
/// Newton iteration, and all stop there).
bool stop_asked() {
  double asked = stop_signal != 0 ? 1.0 : 0.0;
  if (nodus::parallel::size() > 1) nodus::parallel::sum_over_ranks(&asked, 1);
  return asked > 0.0;
}

/// Prints a message on stderr, once: on rank 0 under MPI (every rank meets the same bad input).
void report(const std::string& message) {
  if (nodus::parallel::is_root()) std::fprintf(stderr, "nodus: %s\n", message.c_str());
}

/// `nodus view`: reads RUN_DIR/result.h5 (and its branches') and writes the page to `out` (default
/// RUN_DIR/view.html); says on stdout what it wrote. Status 2 for a folder without a readable result.h5 or a
/// nodus built without the page script, 4 where the page cannot be written.
int view(const std::filesystem::path& run_dir, std::filesystem::path out, double max_megabytes) {
  nodus::output::ViewOptions options;
  options.max_bytes = static_cast<std::uintmax_t>(max_megabytes * 1e6);
  std::filesystem::path name = run_dir.lexically_normal();
  if (name.filename().empty()) name = name.parent_path();  // "DIR/"
  options.title = std::filesystem::absolute(name).filename().string();
  if (out.empty()) out = run_dir / "view.html";
  try {
    const nodus::output::ResultRun run = nodus::output::read_result_h5(run_dir);
    nodus::output::write_view_page(run, out, options);
    std::printf("wrote %s (%s)\n", out.c_str(),
                nodus::output::human_size(std::filesystem::file_size(out)).c_str());
    return 0;
  } catch (const nodus::output::WriteError& e) {
    report(e.what());
    return kWriteFailed;
  } catch (const std::exception& e) {  // no result.h5, a damaged one, no page script
    report(fmt::format("view: {}", e.what()));
    return kBadInput;
  }
}

/// The command line without its PETSc options; `passive_wait_set_here`: for the log.
int nodus_main(int argc, char** argv, bool passive_wait_set_here) {
  CLI::App app{"nodus: contact-friction mechanics of elastic beam assemblies (units: mm, N, MPa, s)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("nodus {} (commit {})", nodus::version(), nodus::commit()));
  nodus::run::Request request;
  // Branches side by side run in processes of this executable; under MPI every rank runs them in turn.
  if (nodus::parallel::size() == 1) request.branch_executable = "/proc/self/exe";
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
  run_cmd->add_option(
      "--timing-from", request.timing_from,
      "output directory of an earlier run of the same stages: the progress lines estimate the "
      "time left from its timing.csv (default: the output directory's own, from an earlier run)");
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

  bool coretype_only = false;
  CLI::App* kernels_cmd = app.add_subcommand(
      "kernels",
      "print the kernels OpenBLAS took and, where they are its generic ones on a processor that can "
      "run better, the OPENBLAS_CORETYPE to start nodus with");
  kernels_cmd->add_flag(
      "--coretype", coretype_only,
      "print only that OPENBLAS_CORETYPE value (an empty line where there is none), for scripts");

  std::string nodes_path, knot_yarn;
  std::vector<std::string> knot_beams;
  double separation = 1.2;
  CLI::App* knot_cmd = app.add_subcommand("knot",
                                          "knot type (Alexander polynomial, the curve closed far away) and "
                                          "smallest self-distance of a beam, or of "
                                          "the fibres of a yarn and their mean centreline");
  knot_cmd->add_option("nodes", nodes_path, "nodal table (final_nodes.csv or stages/NNN_STAGE_nodes.csv)")
      ->required();
  knot_cmd
      ->add_option("--beam", knot_beams,
                   "beam name, repeatable (default: the first beam of the table); with several, also the "
                   "knot type of their mean centreline and the smallest distance between each two")
      ->allow_extra_args(false);  // one name per --beam: `--beam a TABLE.csv` leaves the table positional
  knot_cmd->add_option("--yarn", knot_yarn, "yarn name: as --beam for each of its fibres NAME.rK.fJ");
  knot_cmd
      ->add_option("--separation", separation,
                   "smallest distance between points at least this far apart along the beam [mm]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  std::filesystem::path view_dir, view_out;
  double view_max_megabytes = 80.0;
  CLI::App* view_cmd = app.add_subcommand(
      "view", "write one self-contained HTML page showing a run and its branches in 3D, for any web browser");
  view_cmd->add_option("run_dir", view_dir, "output folder of a run (it reads RUN_DIR/result.h5)")
      ->required();
  view_cmd->add_option("--out,-o", view_out, "the page to write (default: RUN_DIR/view.html)");
  view_cmd
      ->add_option("--max-mb", view_max_megabytes,
                   "size budget of the states in the page [MB]: where they would take more, the page keeps "
                   "evenly spread states, the first, last and stage ends among them")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream out, err;
    const int code = app.exit(e, out, err);
    if (nodus::parallel::is_root()) {
      std::fputs(out.str().c_str(), stdout);
      std::fputs(err.str().c_str(), stderr);
    }
    return code == 0 ? 0 : kBadInput;
  }
  if (verbose) spdlog::set_level(spdlog::level::debug);
  if (!nodus::parallel::is_root()) spdlog::set_level(spdlog::level::off);  // rank 0 logs for all
  const char* wait_policy = std::getenv("OMP_WAIT_POLICY");
  spdlog::debug("OpenMP wait policy: OMP_WAIT_POLICY={}{}", wait_policy ? wait_policy : "(unset)",
                passive_wait_set_here ? " (set by nodus)" : "");
  request.verbose = verbose;

  try {
    if (app.got_subcommand("keys")) {
      if (nodus::parallel::is_root()) std::fputs(nodus::scenario::scenario_keys_markdown().c_str(), stdout);
      return 0;
    }
    if (app.got_subcommand("kernels")) {
      if (nodus::parallel::is_root()) std::fputs(kernels_lines(coretype_only).c_str(), stdout);
      return 0;
    }
    if (app.got_subcommand("knot")) {
      try {
        return nodus::parallel::is_root() ? knot(nodes_path, knot_beams, knot_yarn, separation) : 0;
      } catch (const std::invalid_argument& e) {
        report(e.what());
        return kBadInput;
      }
    }
    if (app.got_subcommand("view"))
      return nodus::parallel::is_root() ? view(view_dir, view_out, view_max_megabytes) : 0;
    if (app.got_subcommand("check")) {
      const nodus::scenario::Scenario scenario = nodus::scenario::read_scenario(scenario_path);
      nodus::simulation::Simulation sim(scenario);
      if (nodus::parallel::is_root()) std::fputs(nodus::scenario::describe(scenario).c_str(), stdout);
      return 0;
    }
    catch_stop_signals();
    request.cancel = stop_asked;
    request.cancel_cause = [] {
      return stop_signal == SIGINT ? std::string("SIGINT") : stop_signal == SIGTERM ? "SIGTERM" : "a signal";
    };
    const nodus::run::Outcome outcome = nodus::run::run(request);
    if (outcome.cancelled) return 128 + (stop_signal != 0 ? static_cast<int>(stop_signal) : SIGTERM);
    return outcome.converged && !outcome.interrupted ? 0 : kNotConverged;
  } catch (const nodus::scenario::ScenarioError& e) {
    report(e.what());  // every rank read the same input and stops here
    return kBadInput;
  } catch (const nodus::output::WriteError& e) {
    // Rank 0 alone writes: the others would wait for it for ever.
    bool resumable = false;
    try {
      resumable = !request.out.empty() &&
                  nodus::persistence::newest_checkpoint(request.out / "checkpoints").has_value();
    } catch (const std::exception&) {  // a damaged one: the message then says to run again
    }
    std::fprintf(stderr, "nodus: %s; the run stopped there: %s\n", e.what(),
                 resumable ? "once the cause is removed, continue it with --resume from its newest checkpoint"
                           : "it has no checkpoint yet: once the cause is removed, run it again");
    if (nodus::parallel::size() > 1) nodus::parallel::abort_all(kWriteFailed);
    return kWriteFailed;
  } catch (const std::exception& e) {
    // This rank alone may have failed (a disk full on rank 0): the others would wait for it for ever.
    std::fprintf(
        stderr, "nodus: error%s: %s\n",
        nodus::parallel::size() > 1 ? fmt::format(" on rank {}", nodus::parallel::rank()).c_str() : "",
        e.what());
    nodus::parallel::abort_all(1);
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool passive_wait_set_here = prefer_passive_openmp_wait(argv);
  nodus::output::use_stderr_logger();
  // PETSc's own options (-ksp_*, -pc_*, -mat_*, -mg_*, -sub_*) go to PETSc, the rest to nodus's command line.
  // MPI and PETSc start here when an MPI launcher started this process or PETSc options were given, else only
  // if a solver needs them (one process).
  const nodus::parallel::SplitArguments split = nodus::parallel::split_petsc_options(argc, argv);
  try {
    if (nodus::parallel::launched_by_mpi() || !split.petsc.empty()) nodus::parallel::initialize(split.petsc);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "nodus: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nodus: error: %s\n", e.what());
    return 1;
  }
  std::vector<std::string> words = split.rest;
  std::vector<char*> rest;
  for (std::string& w : words) rest.push_back(w.data());
  rest.push_back(nullptr);
  const int code = nodus_main(static_cast<int>(words.size()), rest.data(), passive_wait_set_here);
  nodus::parallel::finalize();
  return code;
}
