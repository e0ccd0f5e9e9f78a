#pragma once
/// DIR/summary.json: the size of the model and the outcome of the run, for scripts.

#include <filesystem>
#include <string>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// What summary.json holds.
struct SummaryData {
  int dofs = 0;  ///< unknowns of the model (nine per node)
  int nodes = 0;
  int elements = 0;
  int beams = 0;
  int steps = 0;                      ///< converged load steps
  int newton_iterations = 0;          ///< over all converged steps
  bool converged = false;             ///< every stage completed
  double wall_seconds = 0.0;          ///< wall-clock time of the run [s]
  double detection_seconds = 0.0;     ///< of which in contact detection [s]
  double assembly_seconds = 0.0;      ///< of which in residual and tangent evaluations inside Newton [s]
  double linear_solve_seconds = 0.0;  ///< of which in sparse analysis, factorisation and solves [s]
  std::string failure;                ///< why the run stopped early; empty if it did not
  double final_time = 0.0;            ///< load time of the last converged state [s]
  std::string scenario;               ///< path of the scenario file
};

/// Collects the summary of a finished run.
SummaryData summary_data(const simulation::Simulation& sim, const simulation::RunSummary& summary);

/// The JSON document (an object with the members of SummaryData under the same names, indented, '\n' ended).
std::string summary_json(const SummaryData& data);

/// Writes summary_json(data) to `path` (temporary file + rename).
void write_summary(const std::filesystem::path& path, const SummaryData& data);

/// Writes DIR/summary.json when the run finishes.
class SummaryWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing.
  explicit SummaryWriter(std::filesystem::path dir);

  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/summary.json.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path path_;
};

}  // namespace nodus::output
