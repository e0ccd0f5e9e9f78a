#pragma once
/// DIR/steps.csv: one row per converged load step (step counters, Newton statistics, the size of the contact
/// geometry, what the contact loops did and the contact forces they reached, the force and moment on every
/// condition's section, and what made the step hard). Columns are documented in docs/output.md.

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// The header line (no line end): step,stage,time,newton_iterations,cutbacks,residual,increment,zones,
/// contact_elements,detections,normal_iterations,penetration_ratio,normal_force,tangential_force,slipping,
/// stabilization_force,loops_converged,min_orientation,min_chord,min_clearance,
/// then NAME_fx,NAME_fy,NAME_fz,NAME_mx,NAME_my,NAME_mz for each condition name in order, then
/// BODY_fx,BODY_fy,BODY_fz,BODY_mx,BODY_my,BODY_mz,BODY_error,BODY_tie for each rigid body name in order,
/// then step_size,entered,left,to_slip,to_stick,cutback_causes.
std::string steps_csv_header(const std::vector<std::string>& condition_names,
                             const std::vector<std::string>& body_names = {});

/// One data line (no line end) for `record`, the stage column holding `stage_name`; numbers with ten
/// significant digits: time [s], residual [N], increment [-], penetration_ratio [-], forces [N], moments
/// [N mm]; `zones` and `contact_elements` are the record's counts (0 without contact); `detections`,
/// `normal_iterations`, `penetration_ratio`, `normal_force` (sum of R_N), `tangential_force` (sum of |R_T|)
/// and `slipping` are the record's contact-loop figures (0 without contact forces); `loops_converged` is 1 or
/// 0 (1 without contact forces). Sections missing from the
/// record (fewer than `num_conditions`) give empty fields, as do bodies (fewer than `num_bodies`): the force
/// [N] and moment [N mm] each exerts on its sections, about its point, its error [mm] and its tie force [N].
/// Last come the step's size [s], its changes of regime of the contact elements (StepRecord::regime_changes)
/// and its cutback causes (cutback_causes_field).
std::string steps_csv_row(const simulation::StepRecord& record, const std::string& stage_name,
                          int num_conditions, int num_bodies = 0);

/// The failure messages of a step's cutbacks joined with " | " as one CSV field (csv_field: quoted when they
/// hold a comma, a double quote or a line break); empty when there were none.
std::string cutback_causes_field(const std::vector<std::string>& causes);

/// `text` (a steps.csv) cut after the data line of step `last_step`: the header and the lines of the steps up
/// to `last_step`, each with its line end (a quoted field may hold line breaks).
std::string steps_csv_up_to(std::string_view text, int last_step);

/// A CSV file written a row at a time, each row flushed at once, so that an interrupted run keeps its rows
/// (steps.csv, timing.csv). Throws std::runtime_error naming the file on I/O errors.
class CsvRowFile {
 public:
  explicit CsvRowFile(std::filesystem::path path) : path_(std::move(path)) {}
  ~CsvRowFile();
  CsvRowFile(const CsvRowFile&) = delete;
  CsvRowFile& operator=(const CsvRowFile&) = delete;

  /// Creates the file's folder and opens the file. Anew (`resume` false): the file holds `header` alone.
  /// Resumed: the file keeps its header and its rows up to step `last_step` (steps_csv_up_to; the header
  /// alone if it was missing), which are returned; throws if that header is not `header`.
  std::string open(const std::string& header, bool resume, int last_step);
  /// Appends `line` and a line end.
  void write_line(const std::string& line);
  /// Closes the file (on_finish).
  void close();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

/// Writes DIR/steps.csv: the header at the start of the run, a row per converged step, each row flushed at
/// once so that an interrupted run keeps its rows. When the run resumes an interrupted one
/// (simulation::StartKind::resumed), it keeps the header and the rows up to the resumed state's step and
/// drops the later ones, then appends. Throws std::runtime_error naming the file on I/O errors.
class StepsCsvWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing.
  explicit StepsCsvWriter(const std::filesystem::path& dir) : file_(dir / "steps.csv") {}

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/steps.csv.
  const std::filesystem::path& path() const { return file_.path(); }

 private:
  CsvRowFile file_;
};

}  // namespace nodus::output
