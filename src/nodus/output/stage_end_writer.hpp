#pragma once
/// DIR/stages/NNN_STAGE_nodes.csv and DIR/stages/NNN_STAGE_contact.csv: the state at the end of every stage
/// (the formats of final_nodes.csv and contact_final.csv), so that each stage of a loading program can be
/// read back without replaying it (pictures of the stages, reports).

#include <filesystem>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// Writes the stage-end tables. NNN is the stage index (from 0) and STAGE its name, as in the checkpoint
/// file names (checkpoint_file_name). At the start of a run it removes the stage files of the stages still to
/// run (all of them for a fresh run; those from the resumed stage on for a resumed one).
class StageEndWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder (files go to DIR/stages/).
  explicit StageEndWriter(std::filesystem::path dir);
  void on_start(const simulation::Simulation& sim) override;
  void on_stage_end(const simulation::Simulation& sim, int stage) override;
  /// DIR/stages.
  const std::filesystem::path& folder() const { return folder_; }
  /// "003_settle" for stage 3 named "settle" (characters other than letters, digits, _ . - become _).
  static std::string stem(int stage, std::string_view name);

 private:
  std::filesystem::path folder_;
};

}  // namespace nodus::output
