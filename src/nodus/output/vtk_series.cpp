#include "nodus/output/vtk_series.hpp"

#include <algorithm>
#include <regex>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

namespace nodus::output {

VtkSeries::VtkSeries(std::filesystem::path dir, int tube_sides)
    : dir_(std::move(dir)), tube_sides_(tube_sides) {
  if (tube_sides_ < 3)
    throw std::invalid_argument(fmt::format("VTK output: tube_sides = {}, must be >= 3", tube_sides_));
}

std::string VtkSeries::file_name(int step) {
  return fmt::format("step_{:06d}.vtp", step);
}

void VtkSeries::begin() {
  const std::filesystem::path vtk = dir_ / "vtk";
  std::error_code error;
  std::filesystem::create_directories(vtk, error);
  if (error) throw std::runtime_error("cannot create folder '" + vtk.string() + "': " + error.message());
  const std::regex step_file(R"(step_[0-9]{6,}\.vtp)");
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(vtk, error))
    if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), step_file))
      stale.push_back(entry.path());
  if (error) throw std::runtime_error("cannot list folder '" + vtk.string() + "': " + error.message());
  for (const auto& path : stale) {
    std::filesystem::remove(path, error);
    if (error) throw std::runtime_error("cannot remove old file '" + path.string() + "': " + error.message());
  }
  steps_.clear();
  entries_.clear();
  write_pvd(pvd_path(), entries_);
  begun_ = true;
}

bool VtkSeries::written(int step) const {
  return std::find(steps_.begin(), steps_.end(), step) != steps_.end();
}

void VtkSeries::write(int step, double time, const model::Model& model, const Eigen::VectorXd& x) {
  if (!begun_) begin();
  const std::string name = file_name(step);
  write_vtp(dir_ / "vtk" / name, model, x, tube_sides_, time);
  const auto it = std::find(steps_.begin(), steps_.end(), step);
  if (it == steps_.end()) {
    steps_.push_back(step);
    entries_.push_back({time, "vtk/" + name});
  } else {
    entries_[static_cast<std::size_t>(it - steps_.begin())].time = time;
  }
  write_pvd(pvd_path(), entries_);
}

}  // namespace nodus::output
