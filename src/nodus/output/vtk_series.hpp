#pragma once
/// A series of VTK pictures of one run: DIR/vtk/step_NNNNNN.vtp files and the collection DIR/result.pvd that
/// lists them with their load times, rewritten after every file so that it is valid at any moment. With a
/// contact geometry, the same steps also get DIR/vtk/contact_NNNNNN.vtp (contact_vtk.hpp), collected in
/// DIR/contact.pvd.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"
#include "nodus/output/vtk_format.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::output {

class VtkSeries {
 public:
  /// `dir`: output folder; `tube_sides`: facets around each tube (>= 3); `encoding`: of every file.
  VtkSeries(std::filesystem::path dir, int tube_sides, VtkEncoding encoding = VtkEncoding::binary);

  /// Creates DIR/vtk, removes step_*.vtp and contact_*.vtp files left there by an earlier run and writes an
  /// empty result.pvd; with `contact`, also an empty contact.pvd, without, removes a contact.pvd left by an
  /// earlier run.
  void begin(bool contact = false);
  /// Takes up the series of an interrupted run at its step `last_step`: reads the entries of result.pvd (and
  /// with `contact` of contact.pvd) up to that step, removes the step_*.vtp and contact_*.vtp files of later
  /// steps and rewrites the collections without them; without `contact`, removes a contact.pvd.
  void resume(int last_step, bool contact = false);
  /// Writes DIR/vtk/step_NNNNNN.vtp (NNNNNN = `step`, six digits at least) of state `x` at load time `time`
  /// [s], then rewrites result.pvd. With `contact` (not null), then also writes DIR/vtk/contact_NNNNNN.vtp of
  /// that geometry, with the contact forces of `states` if given (one per element of `contact`; see
  /// write_contact_vtp), and rewrites contact.pvd. Writing a step again replaces its files and entries. Both
  /// pictures are made in memory first: if the disk has not room for them, WriteError says so (require_space)
  /// before either is written.
  void write(int step, double time, const model::Model& model, const Eigen::VectorXd& x,
             const contact::ContactGeometry* contact = nullptr,
             const std::vector<simulation::ContactState>* states = nullptr);

  bool begun() const { return begun_; }
  /// The size of the files of the last write() [bytes], 0 before the first.
  std::uintmax_t last_bytes() const { return last_bytes_; }
  /// Whether the picture of the beams at `step` was written.
  bool written(int step) const { return beams_.has(step); }
  /// The beam files written so far, in order of writing.
  const std::vector<PvdEntry>& entries() const { return beams_.entries; }
  /// The contact files written so far, in order of writing.
  const std::vector<PvdEntry>& contact_entries() const { return contact_.entries; }
  /// DIR.
  const std::filesystem::path& dir() const { return dir_; }
  /// DIR/result.pvd.
  std::filesystem::path pvd_path() const { return dir_ / "result.pvd"; }
  /// DIR/contact.pvd.
  std::filesystem::path contact_pvd_path() const { return dir_ / "contact.pvd"; }
  /// "step_000012.vtp" for step 12.
  static std::string file_name(int step);
  /// "contact_000012.vtp" for step 12.
  static std::string contact_file_name(int step);

 private:
  /// The files of one collection, with the step of each.
  struct Collection {
    std::vector<int> steps;
    std::vector<PvdEntry> entries;
    bool has(int step) const;
    /// Adds the entry of `step`, or updates its time if it is there.
    void add(int step, double time, const std::string& file);
    void clear();
  };

  std::filesystem::path dir_;
  int tube_sides_;
  VtkEncoding encoding_;
  bool begun_ = false;
  std::uintmax_t last_bytes_ = 0;
  Collection beams_;
  Collection contact_;
};

}  // namespace nodus::output
