#pragma once
/// DIR/contact_final.csv and DIR/zones_final.csv: the contact geometry of the last converged state, element
/// by element and zone by zone; DIR/contact/contact_NNNNNN.csv: the contact elements at the VTK output steps
/// (output.contact_csv). See contact_table.hpp for the format.

#include <filesystem>
#include <string>
#include <vector>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// The contact states to write with sim.contact(): &sim.contact_states() (those of the last converged step)
/// when the run has contact forces and a step has converged, null otherwise (no contact, detection only, or
/// the initial state, before any contact force is computed: the contact files then carry no forces).
const std::vector<simulation::ContactState>* contact_states_to_write(const simulation::Simulation& sim);

/// When the run has contact (Simulation::contact() not null), writes DIR/contact_final.csv and
/// DIR/zones_final.csv when the run finishes (converged or not: the last converged state);
/// contact_final.csv carries the contact forces of the last converged step when the run has contact forces
/// and at least one step converged. At the start of the run it removes those files left by an earlier run,
/// so that they never describe another run.
class ContactCsvWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing.
  explicit ContactCsvWriter(std::filesystem::path dir);

  void on_start(const simulation::Simulation& sim) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/contact_final.csv.
  const std::filesystem::path& contact_path() const { return contact_path_; }
  /// DIR/zones_final.csv.
  const std::filesystem::path& zones_path() const { return zones_path_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path contact_path_;
  std::filesystem::path zones_path_;
};

/// The series DIR/contact/contact_NNNNNN.csv: the contact element table (contact_final_csv) of the state of
/// step NNNNNN, one file per step it is asked for (VtkSeriesWriter asks at its output steps, so a file has
/// the NNNNNN of the .vtp files of the same state).
class ContactCsvSeries {
 public:
  /// `dir`: output folder (files go to DIR/contact/).
  explicit ContactCsvSeries(std::filesystem::path dir);

  /// Removes contact_NNNNNN.csv files left in DIR/contact by an earlier run (other files are kept).
  void begin();
  /// Takes up the series of an interrupted run at its step `last_step`: removes the files of later steps.
  void resume(int last_step);
  /// Writes DIR/contact/contact_NNNNNN.csv (NNNNNN = `step`, six digits at least; the folder is created if
  /// missing) of `geometry`, with `states` if given (temporary file + rename). Writing a step again replaces
  /// its file.
  void write(int step, const contact::ContactGeometry& geometry, const std::vector<std::string>& beam_names,
             const std::vector<simulation::ContactState>* states = nullptr);

  /// DIR/contact.
  const std::filesystem::path& folder() const { return folder_; }
  /// "contact_000012.csv" for step 12.
  static std::string file_name(int step);

 private:
  std::filesystem::path folder_;
};

}  // namespace nodus::output
