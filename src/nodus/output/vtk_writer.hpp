#pragma once
/// VTK output of a run: a picture of the initial state (for a branch, of the state it starts from, under the
/// step number it has there), of every `every`-th converged step and of the final converged state, collected
/// in DIR/result.pvd (see vtk_format.hpp and vtk_series.hpp); when the run has contact (Simulation::contact()
/// not null), a picture of the contact geometry for the same steps, collected in DIR/contact.pvd (see
/// contact_vtk.hpp), carrying the contact forces when the run has them; and with output.contact_csv, the
/// contact element table of the same steps as DIR/contact/contact_NNNNNN.csv (see contact_csv_writer.hpp). A
/// run that resumes an interrupted one takes up its series at the resumed step instead of starting anew.

#include <filesystem>

#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/vtk_series.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

class VtkSeriesWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder (files go to DIR/vtk/, DIR/result.pvd, DIR/contact.pvd and DIR/contact/); `every`:
  /// write every N-th converged step (0: only the initial and the final state), >= 0; `tube_sides`: facets
  /// around each tube, >= 3; `encoding`: of the VTK files. Throws std::invalid_argument on bad settings.
  /// Whether the contact tables are written is read from the scenario (output.contact_csv) when the run
  /// starts. A run that starts afresh writes its initial picture, then warns if the free space of the disk
  /// is less than that picture's size times the pictures its stages' nominal steps will write.
  VtkSeriesWriter(std::filesystem::path dir, int every, int tube_sides,
                  VtkEncoding encoding = VtkEncoding::binary);

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;
  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  const VtkSeries& series() const { return series_; }
  const ContactCsvSeries& contact_tables() const { return contact_tables_; }

 private:
  /// The files of output step `step` (load time `time` [s]) from the current state of `sim`.
  void write(const simulation::Simulation& sim, int step, double time);
  /// The warning of a run whose pictures will not fit on the disk (see the constructor).
  void warn_if_short_of_space(const simulation::Simulation& sim) const;

  VtkSeries series_;
  ContactCsvSeries contact_tables_;
  int every_;
  bool contact_csv_ = false;  ///< output.contact_csv of the running scenario
  int last_step_ = 0;         ///< last converged step seen (0: the initial state)
};

}  // namespace nodus::output
