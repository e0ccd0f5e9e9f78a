#pragma once
/// A scenario: what a YAML file describes, resolved and validated. Units throughout: mm, N, MPa, s.
/// Every field maps one to one onto a key of the file; docs/scenario.md documents each key.

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::scenario {

using Vec3 = Eigen::Vector3d;

/// Bad user input: the message is one line "FILE:LINE: KEY: expected ..., got ...".
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Isotropic elastic material.
struct Material {
  std::string name;
  double young_modulus = 0.0;  ///< E [MPa], > 0
  double poisson_ratio = 0.0;  ///< nu [-], in [0, 0.5)
};

/// A straight beam in its reference configuration.
struct BeamSpec {
  std::string name;
  int material = 0;                ///< index into Scenario::materials
  double radius = 0.0;             ///< R [mm], > 0
  double length = 0.0;             ///< L [mm], > 0
  int elements = 0;                ///< number of 3-node quadratic elements, >= 1
  Vec3 start = Vec3::Zero();       ///< centre of the first end section [mm]
  Vec3 direction = Vec3::UnitX();  ///< unit axis direction (normalised by the reader)
  Vec3 director1 =
      Vec3::UnitY();  ///< unit first section director, orthogonal to direction (made so by the reader)
  double bending_factor = 1.0;  ///< multiplies the second moment of area in bending (Table 1: 0.3), > 0
};

/// Index of the nine nodal unknowns: centre r, then directors g1 and g2.
enum Dof : int { kX = 0, kY, kZ, kG1x, kG1y, kG1z, kG2x, kG2y, kG2z };
using DofMask = std::array<bool, 9>;

enum class ConditionType {
  clamp,   ///< the selected dofs keep the values they have when the condition is activated
  motion,  ///< the selected dofs follow a prescribed translation and rotation of the section (stage targets)
  rigid,   ///< every dof of every node of the beam follows a rigid motion (a tool beam; stage targets)
  load,    ///< dead force on the centre and moment about a fixed axis, applied to the section
};

/// A named boundary condition on one cross-section (node) of one beam.
struct ConditionSpec {
  std::string name;
  ConditionType type = ConditionType::clamp;
  int beam = 0;                  ///< index into Scenario::beams
  int node = 0;                  ///< local node index on the beam, resolved from "at" (start = 0, end = 2n)
  DofMask dofs{};                ///< clamp and motion: the constrained dofs (default: all nine)
  bool initially_active = true;  ///< active from the first stage on, unless false
  Vec3 force = Vec3::Zero();     ///< load: initial force [N]
  Vec3 moment = Vec3::Zero();    ///< load: initial moment [N mm]
  std::optional<Vec3> pivot;     ///< motion, rigid: the point the rotation turns about [mm]
  /// load: the fixed axis of its moment (unit), the direction of its first nonzero moment value in the file
  /// (initial value, stages, then the branches' stages); none if every value is zero. Set by the reader.
  std::optional<Vec3> moment_axis;
  int line = 0;  ///< line of the condition in the file (for messages)
};

/// A keyframe of a prescribed motion inside a stage, cumulative since the condition was activated.
struct Keyframe {
  double at = 1.0;                  ///< fraction of the stage, in (0, 1], increasing
  Vec3 translation = Vec3::Zero();  ///< of the section centre [mm]
  Vec3 rotation = Vec3::Zero();     ///< rotation vector of the section [degrees]
};

struct MotionTarget {
  int condition = 0;                ///< index into Scenario::conditions (type motion)
  std::vector<Keyframe> keyframes;  ///< at least one; the last one has at = 1
};

struct LoadTarget {
  int condition = 0;           ///< index into Scenario::conditions (type load)
  Vec3 force = Vec3::Zero();   ///< value reached at the end of the stage [N]
  Vec3 moment = Vec3::Zero();  ///< value reached at the end of the stage [N mm]
};

/// One stage of the loading program.
struct StageSpec {
  std::string name;
  int steps = 1;              ///< number of nominal load steps, >= 1
  double duration = 1.0;      ///< length of the stage in load time [s], > 0
  std::vector<int> activate;  ///< conditions switched on at the start of the stage
  std::vector<int> release;   ///< conditions switched off at the start of the stage
  std::vector<MotionTarget> motions;
  std::vector<LoadTarget> loads;
  std::vector<int> contact_off;  ///< beams taken out of contact at the start of the stage (tools removed)
  std::vector<int> contact_on;   ///< beams put back into contact at the start of the stage
  /// Viscous stabilisation [N s/mm^2] at the start and at the end of the stage (geometric in between; an end
  /// value of 0 decays to 1e-6 of the start value and is exactly 0 at the stage end); 0: none.
  double stabilization = 0.0;
  double stabilization_end = 0.0;
};

enum class LinearSolverKind { cholmod, umfpack };

/// The `solver` section. The Newton and stepping defaults are the library's (solver::NewtonSettings,
/// solver::StepControl); the others equal those of the library structs that take them, which a test checks
/// (tests/scenario/test_scenario_keys.cpp).
struct SolverSettings {
  LinearSolverKind linear_solver = LinearSolverKind::cholmod;
  int max_newton_iterations = ::nodus::solver::NewtonSettings{}.max_iterations;  ///< per step attempt, >= 1
  double residual_tolerance = 1e-8;   ///< |R| <= tol * force scale [-], > 0
  double increment_tolerance = 1e-6;  ///< |du|_inf <= tol * length scale [-], > 0
  /// Successive halvings of a step before giving up, >= 0.
  int max_cutbacks = ::nodus::solver::StepControl{}.max_cutbacks;
  /// A step converged in at most this many iterations lets the next grow, >= 1.
  int easy_iterations = ::nodus::solver::StepControl{}.easy_iterations;
  /// Damp the Newton updates by a line search: slower on every verification case so far (docs/model.md).
  bool line_search = ::nodus::solver::NewtonSettings{}.line_search;
  int gauss_points = 2;         ///< Gauss points per element along the axis, 1..5
  double fold_stiffness = 0.0;  ///< beta of the fold stabilisation (beam_element.hpp), >= 0
};

struct OutputSettings {
  int vtk_every = 1;              ///< write a VTK file every N converged steps (0: only the final state)
  int tube_sides = 12;            ///< facets around each tube in the VTK output, >= 3
  double progress_seconds = 1.0;  ///< minimum interval between progress lines on stderr [s]
  bool contact_csv = false;       ///< also write contact/contact_NNNNNN.csv at every VTK output step
  int checkpoint_every = 0;  ///< also save the run's state every N converged steps (0: at stage ends only)
};

/// How Newton's tangent linearises the friction force (contact.friction_tangent; docs/contact.md). The force
/// itself is the same either way.
enum class FrictionTangent {
  frozen,   ///< R_N held fixed, as in Durville 2012, Sect. 5.3: symmetric, any linear solver
  varying,  ///< the exact derivative, R_N varying: not symmetric, needs LU (umfpack)
};

/// Contact detection settings: the `contact` section (docs/scenario.md, docs/contact.md). Lengths <= 0 mean
/// "auto": derived from the radii and element lengths when the simulation starts.
struct ContactSettings {
  bool enabled = false;      ///< true when the file has a contact section, unless contact.enabled: false
  bool self_contact = true;  ///< also between separate parts of one beam
  std::vector<int> beams;    ///< indices into Scenario::beams that take part; empty: all beams
  double proximity_distance = 0.0;   ///< delta_prox [mm], auto if <= 0
  double separation_distance = 0.0;  ///< delta_separ [mm], auto if <= 0
  double test_point_spacing = 0.0;   ///< h_dist [mm], auto if <= 0
  double matching_length = 0.0;      ///< l_p [mm], auto if <= 0
  double element_spacing = 0.0;      ///< h_c [mm], auto if <= 0
  // Contact mechanics (Sect. 5-6).
  bool forces = true;                ///< apply contact forces; false: detection only
  double penalty = 0.0;              ///< initial k_c per zone [N/mm], auto if <= 0
  double max_penetration = 0.0;      ///< p_max [mm], auto if <= 0
  double regularization = 0.0;       ///< p_reg [mm], auto if <= 0
  double friction = 0.0;             ///< mu [-], >= 0
  double max_reversible_slip = 0.0;  ///< g_rev_max [mm], auto if <= 0
  FrictionTangent friction_tangent = FrictionTangent::frozen;
  /// Particles at the facing points of the sections during Newton (contact.particles: facing); false: the
  /// paper's fixed material particles (fixed).
  bool facing_particles = false;
  int max_detections = 4;          ///< loop 2: detections of contact elements per step, >= 1
  int max_normal_iterations = 6;   ///< loop 3: updates of the normals per detection, >= 1
  double normal_tolerance = 1e-3;  ///< loop 3 stops when no normal turns by more than this [rad], > 0
};

/// A run that continues from the state at the end of one stage of Scenario::stages (key `branches`).
struct BranchSpec {
  std::string name;                ///< unique among branches; also its output folder DIR/branches/NAME
  int from = 0;                    ///< index into Scenario::stages: the branch starts from the end of it
  std::optional<double> friction;  ///< overrides contact.friction for the branch's stages [-], >= 0
  std::vector<StageSpec> stages;   ///< run after stage `from`, names unique within the branch
  int line = 0;                    ///< line of the branch in the file (for messages)
};

/// What makes the scenario of a branch (branch_scenario) a continuation of its parent run.
struct BranchOrigin {
  std::string name;              ///< BranchSpec::name
  int from = 0;                  ///< stages 0 .. from are the parent's, run with the parent's friction
  double parent_friction = 0.0;  ///< contact.friction of the parent run [-]
};

struct Scenario {
  std::string path;  ///< the file it was read from
  std::vector<Material> materials;
  std::vector<BeamSpec> beams;
  std::vector<ConditionSpec> conditions;
  std::vector<StageSpec> stages;
  SolverSettings solver;
  OutputSettings output;
  ContactSettings contact;
  std::vector<BranchSpec> branches;
  /// Set on the scenario of a branch (branch_scenario), empty for a scenario read from a file.
  std::optional<BranchOrigin> origin;
};

/// Reads and validates a scenario file. Throws ScenarioError with a one-line message on bad input.
Scenario read_scenario(const std::string& path);

/// Same, from YAML text; `path` is used in messages only.
Scenario parse_scenario(const std::string& yaml_text, const std::string& path);

/// The scenario of branch `branch` of `main` as a run of its own: the stages of `main` up to and including
/// the branch's `from`, then the branch's stages; contact.friction overridden if the branch says so; no
/// branches; `origin` set. A run of it that starts from the state of `main` at the end of stage `from`
/// continues `main` as the branch asks.
Scenario branch_scenario(const Scenario& main, std::size_t branch);

/// The table of all keys of the file format (name, type, unit, default, range, help) as a markdown table;
/// the same table drives the reader's messages (see keys.hpp) and is pasted into docs/scenario.md.
std::string scenario_keys_markdown();

}  // namespace nodus::scenario

// The echo and the fingerprint of a scenario: part of this header's API, declared in their own files.
#include "nodus/scenario/describe.hpp"     // IWYU pragma: export
#include "nodus/scenario/fingerprint.hpp"  // IWYU pragma: export
