#include "nodus/output/contact_csv_writer.hpp"

#include <charconv>
#include <regex>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_table.hpp"

namespace nodus::output {
namespace {

void create_folder(const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw_write_error("create folder", dir, error.value());
}

void remove_file(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::remove(path, error);
  if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
}

}  // namespace

const std::vector<simulation::ContactState>* contact_states_to_write(const simulation::Simulation& sim) {
  const contact::ContactGeometry* geometry = sim.contact();
  if (!geometry || !sim.contact_forces()) return nullptr;
  // After a converged step Simulation::contact_states() holds one state per element of contact(); before the
  // first, none (the table then has no force columns). A converged state without any contact element has
  // none of either: its table has the force columns and no rows (a knot that came undone).
  const std::vector<simulation::ContactState>& states = sim.contact_states();
  return states.size() == geometry->elements.size() ? &states : nullptr;
}

ContactCsvWriter::ContactCsvWriter(std::filesystem::path dir)
    : dir_(std::move(dir)),
      contact_path_(dir_ / "contact_final.csv"),
      zones_path_(dir_ / "zones_final.csv") {}

void ContactCsvWriter::on_start(const simulation::Simulation& /*sim*/) {
  for (const auto& path : {contact_path_, zones_path_}) remove_file(path);
}

void ContactCsvWriter::on_finish(const simulation::Simulation& sim,
                                 const simulation::RunSummary& /*summary*/) {
  const contact::ContactGeometry* geometry = sim.contact();
  if (!geometry) return;
  create_folder(dir_);
  const std::vector<std::string> names = beam_names(sim.model());
  write_contact_final(contact_path_, *geometry, names, contact_states_to_write(sim));
  write_zones_final(zones_path_, *geometry, names);
}

ContactCsvSeries::ContactCsvSeries(std::filesystem::path dir) : folder_(std::move(dir) / "contact") {}

std::string ContactCsvSeries::file_name(int step) {
  return fmt::format("contact_{:06d}.csv", step);
}

void ContactCsvSeries::begin() {
  resume(-1);
}

void ContactCsvSeries::resume(int last_step) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder_, error)) return;
  const std::regex series_file(R"(contact_([0-9]{6,})\.csv)");
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(folder_, error)) {
    std::smatch match;
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || !std::regex_match(name, match, series_file)) continue;
    long long step = 0;
    const std::string digits = match[1].str();
    std::from_chars(digits.data(), digits.data() + digits.size(), step);
    if (step > last_step) stale.push_back(entry.path());
  }
  if (error) throw std::runtime_error("cannot list folder '" + folder_.string() + "': " + error.message());
  for (const auto& path : stale) remove_file(path);
}

void ContactCsvSeries::write(int step, const contact::ContactGeometry& geometry,
                             const std::vector<std::string>& beam_names,
                             const std::vector<simulation::ContactState>* states) {
  create_folder(folder_);
  write_contact_final(folder_ / file_name(step), geometry, beam_names, states);
}

}  // namespace nodus::output
