#include "nodus/output/vtk_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "nodus/output/contact_table.hpp"

namespace nodus::output {

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path dir, int every, int tube_sides)
    : series_(dir, tube_sides), contact_tables_(dir), every_(every) {
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
