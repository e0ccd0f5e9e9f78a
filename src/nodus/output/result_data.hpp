#pragma once
/// A run's results as read back from its result.h5 (docs/output.md): the beams, every output state with
/// its nodes and contact elements, the stages and the branches. What `nodus view` draws and what tests
/// compare with the CSV files. Units: mm, N, MPa, s.

#include <array>
#include <map>
#include <string>
#include <vector>

namespace nodus::output {

/// One beam of the scenario, in the order of the scenario (its index is the `beam` of the VTK files).
struct ResultBeam {
  std::string name;
  double radius = 0.0;         ///< section radius [mm]
  double young_modulus = 0.0;  ///< E of its material [MPa]
  int first_node = 0;          ///< global number of its first node (beams numbered one after the other)
  int node_count = 0;          ///< its nodes; element e joins nodes first_node + e and first_node + e + 1
  bool tool = false;           ///< a tool beam (a `rigid` condition moves it), drawn greyed
};

/// The contact elements of one state, column by column as in contact_final.csv (one entry per element).
struct ResultContacts {
  std::vector<int> zone;
  std::vector<int> beam_i, beam_j;         ///< beam indices into ResultRun::beams
  std::vector<std::array<double, 3>> x_i;  ///< particle on beam I [mm]
  std::vector<std::array<double, 3>> x_j;  ///< particle on beam J [mm]
  std::vector<std::array<double, 3>> normal;
  std::vector<double> gap;               ///< [mm], negative when the surfaces overlap
  std::vector<double> normal_force;      ///< R_N [N]; empty for a state without forces
  std::vector<double> tangential_force;  ///< |T| [N]; empty for a state without forces
  std::vector<std::string> state;        ///< open, stick or slip; empty for a state without forces
  std::size_t size() const { return x_i.size(); }
};

/// One output state (the steps of the VTK files: step 0, every output.vtk_every-th step, the last one).
struct ResultState {
  int step = 0;            ///< converged step number (0: the initial state)
  double load_time = 0.0;  ///< [s]
  std::string stage;       ///< name of the stage the step belongs to (the first stage's for step 0)
  std::vector<std::array<double, 3>> centre, g1, g2;  ///< per node: section centre [mm] and directors [-]
  /// Per-node measures by name, as in the VTK files: e11 ... e33 [-], q11 ... q22 [1/mm], k1, k2 [1/mm],
  /// m11, m22, m12 [1/mm^2].
  std::map<std::string, std::vector<double>> node_fields;
  ResultContacts contacts;  ///< empty without contact
};

struct ResultStage {
  std::string name;
  double start_time = 0.0, end_time = 0.0;  ///< load time [s] at its start and end
};

/// A run: the main run of a folder, or one of its branches (a run of its own from a stage-end state).
struct ResultRun {
  std::string name;  ///< "main", or the branch's name
  std::vector<ResultBeam> beams;
  std::vector<ResultStage> stages;
  std::vector<ResultState> states;  ///< in step order
  std::vector<ResultRun> branches;
};

}  // namespace nodus::output
