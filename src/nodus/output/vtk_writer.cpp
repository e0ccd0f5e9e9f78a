#include "nodus/output/vtk_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_table.hpp"

namespace nodus::output {

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path dir, int every, int tube_sides, VtkEncoding encoding)
    : series_(dir, tube_sides, encoding), contact_tables_(dir), every_(every) {
  if (every_ < 0) throw std::invalid_argument(fmt::format("VTK output: every = {}, must be >= 0", every_));
}

void VtkSeriesWriter::write(const simulation::Simulation& sim, int step, double time) {
  const std::vector<simulation::ContactState>* states = contact_states_to_write(sim);
  series_.write(step, time, sim.model(), sim.state(), sim.contact(), states);
  if (contact_csv_ && sim.contact())
    contact_tables_.write(step, *sim.contact(), beam_names(sim.model()), states);
}

void VtkSeriesWriter::on_start(const simulation::Simulation& sim) {
  contact_csv_ = sim.scenario().output.contact_csv;
  last_step_ = sim.steps();
  if (sim.start_kind() == simulation::StartKind::resumed) {
    series_.resume(last_step_, sim.contact() != nullptr);
    contact_tables_.resume(last_step_);
    return;
  }
  series_.begin(sim.contact() != nullptr);
  contact_tables_.begin();
  write(sim, last_step_, sim.time());
  warn_if_short_of_space(sim);
}

void VtkSeriesWriter::warn_if_short_of_space(const simulation::Simulation& sim) const {
  std::uintmax_t steps = 0;
  for (const scenario::StageSpec& stage : sim.scenario().stages)
    steps += static_cast<std::uintmax_t>(stage.steps);
  const auto every = static_cast<std::uintmax_t>(every_);
  const std::uintmax_t due = every > 0 ? (steps + every - 1) / every : 1;
  const std::uintmax_t bytes = due * series_.last_bytes();
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(series_.dir(), error);
  if (error || space.available >= bytes) return;
  spdlog::warn(
      "the pictures of this run may not fit on its disk: {} more VTK outputs of {} each at least ({}), {} "
      "free "
      "in '{}'; the run will stop where the disk is full and can then be resumed (output.vtk_every sets how "
      "often they are written)",
      due, human_size(series_.last_bytes()), human_size(bytes), human_size(space.available),
      series_.dir().string());
}

void VtkSeriesWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  last_step_ = record.step;
  if (every_ > 0 && record.step % every_ == 0) write(sim, record.step, record.time);
}

void VtkSeriesWriter::on_finish(const simulation::Simulation& sim,
                                const simulation::RunSummary& /*summary*/) {
  if (!series_.written(last_step_)) write(sim, last_step_, sim.time());
}

}  // namespace nodus::output
