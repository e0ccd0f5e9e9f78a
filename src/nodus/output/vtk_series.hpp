#pragma once
/// A series of VTK pictures of one run: DIR/vtk/step_NNNNNN.vtp files and the collection DIR/result.pvd that
/// lists them with their load times, rewritten after every file so that it is valid at any moment.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"
#include "nodus/output/vtk_format.hpp"

namespace nodus::output {

class VtkSeries {
 public:
  /// `dir`: output folder; `tube_sides`: facets around each tube (>= 3).
  VtkSeries(std::filesystem::path dir, int tube_sides);

  /// Creates DIR/vtk, removes step_*.vtp files left there by an earlier run and writes an empty result.pvd.
  void begin();
  /// Writes DIR/vtk/step_NNNNNN.vtp (NNNNNN = `step`, six digits at least) of state `x` at load time `time`
  /// [s], then rewrites result.pvd. Writing a step again replaces its file and entry.
  void write(int step, double time, const model::Model& model, const Eigen::VectorXd& x);

  bool begun() const { return begun_; }
  bool written(int step) const;
  /// The files written so far, in order of writing.
  const std::vector<PvdEntry>& entries() const { return entries_; }
  /// DIR/result.pvd.
  std::filesystem::path pvd_path() const { return dir_ / "result.pvd"; }
  /// "step_000012.vtp" for step 12.
  static std::string file_name(int step);

 private:
  std::filesystem::path dir_;
  int tube_sides_;
  bool begun_ = false;
  std::vector<int> steps_;  ///< step of each entry
  std::vector<PvdEntry> entries_;
};

}  // namespace nodus::output
