#include "nodus/run/run_outputs.hpp"

#include <utility>

namespace nodus::run {

RunOutputs::RunOutputs(const std::filesystem::path& dir, const scenario::Scenario& scenario, bool quiet,
                       bool write_summary, std::string label, const std::filesystem::path& timing)
    : steps_(dir),
      timing_(dir),
      vtk_(dir, scenario.output.vtk_every, scenario.output.tube_sides, scenario.output.vtk_format),
      final_nodes_(dir),
      contact_tables_(dir),
      stage_ends_(dir),
      summary_(dir, write_summary),
      result_h5_(dir, scenario.output.vtk_every, scenario.output.hdf5),
      checkpoints_(dir, scenario.output.checkpoint_every),
      progress_(scenario.output.progress_seconds, std::move(label),
                quiet            ? std::filesystem::path()
                : timing.empty() ? timing_.path()
                                 : timing,
                !timing.empty()) {
  // The checkpoint comes after the files of its step, so that they are complete up to it.
  // result.h5 after steps.csv, whose rows it takes up on resuming.
  observers_ = {&steps_,      &timing_,  &vtk_,       &final_nodes_, &contact_tables_,
                &stage_ends_, &summary_, &result_h5_, &checkpoints_};
  if (!quiet) observers_.push_back(&progress_);
}

const std::vector<simulation::StepObserver*>& no_observers() {
  static const std::vector<simulation::StepObserver*> none;
  return none;
}

}  // namespace nodus::run
