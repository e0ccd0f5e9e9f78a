#pragma once
/// DIR/timing.csv: the wall time of a run at each converged step, so that a later run of the same loading
/// program can estimate its time left from it (output::RemainingTime::use_profile; docs/output.md).
///
///   step,stage,time,newton_iterations,wall_seconds
///
/// The first data row is the run's start: `step` the converged steps before it (0 from the initial state, the
/// parent's count for a branch), `stage` the stage about to run, `time` the load time there [s], 0 Newton
/// iterations and 0 s. Then one row per converged step; `wall_seconds` is the wall time of the run from its
/// start to the end of that step [s] (a resumed run goes on from the interrupted one's last kept row).

#include <filesystem>
#include <string>
#include <vector>

#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// One row of timing.csv.
struct TimingRow {
  int step = 0;
  std::string stage;
  double time = 0.0;          ///< load time [s]
  int newton_iterations = 0;  ///< of the step's successful attempt
  double wall_seconds = 0.0;  ///< since the start of the run [s]
};

/// The header line (no line end).
inline constexpr const char* kTimingCsvHeader = "step,stage,time,newton_iterations,wall_seconds";

/// One data line (no line end); numbers with ten significant digits.
std::string timing_csv_row(const TimingRow& row);

/// The rows of a timing.csv. Throws std::runtime_error ("FILE:LINE: expected ..., got ...") on a missing
/// file, another header or a malformed row; a last line cut short by a kill is ignored.
std::vector<TimingRow> read_timing_csv(const std::filesystem::path& path);

/// Writes DIR/timing.csv: the header and the start row at the start of the run, a row per converged step,
/// each flushed at once. A resumed run (simulation::StartKind::resumed) keeps the rows up to its state's step
/// and goes on from the wall time of the last one. Throws std::runtime_error naming the file on I/O errors.
class TimingCsvWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing.
  explicit TimingCsvWriter(const std::filesystem::path& dir) : file_(dir / "timing.csv") {}

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/timing.csv.
  const std::filesystem::path& path() const { return file_.path(); }

 private:
  CsvRowFile file_;
  /// timing.csv's wall_seconds = the run's cumulative counter (Simulation::counters) minus this [s].
  double wall_offset_ = 0.0;
};

}  // namespace nodus::output
