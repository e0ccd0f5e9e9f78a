#pragma once
/// The output writers of one run (the main run, or a branch) into a folder, as the observers of its
/// Simulation: steps.csv, timing.csv, VTK, final nodes, contact tables, stage-end files, summary.json,
/// result.h5, checkpoints and the progress line (docs/output.md).

#include <filesystem>
#include <string>
#include <vector>

#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/final_nodes_writer.hpp"
#include "nodus/output/progress_reporter.hpp"
#include "nodus/output/result_h5.hpp"
#include "nodus/output/stage_end_writer.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/summary_writer.hpp"
#include "nodus/output/timing_csv.hpp"
#include "nodus/output/vtk_writer.hpp"
#include "nodus/persistence/checkpoint_files.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::run {

class RunOutputs {
 public:
  /// `write_summary`: whether summary.json is written at the end (the main run of a scenario with branches
  /// writes it itself, after them); `label` prefixes the progress lines. `timing`: the timing.csv of an
  /// earlier run of the same program, for the progress lines' estimate of the time left; empty: DIR's own,
  /// left by an earlier run into DIR (read before this run replaces it), if any and if it serves.
  RunOutputs(const std::filesystem::path& dir, const scenario::Scenario& scenario, bool quiet,
             bool write_summary, std::string label = {}, const std::filesystem::path& timing = {});
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  const std::vector<simulation::StepObserver*>& observers() const { return observers_; }
  const output::SummaryWriter& summary() const { return summary_; }
  /// Saves the last converged state of a run stopped between its checkpoints (Request::cancel) as its
  /// newest checkpoint.
  void save_stopped(const simulation::Simulation& sim) { checkpoints_.save_now(sim); }

 private:
  output::StepsCsvWriter steps_;
  output::TimingCsvWriter timing_;
  output::VtkSeriesWriter vtk_;
  output::FinalNodesWriter final_nodes_;
  output::ContactCsvWriter contact_tables_;
  output::StageEndWriter stage_ends_;
  output::SummaryWriter summary_;
  output::ResultH5Writer result_h5_;
  persistence::CheckpointWriter checkpoints_;
  output::ProgressReporter progress_;
  std::vector<simulation::StepObserver*> observers_;
};

/// The observers of a process that writes nothing (an MPI rank other than 0).
const std::vector<simulation::StepObserver*>& no_observers();

}  // namespace nodus::run
