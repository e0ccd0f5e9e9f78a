#pragma once
/// VTK output of a run: a picture of the initial state, of every `every`-th converged step and of the final
/// converged state, collected in DIR/result.pvd (see vtk_format.hpp and vtk_series.hpp); when the run has
/// contact (Simulation::contact() not null), a picture of the contact geometry for the same steps, collected
/// in DIR/contact.pvd (see contact_vtk.hpp).

#include <filesystem>

#include "nodus/output/vtk_series.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

class VtkSeriesWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder (files go to DIR/vtk/, DIR/result.pvd and DIR/contact.pvd); `every`: write every
  /// N-th converged step (0: only the initial and the final state), >= 0; `tube_sides`: facets around each
  /// tube, >= 3. Throws std::invalid_argument on bad settings.
  VtkSeriesWriter(std::filesystem::path dir, int every, int tube_sides);

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  const VtkSeries& series() const { return series_; }

 private:
  VtkSeries series_;
  int every_;
  int last_step_ = 0;  ///< last converged step seen (0: the initial state)
};

}  // namespace nodus::output
