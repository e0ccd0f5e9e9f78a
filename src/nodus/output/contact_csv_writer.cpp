#include "nodus/output/contact_csv_writer.hpp"

#include <stdexcept>
#include <system_error>

#include "nodus/output/contact_table.hpp"

namespace nodus::output {

ContactCsvWriter::ContactCsvWriter(std::filesystem::path dir)
    : dir_(std::move(dir)),
      contact_path_(dir_ / "contact_final.csv"),
      zones_path_(dir_ / "zones_final.csv") {}

void ContactCsvWriter::on_start(const simulation::Simulation& /*sim*/) {
  for (const auto& path : {contact_path_, zones_path_}) {
    std::error_code error;
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
}

void ContactCsvWriter::on_finish(const simulation::Simulation& sim,
                                 const simulation::RunSummary& /*summary*/) {
  const contact::ContactGeometry* geometry = sim.contact();
  if (!geometry) return;
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw std::runtime_error("cannot create folder '" + dir_.string() + "': " + error.message());
  const std::vector<std::string> names = beam_names(sim.model());
  write_contact_final(contact_path_, *geometry, names);
  write_zones_final(zones_path_, *geometry, names);
}

}  // namespace nodus::output
