#include "nodus/output/vtk_series.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <optional>
#include <regex>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_vtk.hpp"

namespace nodus::output {

bool VtkSeries::Collection::has(int step) const {
  return std::find(steps.begin(), steps.end(), step) != steps.end();
}

void VtkSeries::Collection::add(int step, double time, const std::string& file) {
  const auto it = std::find(steps.begin(), steps.end(), step);
  if (it == steps.end()) {
    steps.push_back(step);
    entries.push_back({time, file});
  } else {
    entries[static_cast<std::size_t>(it - steps.begin())].time = time;
  }
}

void VtkSeries::Collection::clear() {
  steps.clear();
  entries.clear();
}

VtkSeries::VtkSeries(std::filesystem::path dir, int tube_sides, VtkEncoding encoding)
    : dir_(std::move(dir)), tube_sides_(tube_sides), encoding_(encoding) {
  if (tube_sides_ < 3)
    throw std::invalid_argument(fmt::format("VTK output: tube_sides = {}, must be >= 3", tube_sides_));
}

std::string VtkSeries::file_name(int step) {
  return fmt::format("step_{:06d}.vtp", step);
}

std::string VtkSeries::contact_file_name(int step) {
  return fmt::format("contact_{:06d}.vtp", step);
}

void VtkSeries::begin(bool contact) {
  const std::filesystem::path vtk = dir_ / "vtk";
  std::error_code error;
  std::filesystem::create_directories(vtk, error);
  if (error) throw_write_error("create folder", vtk, error.value());
  const std::regex series_file(R"((step|contact)_[0-9]{6,}\.vtp)");
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(vtk, error))
    if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), series_file))
      stale.push_back(entry.path());
  if (error) throw std::runtime_error("cannot list folder '" + vtk.string() + "': " + error.message());
  if (!contact && std::filesystem::exists(contact_pvd_path())) stale.push_back(contact_pvd_path());
  for (const auto& path : stale) {
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
  beams_.clear();
  contact_.clear();
  write_pvd(pvd_path(), beams_.entries);
  if (contact) write_pvd(contact_pvd_path(), contact_.entries);
  begun_ = true;
}

namespace {

/// The number NNNNNN of a file name "PREFIX_NNNNNN.vtp" (or a path ending with it); none if it is not one.
std::optional<int> series_step(const std::string& name, const std::regex& pattern) {
  std::smatch match;
  if (!std::regex_match(name, match, pattern)) return std::nullopt;
  int step = 0;
  const std::string digits = match[2].str();
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), step);
  if (error != std::errc{} || end != digits.data() + digits.size()) return std::nullopt;
  return step;
}

/// The (time, file) entries of a .pvd collection written by write_pvd; none if the file does not exist.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& path) {
  std::vector<PvdEntry> entries;
  std::ifstream in(path);
  if (!in) return entries;
  const std::regex data_set(R"re(\s*<DataSet timestep="([^"]*)" group="" part="0" file="([^"]*)"/>\s*)re");
  std::string line;
  while (std::getline(in, line)) {
    std::smatch match;
    if (!std::regex_match(line, match, data_set)) continue;
    const std::string time_text = match[1].str();
    double time = 0.0;
    const auto [end, error] = std::from_chars(time_text.data(), time_text.data() + time_text.size(), time);
    if (error != std::errc{} || end != time_text.data() + time_text.size())
      throw std::runtime_error("'" + path.string() + "': unreadable timestep '" + time_text + "'");
    entries.push_back({time, match[2].str()});
  }
  return entries;
}

}  // namespace

void VtkSeries::resume(int last_step, bool contact) {
  const std::filesystem::path vtk = dir_ / "vtk";
  std::error_code error;
  std::filesystem::create_directories(vtk, error);
  if (error) throw_write_error("create folder", vtk, error.value());
  const std::regex series_file(R"((step|contact)_([0-9]{6,})\.vtp)");
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(vtk, error)) {
    if (!entry.is_regular_file()) continue;
    const auto step = series_step(entry.path().filename().string(), series_file);
    if (step && *step > last_step) stale.push_back(entry.path());
  }
  if (error) throw std::runtime_error("cannot list folder '" + vtk.string() + "': " + error.message());
  if (!contact && std::filesystem::exists(contact_pvd_path())) stale.push_back(contact_pvd_path());
  for (const auto& path : stale) {
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
  const std::regex entry_file(R"(vtk/(step|contact)_([0-9]{6,})\.vtp)");
  const auto take_up = [&](Collection& collection, const std::filesystem::path& pvd) {
    collection.clear();
    for (const PvdEntry& e : read_pvd(pvd)) {
      const auto step = series_step(e.file, entry_file);
      if (step && *step <= last_step) collection.add(*step, e.time, e.file);
    }
    write_pvd(pvd, collection.entries);
  };
  take_up(beams_, pvd_path());
  contact_.clear();
  if (contact) take_up(contact_, contact_pvd_path());
  begun_ = true;
}

void VtkSeries::write(int step, double time, const model::Model& model, const Eigen::VectorXd& x,
                      const contact::ContactGeometry* contact,
                      const std::vector<simulation::ContactState>* states) {
  if (!begun_) begin(contact != nullptr);
  const std::string name = file_name(step);
  AtomicFile beams(dir_ / "vtk" / name);
  write_vtp(beams.stream(), model, x, tube_sides_, time, encoding_);
  std::optional<AtomicFile> contacts;
  std::string contact_name;
  if (contact) {
    contact_name = contact_file_name(step);
    contacts.emplace(dir_ / "vtk" / contact_name);
    write_contact_vtp(contacts->stream(), *contact, time, states, encoding_);
  }
  last_bytes_ = beams.size() + (contacts ? contacts->size() : 0);
  require_space(dir_ / "vtk", last_bytes_, beams.path());
  beams.commit();
  beams_.add(step, time, "vtk/" + name);
  write_pvd(pvd_path(), beams_.entries);
  if (contacts) {
    contacts->commit();
    contact_.add(step, time, "vtk/" + contact_name);
    write_pvd(contact_pvd_path(), contact_.entries);
  }
}

}  // namespace nodus::output
