#include "nodus/output/stage_end_writer.hpp"

#include <charconv>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/contact_table.hpp"
#include "nodus/output/final_nodes_table.hpp"
#include "nodus/persistence/checkpoint_files.hpp"

namespace nodus::output {

StageEndWriter::StageEndWriter(std::filesystem::path dir) : folder_(std::move(dir) / "stages") {}

std::string StageEndWriter::stem(int stage, std::string_view name) {
  return std::filesystem::path(persistence::checkpoint_file_name(stage, name)).stem().string();
}

void StageEndWriter::on_start(const simulation::Simulation& sim) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder_, error)) return;
  const int first_to_run = sim.progress().stage;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(folder_, error)) {
    const std::string name = entry.path().filename().string();
    int stage = -1;
    const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), stage);
    if (ec != std::errc() || end != name.data() + 3 || name.size() < 4 || name[3] != '_') continue;
    if (stage >= first_to_run) stale.push_back(entry.path());
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder_.string() + "': " + error.message());
  for (const auto& path : stale) {
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
}

void StageEndWriter::on_stage_end(const simulation::Simulation& sim, int stage) {
  std::error_code error;
  std::filesystem::create_directories(folder_, error);
  if (error) throw_write_error("create folder", folder_, error.value());
  const std::string base = stem(stage, sim.scenario().stages.at(static_cast<std::size_t>(stage)).name);
  write_final_nodes(folder_ / (base + "_nodes.csv"), sim.model(), sim.state());
  if (const contact::ContactGeometry* geometry = sim.contact())
    write_contact_final(folder_ / (base + "_contact.csv"), *geometry, beam_names(sim.model()),
                        contact_states_to_write(sim));
}

}  // namespace nodus::output
