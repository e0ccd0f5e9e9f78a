#pragma once
/// The format of a checkpoint: the complete state of a run (simulation::SimulationState) in a binary file,
/// from which `nodus run --resume` continues a killed run and a branch starts (docs/output.md). A run saves
/// DIR/checkpoints/NNN_<stage>.nodus-state at the end of every stage (NNN the stage index) and, with
/// output.checkpoint_every = N, DIR/checkpoints/latest.nodus-state every N converged steps.
///
/// Format, version kCheckpointVersion (raised at every change of the layout; integers little-endian, doubles
/// as their IEEE 754 bits, little-endian):
///
///     magic     12 bytes "NODUS-STATE\n"
///     version   u32
///     header    u64 fingerprint hash, string fingerprint text (scenario::state_fingerprint_text),
///               i32 steps, i32 stage, u8 stage begun, f64 load time
///     state     the rest of simulation::SimulationState (state_format.cpp lists it field by field)
///     checksum  u64 FNV-1a hash of every byte before it
///
/// A string or list is a u64 count followed by its items. A file is written to a temporary file and renamed
/// onto its name, so a killed run leaves either the previous file or the new one.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::persistence {

inline constexpr std::string_view kCheckpointMagic = "NODUS-STATE\n";
inline constexpr std::uint32_t kCheckpointVersion = 3;
/// The extension of checkpoint files.
inline constexpr std::string_view kCheckpointExtension = ".nodus-state";
/// The intermediate checkpoint (output.checkpoint_every), replaced each time.
inline constexpr std::string_view kLatestCheckpoint = "latest.nodus-state";

/// The bytes of a checkpoint of `state`, a state of a run of `scenario`.
std::string encode_checkpoint(const scenario::Scenario& scenario, const simulation::SimulationState& state);

/// The state in checkpoint `bytes` (read from `path`, named in messages), for a run of `scenario`. Throws
/// scenario::ScenarioError with one line "PATH: checkpoint: expected ..., got ..." if the bytes are not a
/// checkpoint of this format version, are damaged, or hold a state of another scenario: one whose
/// state_fingerprint_text differs (the message quotes the first differing line).
simulation::SimulationState decode_checkpoint(std::string_view bytes, const scenario::Scenario& scenario,
                                              const std::filesystem::path& path);

/// What the header of a checkpoint says.
struct CheckpointInfo {
  std::filesystem::path path;
  int steps = 0;             ///< converged steps of the state
  int stage = 0;             ///< the stage in progress, or the next one to begin
  bool stage_begun = false;  ///< inside `stage` (false: at its start, after the end of the one before)
  double time = 0.0;         ///< load time [s]
};

/// The header of the checkpoint `bytes` (read from `path`, named in messages). Throws scenario::ScenarioError
/// (one line) if they are not a checkpoint of this format version.
CheckpointInfo read_checkpoint_header(std::string_view bytes, const std::filesystem::path& path);

}  // namespace nodus::persistence
