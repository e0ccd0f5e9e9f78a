#include "nodus/output/vtk_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace nodus::output {

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path dir, int every, int tube_sides)
    : series_(std::move(dir), tube_sides), every_(every) {
  if (every_ < 0) throw std::invalid_argument(fmt::format("VTK output: every = {}, must be >= 0", every_));
}

void VtkSeriesWriter::on_start(const simulation::Simulation& sim) {
  series_.begin(sim.contact() != nullptr);
  last_step_ = 0;
  series_.write(0, sim.time(), sim.model(), sim.state(), sim.contact());
}

void VtkSeriesWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  last_step_ = record.step;
  if (every_ > 0 && record.step % every_ == 0)
    series_.write(record.step, record.time, sim.model(), sim.state(), sim.contact());
}

void VtkSeriesWriter::on_finish(const simulation::Simulation& sim,
                                const simulation::RunSummary& /*summary*/) {
  if (!series_.written(last_step_))
    series_.write(last_step_, sim.time(), sim.model(), sim.state(), sim.contact());
}

}  // namespace nodus::output
