#include "nodus/persistence/checkpoint_files.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/persistence/binary_codec.hpp"

namespace nodus::persistence {
namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad_file(path, "a readable file", "cannot open it");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) bad_file(path, "a readable file", "a read error");
  return bytes.str();
}

}  // namespace

std::string checkpoint_file_name(int stage, std::string_view stage_name) {
  std::string name;
  for (const char c : stage_name)
    name += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' ? c : '_';
  return fmt::format("{:03d}_{}{}", stage, name, kCheckpointExtension);
}

void write_checkpoint(const std::filesystem::path& path, const simulation::Simulation& sim) {
  output::write_file_atomically(path, encode_checkpoint(sim.scenario(), sim.snapshot()));
}

simulation::SimulationState read_checkpoint(const std::filesystem::path& path,
                                            const scenario::Scenario& scenario) {
  return decode_checkpoint(read_bytes(path), scenario, path);
}

CheckpointInfo checkpoint_info(const std::filesystem::path& path) {
  return read_checkpoint_header(read_bytes(path), path);
}

std::optional<CheckpointInfo> newest_checkpoint(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return std::nullopt;
  std::optional<CheckpointInfo> newest;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (!entry.is_regular_file() || entry.path().extension() != kCheckpointExtension) continue;
    const CheckpointInfo info = checkpoint_info(entry.path());
    // At equal steps the stage-end file, then the first name, so that the choice does not depend on the
    // order of the listing.
    const auto key = [](const CheckpointInfo& i) {
      return std::tuple(i.steps, i.path.filename() != kLatestCheckpoint, i.path.filename().string());
    };
    if (!newest || key(info) > key(*newest)) newest = info;
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder.string() + "': " + error.message());
  return newest;
}

void remove_checkpoints(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error))
    if (entry.is_regular_file() && entry.path().extension() == kCheckpointExtension)
      stale.push_back(entry.path());
  if (error) throw std::runtime_error("cannot list folder '" + folder.string() + "': " + error.message());
  for (const auto& path : stale) {
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
}

CheckpointWriter::CheckpointWriter(std::filesystem::path dir, int every)
    : folder_(std::move(dir) / "checkpoints"), every_(every) {
  if (every_ < 0) throw std::invalid_argument(fmt::format("checkpoints: every = {}, must be >= 0", every_));
}

void CheckpointWriter::on_start(const simulation::Simulation& sim) {
  std::error_code error;
  std::filesystem::create_directories(folder_, error);
  if (error) output::throw_write_error("create folder", folder_, error.value());
  if (sim.start_kind() != simulation::StartKind::resumed) remove_checkpoints(folder_);
}

void CheckpointWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  if (every_ > 0 && record.step % every_ == 0 && !record.ends_stage)
    write_checkpoint(folder_ / kLatestCheckpoint, sim);
}

void CheckpointWriter::save_now(const simulation::Simulation& sim) {
  write_checkpoint(folder_ / kLatestCheckpoint, sim);
}

void CheckpointWriter::on_stage_end(const simulation::Simulation& sim, int stage) {
  write_checkpoint(
      folder_ / checkpoint_file_name(stage, sim.scenario().stages.at(static_cast<std::size_t>(stage)).name),
      sim);
}

}  // namespace nodus::persistence
