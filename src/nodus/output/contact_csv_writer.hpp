#pragma once
/// DIR/contact_final.csv and DIR/zones_final.csv: the contact geometry of the last converged state, element
/// by element and zone by zone (see contact_table.hpp for the format).

#include <filesystem>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// When the run has contact (Simulation::contact() not null), writes DIR/contact_final.csv and
/// DIR/zones_final.csv when the run finishes (converged or not: the last converged state). At the start of
/// the run it removes those files left by an earlier run, so that they never describe another run.
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

}  // namespace nodus::output
