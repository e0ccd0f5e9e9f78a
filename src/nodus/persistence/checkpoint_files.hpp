#pragma once
/// Checkpoint files: a run saves DIR/checkpoints/NNN_<stage>.nodus-state at the end of every stage (NNN the
/// stage index) and, with output.checkpoint_every = N, DIR/checkpoints/latest.nodus-state every N converged
/// steps, from which `nodus run --resume` continues a killed run and a branch starts (docs/output.md). The
/// format is in state_format.hpp. A file is written to a temporary file and renamed onto its name, so a
/// killed run leaves either the previous file or the new one.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "nodus/persistence/state_format.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::persistence {

/// "003_tighten.nodus-state" for stage 3 named tighten; characters other than letters, digits, '_', '.' and
/// '-' in the name become '_'.
std::string checkpoint_file_name(int stage, std::string_view stage_name);

/// Writes a checkpoint of sim.snapshot() to `path` (temporary file + rename).
void write_checkpoint(const std::filesystem::path& path, const simulation::Simulation& sim);

/// Reads the checkpoint `path` for a run of `scenario` (see decode_checkpoint; an unreadable file throws
/// scenario::ScenarioError too).
simulation::SimulationState read_checkpoint(const std::filesystem::path& path,
                                            const scenario::Scenario& scenario);

/// The header of checkpoint `path`. Throws scenario::ScenarioError (one line) if it is not a checkpoint of
/// this format version.
CheckpointInfo checkpoint_info(const std::filesystem::path& path);

/// A checkpoint that cannot be read back: cut short, changed after it was written (its checksum), or not a
/// state file at all (a foreign one, of another format version or scenario, is a plain ScenarioError).
class DamagedFile : public scenario::ScenarioError {
 public:
  using scenario::ScenarioError::ScenarioError;
};

/// The checkpoint of `folder` (*.nodus-state files) with the most steps, a stage-end one before `latest` at
/// equal steps; none if the folder has none (or does not exist). Throws DamagedFile if one's header is
/// damaged.
std::optional<CheckpointInfo> newest_checkpoint(const std::filesystem::path& folder);

/// The newest checkpoint of `folder`, in the order of newest_checkpoint, that reads back whole as a state of
/// `scenario`: a damaged one (DamagedFile) is passed over with a warning that names it and what is wrong, and
/// the next newest tried. None if the folder has none. Throws scenario::ScenarioError if there are
/// checkpoints but every one is damaged (naming them), or if the first intact one is of another scenario.
std::optional<CheckpointInfo> newest_intact_checkpoint(const std::filesystem::path& folder,
                                                       const scenario::Scenario& scenario);

/// Saves the run's checkpoints into DIR/checkpoints: NNN_<stage>.nodus-state at the end of each stage and,
/// every `every` converged steps (0: never) unless the step ends a stage, latest.nodus-state. At the start of
/// a run that does not resume one, it removes the checkpoints left in the folder by an earlier run.
class CheckpointWriter : public simulation::StepObserver {
 public:
  /// `dir`: the run's output folder; `every` >= 0.
  CheckpointWriter(std::filesystem::path dir, int every);

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_stage_end(const simulation::Simulation& sim, int stage) override;
  /// Writes latest.nodus-state now, between the regular ones: the last converged state of a run stopped by a
  /// signal, from which --resume goes on as from any other.
  void save_now(const simulation::Simulation& sim);

  /// DIR/checkpoints.
  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
  int every_;
};

/// Removes the *.nodus-state files of `folder` (if it exists).
void remove_checkpoints(const std::filesystem::path& folder);

}  // namespace nodus::persistence
