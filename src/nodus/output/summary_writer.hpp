#pragma once
/// DIR/summary.json: the size of the model and the outcome of the run, for scripts.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nodus/output/provenance.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// The outcome of one branch (scenario key `branches`), listed in the main run's summary.json.
struct BranchOutcome {
  std::string name;
  std::string from;         ///< the stage of the main run it starts from
  double friction = 0.0;    ///< contact.friction of its stages [-]
  std::string folder;       ///< its output folder, relative to DIR: branches/NAME
  bool converged = false;   ///< every stage of the branch completed
  std::string failure;      ///< why it stopped early, or why it did not run; empty if it did not
  int steps = 0;            ///< converged steps at its end (numbering goes on from the main run's)
  double final_time = 0.0;  ///< load time of its last converged state [s]
};

/// What summary.json holds.
struct SummaryData {
  int dofs = 0;  ///< unknowns of the model (nine per node)
  int nodes = 0;
  int elements = 0;
  int beams = 0;
  int steps = 0;                        ///< converged load steps
  int newton_iterations = 0;            ///< over all converged steps
  bool converged = false;               ///< every stage completed
  double wall_seconds = 0.0;            ///< wall-clock time of the run [s]
  double detection_seconds = 0.0;       ///< of which in contact detection [s]
  double assembly_seconds = 0.0;        ///< of which in residual and tangent evaluations inside Newton [s]
  double linear_solve_seconds = 0.0;    ///< of which in sparse analysis, factorisation and solves [s]
  int factorizations = 0;               ///< numerical factorisations of the tangent
  int analyses = 0;                     ///< symbolic analyses of the tangent's pattern
  int krylov_iterations = 0;            ///< GMRES iterations on lagged factors
  std::string failure;                  ///< why the run stopped early; empty if it did not
  double final_time = 0.0;              ///< load time of the last converged state [s]
  std::string scenario;                 ///< path of the scenario file
  std::optional<double> friction;       ///< contact.friction of the run, with contact forces [-]
  std::string branch;                   ///< for the run of a branch: its name; empty for the main run
  std::vector<BranchOutcome> branches;  ///< main run of a scenario with branches: their outcomes
  /// Where the result came from: nodus, the machine, threads, ranks and linear solvers (not read back).
  std::optional<Provenance> provenance;
};

/// Collects the summary of a finished run.
SummaryData summary_data(const simulation::Simulation& sim, const simulation::RunSummary& summary);

/// The JSON document (an object with the members of SummaryData under the same names, indented, '\n' ended;
/// `friction` only with contact forces, `branch` only for a branch, `branches` only when there are some;
/// `provenance` last, where there is one).
std::string summary_json(const SummaryData& data);

/// The SummaryData of a summary.json written by write_summary. Throws std::runtime_error naming the file if
/// it cannot be read.
SummaryData read_summary(const std::filesystem::path& path);

/// Writes summary_json(data) to `path` (temporary file + rename).
void write_summary(const std::filesystem::path& path, const SummaryData& data);

/// Writes DIR/summary.json when the run finishes, and removes one left by an earlier run when it starts (a
/// summary.json marks a finished run: `nodus run --resume` leaves such a run alone).
class SummaryWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing. `write_at_finish` false: the summary is only collected
  /// (data()), for the caller to complete and write (the main run of a scenario with branches).
  explicit SummaryWriter(std::filesystem::path dir, bool write_at_finish = true);

  void on_start(const simulation::Simulation& sim) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/summary.json.
  const std::filesystem::path& path() const { return path_; }
  /// The summary of the finished run; empty before on_finish.
  const std::optional<SummaryData>& data() const { return data_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path path_;
  bool write_at_finish_;
  std::optional<SummaryData> data_;
};

}  // namespace nodus::output
