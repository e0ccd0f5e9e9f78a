#include "nodus/persistence/checkpoint_files.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <system_error>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/persistence/binary_codec.hpp"

namespace nodus::persistence {
namespace {

/// Orders checkpoints from the oldest to the newest: by steps, at equal steps the stage-end file after
/// `latest`, then by name, so that the choice does not depend on the order of the listing.
auto newer_key(const CheckpointInfo& i) {
  return std::tuple(i.steps, i.path.filename() != kLatestCheckpoint, i.path.filename().string());
}

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
    if (!newest || newer_key(info) > newer_key(*newest)) newest = info;
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder.string() + "': " + error.message());
  return newest;
}

std::optional<CheckpointInfo> newest_intact_checkpoint(const std::filesystem::path& folder,
                                                       const scenario::Scenario& scenario) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return std::nullopt;
  std::vector<CheckpointInfo> readable;
  std::vector<std::string> damaged;  // their file names
  const auto pass_over = [&damaged](const std::filesystem::path& path, const DamagedFile& e) {
    const std::string what = e.what();
    const std::string reason = what.substr(what.find(": checkpoint: ") + 14);
    spdlog::warn("{}: damaged ({}), passed over", path.string(), reason);
    damaged.push_back(path.filename().string());
  };
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (!entry.is_regular_file() || entry.path().extension() != kCheckpointExtension) continue;
    try {
      readable.push_back(checkpoint_info(entry.path()));
    } catch (const DamagedFile& e) {
      pass_over(entry.path(), e);
    }
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder.string() + "': " + error.message());
  std::sort(readable.begin(), readable.end(),
            [](const CheckpointInfo& a, const CheckpointInfo& b) { return newer_key(a) > newer_key(b); });
  for (const CheckpointInfo& info : readable) {
    try {
      read_checkpoint(info.path, scenario);
      return info;
    } catch (const DamagedFile& e) {
      pass_over(info.path, e);
    }
  }
  if (damaged.empty()) return std::nullopt;
  std::sort(damaged.begin(), damaged.end());
  std::string names;
  for (const std::string& name : damaged) names += (names.empty() ? "" : ", ") + name;
  throw scenario::ScenarioError(fmt::format(
      "{}: --resume: expected an intact checkpoint, got only damaged ones ({}): nothing to resume from (run "
      "without --resume to start the run again)",
      folder.string(), names));
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
