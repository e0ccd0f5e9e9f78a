#pragma once
/// The readers of the sections of a scenario file, each turning one part of the YAML tree into its part of
/// Scenario, with the one-line messages of Reader. Internal to the scenario module: model_readers.cpp
/// (materials, beams, conditions), yarn_readers.cpp (yarns), loading_readers.cpp (stages, branches),
/// settings_readers.cpp (units, solver, output, contact).

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

/// director1 may not be within this |sin angle| of direction.
constexpr double kDirectorParallelTolerance = 1e-6;
/// Nonzero moments of one load must be parallel within this |sin angle|.
constexpr double kMomentAxisTolerance = 1e-9;
/// Upper limit of beams[].elements, so that node indices 2 * elements fit an int with room to spare.
constexpr int kMaxElements = 100'000'000;

constexpr std::string_view kDofNames[] = {"x", "y", "z", "g1x", "g1y", "g1z", "g2x", "g2y", "g2z"};

// What the messages of cross-field checks expect, shared by the readers and validate().
constexpr std::string_view kMatchingLengthExpected =
    ">= test_point_spacing (successive matching intervals must overlap)";
constexpr std::string_view kSeparationDistanceExpected =
    "> proximity_distance (neighbouring parts of a beam would be paired)";
constexpr std::string_view kStabilizationEndExpected =
    "0 when stabilization is 0 (the decay is geometric from stabilization)";
constexpr std::string_view kStageParticlesExpected = "no particles in a stage without a contact section";
// A bind holds the translations of several bodies together by a penalty, from activation to the end.
constexpr std::string_view kBindBodiesExpected = "two or more bodies for a bind condition";
constexpr std::string_view kBindDofsExpected = "dofs among position | x | y | z for a bind condition";
constexpr std::string_view kBindOnBodiesExpected =
    "a type other than bind without bodies (a bind holds the translations of two or more bodies together)";
constexpr std::string_view kReleaseBindExpected =
    "a condition that is not a bind (a bind holds its bodies together to the end of the run)";
// A clamp or motion of several bodies holds them together; it is not released as a whole.
constexpr std::string_view kReleaseOnSeveralBodiesExpected =
    "a condition on one body (a clamp or motion of several bodies is released body by body: give each "
    "its own condition)";
// CHOLMOD reads one triangle of the tangent: the varying friction tangent, not symmetric, needs LU. Asked
// for explicitly rather than switched on behind the user's back, so that the file says which solver runs.
constexpr std::string_view kPetscBuildExpected =
    "cholmod, umfpack, mumps or klu (petsc needs nodus built with PETSc: install petsc-dev and rebuild)";
constexpr std::string_view kFrictionTangentExpected =
    "frozen with solver.linear_solver: cholmod (the varying tangent is not symmetric and needs LU: "
    "set solver.linear_solver: umfpack, mumps or klu)";

// The same for the normals linearised in the tangent.
constexpr std::string_view kLinearizedNormalsExpected =
    "nested or inside_newton with solver.linear_solver: cholmod (the linearized normals' tangent is not "
    "symmetric and needs LU: set solver.linear_solver: umfpack, mumps or klu)";

// A stage's own linear solver (stages[].linear_solver): none with petsc, whose ranks share every stage's
// rows; not cholmod where the tangent is not symmetric.
constexpr std::string_view kStageSolverWithPetscExpected =
    "solver (with solver.linear_solver: petsc every stage runs on PETSc, which shares the rows among the MPI "
    "ranks)";

constexpr std::string_view kStageCholmodExpected =
    "solver, umfpack, mumps or klu (the tangent is not symmetric with contact.friction_tangent: varying or "
    "contact.normal_updates: linearized, and cholmod reads one triangle)";

/// What a stage's own linear solver must be, if anything (the reader's and validate()'s checks): empty if
/// `stage`'s choice goes with the scenario's solver and contact settings.
inline std::string_view stage_solver_expected(const StageSpec& stage, const Scenario& s) {
  if (!stage.linear_solver) return {};
  if (s.solver.linear_solver == LinearSolverKind::petsc) return kStageSolverWithPetscExpected;
  const bool unsymmetric = s.contact.friction_tangent == FrictionTangent::varying ||
                           s.contact.normal_updates == NormalUpdates::linearized;
  if (unsymmetric && *stage.linear_solver == LinearSolverKind::cholmod) return kStageCholmodExpected;
  return {};
}

/// What a message expects of a fibre's radius (key pattern `pattern`) that exceeds its length: a beam is
/// slender, its radius at most its length.
std::string radius_expected(std::string_view pattern, double length);

/// The memory a model takes per element while it is built: `nodus check` of the 3x9 and 3x25 yarns (2,700 and
/// 7,500 elements) takes 142 and 320 MB, 37 kB more an element; rounded up.
constexpr double kBytesPerElement = 40e3;
/// The most elements of all beams and yarn fibres together: this machine's physical memory over
/// kBytesPerElement, and at most kMaxElements.
long long max_model_elements();
/// What a message expects of the `elements` key (pattern `pattern`) that takes the model past
/// max_model_elements(), `before` elements being there already.
std::string model_elements_expected(std::string_view pattern, long long before);

