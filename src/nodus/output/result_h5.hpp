#pragma once
/// DIR/result.h5: what a run's CSV and VTK files hold, in one HDF5 file (layout in docs/output.md,
/// "result.h5"): the scenario echo, the beams and their centreline segments, the step table of steps.csv,
/// every output state (the steps of the VTK files) with its nodes, strain measures and contact tables, the
/// stages, and for a scenario with branches an external link to each branch's own result.h5. Beside it,
/// DIR/result.xmf, an XDMF index of the states so that ParaView opens the series. Units: mm, N, MPa, s.
///
/// The file is opened for each output state and closed (flushed) after it. A run that resumes an
/// interrupted one keeps the states up to the resumed step and drops the later ones, and rebuilds the step
/// table from steps.csv; a file that cannot be opened then (damaged by a hard kill) is moved aside as
/// result.h5.damaged and a new one begun.

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "nodus/output/result_data.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// The root attribute `format` of result.h5, and its `format_version`.
inline constexpr const char* kResultFormat = "nodus-result";
inline constexpr int kResultFormatVersion = 1;

class ResultH5Writer : public simulation::StepObserver {
 public:
  /// `dir`: output folder; `every`: write a state every N-th converged step (output.vtk_every; 0: only the
  /// initial and the final state), >= 0; `enabled`: output.hdf5 (false: write nothing, and remove a
  /// result.h5 and result.xmf left by an earlier run). Throws std::invalid_argument on every < 0.
  ResultH5Writer(std::filesystem::path dir, int every, bool enabled = true);

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/result.h5.
  std::filesystem::path path() const { return dir_ / "result.h5"; }
  /// DIR/result.xmf.
  std::filesystem::path xdmf_path() const { return dir_ / "result.xmf"; }
  /// The steps of the states in the file, in order.
  const std::vector<int>& state_steps() const { return steps_; }

 private:
  /// Writes the state of `sim` as /states/NNNNNN (step `step`, load time `time` [s], stage `stage`), the
  /// step table so far, then closes the file and rewrites result.xmf.
  void write_state(const simulation::Simulation& sim, int step, double time, const std::string& stage);
  /// Creates a new file with the parts that do not change during the run (scenario, beams, mesh, stages).
  void create(const simulation::Simulation& sim);
  /// Takes up the file of an interrupted run at step `last_step` (see the header comment).
  void resume(const simulation::Simulation& sim, int last_step);
  /// The XDMF index of the states written so far.
  void write_xdmf() const;

  std::filesystem::path dir_;
  int every_;
  bool enabled_;
  bool active_ = false;                         ///< output.hdf5 of the running scenario, and begun
  std::vector<int> steps_;                      ///< steps of the states in the file, in order
  std::vector<double> times_;                   ///< their load times [s]
  std::vector<std::string> step_header_;        ///< the columns of steps.csv
  std::vector<std::vector<std::string>> rows_;  ///< the fields of its rows so far
  std::string stage_;                           ///< the stage of the last converged state
  int last_step_ = 0;                           ///< last converged step seen
  int num_nodes_ = 0;
  int num_segments_ = 0;
};

/// Reads DIR/result.h5 of the run in `run_dir` and, recursively, of its branches (those whose result.h5
/// exists; a branch that did not run has none). Throws std::runtime_error with a one-line message naming the
/// file and what was expected if it is missing, not a nodus result of this format, or incomplete.
ResultRun read_result_h5(const std::filesystem::path& run_dir);

/// Every dataset and attribute of the HDF5 file `path` as text, one line per object in name order (its
/// path, type, shape and values), leaving out the attributes named in `skipped`: a canonical form for
/// comparing two files by content (resumed and uninterrupted runs). Throws std::runtime_error if the file
/// cannot be opened.
std::string result_h5_text(const std::filesystem::path& path, const std::set<std::string>& skipped = {});

/// Splits CSV text (RFC 4180, as nodus writes it) into records of fields; a last record cut short (no line
/// end) is left out.
std::vector<std::vector<std::string>> split_csv(const std::string& text);

}  // namespace nodus::output