/// The test points of contact detection along the contact beams of `s` (contact.beams, or all): the spacing
/// h_dist as the run resolves it (contact::resolve_parameters: auto from the largest radius) and their
/// number, sum over the beams of length / h_dist + 2 (contact/proximity_zone.cpp). Zero points without
/// contact.
struct TestPoints {
  double spacing = 0.0;  ///< [mm]
  double count = 0.0;
};
TestPoints contact_test_points(const Scenario& s);
/// The most test points a model may have: each costs its share of every detection, and a spacing that is
/// tiny against the beams' lengths (or lengths huge against the radius, with the auto spacing) would stall
/// the first detection for hours.
inline long long max_test_points() {
  return 10 * max_model_elements();
}
/// What a message expects of contact.test_point_spacing when contact_test_points() gives too many.
std::string test_points_expected(const TestPoints& points);

/// The word of the file for a condition type: clamp, motion, rigid, load.
std::string_view type_name(ConditionType type);

/// The unit vector orthogonal to `direction` (unit) made from the coordinate axis least parallel to it.
Vec3 default_director(const Vec3& direction);

/// |sin| of the angle between two nonzero vectors.
double sin_angle(const Vec3& a, const Vec3& b);

/// Checks that every nonzero moment of each load keeps the axis of the first nonzero one.
class MomentAxes {
 public:
  void check(const Reader& reader, int condition, const Vec3& moment, const Field& field) {
    if (moment.squaredNorm() == 0.0) return;
    const auto found = first_.find(condition);
    if (found == first_.end()) {
      first_.emplace(condition, std::pair{moment, fmt::format("{} (line {})", field.path, field.line)});
      return;
    }
    if (sin_angle(found->second.first, moment) >= kMomentAxisTolerance) {
      reader.fail(field, fmt::format("a moment parallel to {} given at {} (moment axis must stay fixed)",
                                     format_vec(found->second.first), found->second.second));
    }
  }

  /// The direction of the first nonzero moment of `condition` (unit); none if it had none.
  std::optional<Vec3> axis(int condition) const {
    const auto found = first_.find(condition);
    if (found == first_.end()) return std::nullopt;
    return found->second.first.normalized();
  }

 private:
  std::map<int, std::pair<Vec3, std::string>> first_;
};

/// The value (force, moment) each load has, by condition.
using LoadValues = std::map<int, std::pair<Vec3, Vec3>>;

/// The values the loads start with: their initial values.
LoadValues initial_load_values(const std::vector<ConditionSpec>& conditions);

void read_units(const Reader& reader, const MapView& top);

std::vector<Material> read_materials(const Reader& reader, const MapView& top, NameTable& names);

std::vector<BeamSpec> read_beams(const Reader& reader, const MapView& top, const NameTable& materials,
                                 NameTable& names);

/// Reads `yarns` (yarn_readers.cpp), if present: each yarn checked, then appended with its fibres and
/// bodies (append_yarn) to `scenario`, the fibres' names added to `beam_names`. Without beams in the file
/// the list must not be empty.
void read_yarns(const Reader& reader, const MapView& top, const NameTable& materials, NameTable& beam_names,
                Scenario& scenario);

/// The `bodies` section (empty if absent). Body names go to `names`.
std::vector<BodySpec> read_bodies(const Reader& reader, const MapView& top, const NameTable& beam_names,
                                  const std::vector<BeamSpec>& beams, NameTable& names);

/// The `conditions` section; a condition may not take the name of a body (`body_names`), since both name
/// columns of steps.csv.
std::vector<ConditionSpec> read_conditions(const Reader& reader, const MapView& top,
                                           const NameTable& beam_names, const std::vector<BeamSpec>& beams,
                                           const NameTable& body_names, NameTable& names,
                                           MomentAxes& moment_axes);

/// A list of stages (`stages`, or a branch's `stages`: `list` then has the pattern "stages" and its own
/// path). `load_values`: the value of each load at the start of the first stage, updated stage by stage;
/// `after_each`, if given, receives them after each stage. `stage_names` receives the names.
std::vector<StageSpec> read_stages(const Reader& reader, const Field& list, const NameTable& condition_names,
                                   const std::vector<ConditionSpec>& conditions, const NameTable& beam_names,
                                   const ContactSettings& contact, MomentAxes& moment_axes,
                                   LoadValues& load_values, NameTable& stage_names,
                                   std::vector<LoadValues>* after_each = nullptr);

std::vector<BranchSpec> read_branches(const Reader& reader, const MapView& top, const NameTable& stage_names,
                                      const std::vector<LoadValues>& load_values_after,
                                      const NameTable& condition_names,
                                      const std::vector<ConditionSpec>& conditions,
                                      const NameTable& beam_names, const ContactSettings& contact,
                                      bool has_contact_section, MomentAxes& moment_axes);

SolverSettings read_solver(const Reader& reader, const MapView& top);

OutputSettings read_output(const Reader& reader, const MapView& top);

ContactSettings read_contact(const Reader& reader, const MapView& top, const NameTable& beam_names);

}  // namespace nodus::scenario
