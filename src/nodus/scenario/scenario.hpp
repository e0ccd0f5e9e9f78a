#pragma once
/// A scenario: what a YAML file describes, resolved and validated. Units throughout: mm, N, MPa, s.
/// Every field maps one to one onto a key of the file; docs/scenario.md documents each key.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection_parameters.hpp"
#include "nodus/model/rotation_vector.hpp"
#include "nodus/model/yarn_layout.hpp"
#include "nodus/output/vtk_encoding.hpp"
#include "nodus/scenario/key.hpp"
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

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<Material>> keys();
};

inline std::span<const Key<Material>> Material::keys() {
  using K = Key<Material>;
  static const K keys[] = {
      K::doc("materials[].name", KeyType::string, "", "required", "unique among materials",
             "name by which beams refer to the material"),
      K::real("materials[].young_modulus", &Material::young_modulus, "MPa", "> 0", ranges::positive,
              "Young's modulus E")
          .shown_default("required"),
      K::real("materials[].poisson_ratio", &Material::poisson_ratio, "", "in [0, 0.5)",
              ranges::below_one_half, "Poisson's ratio nu; the shear modulus is E / (2 (1 + nu))")
          .shown_default("required"),
  };
  return keys;
}

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

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<BeamSpec>> keys();
};

inline std::span<const Key<BeamSpec>> BeamSpec::keys() {
  using K = Key<BeamSpec>;
  static const K keys[] = {
      K::doc("beams[].name", KeyType::string, "", "required", "unique among beams",
             "name by which conditions refer to the beam"),
      K::doc("beams[].material", KeyType::string, "", "required", "naming a material", "the beam's material"),
      K::real("beams[].radius", &BeamSpec::radius, "mm", "> 0", ranges::positive,
              "radius of the circular cross-section")
          .shown_default("required"),
      K::real("beams[].length", &BeamSpec::length, "mm", "> 0", ranges::positive, "length of the beam axis")
          .shown_default("required"),
      K::whole("beams[].elements", &BeamSpec::elements, ">= 1", ranges::at_least_one,
               "number of 3-node quadratic elements; the beam has nodes 0 .. 2 elements")
          .shown_default("required"),
      K::doc("beams[].start", KeyType::vector, "mm", "[0, 0, 0]", "", "centre of the first end section"),
      K::doc("beams[].direction", KeyType::vector, "", "[1, 0, 0]", "with nonzero length",
             "axis direction from start to end; normalised by the reader"),
      K::doc("beams[].director1", KeyType::vector, "", "auto", "not parallel to direction",
             "first section director; orthogonalised against direction and normalised. auto: "
             "the coordinate axis least parallel to direction, orthogonalised"),
      K::real("beams[].bending_factor", &BeamSpec::bending_factor, "", "> 0", ranges::positive,
              "multiplies the second moment of area in bending (Table 1 of the paper uses 0.3)"),
  };
  return keys;
}

/// One cross-section of a beam: the beam and its local node (start = 0, end = 2 elements).
struct SectionRef {
  int beam = 0;  ///< index into Scenario::beams
  int node = 0;  ///< local node index on the beam
};

/// A rigid body bound to fibre end sections by averaged kinematic conditions (docs/bodies.md): six unknowns,
/// the position c of its reference point [mm] (in the reference state the mean of the bound section centres)
/// and its rotation vector theta [rad]. Conditions that name it in `bodies` prescribe, load or release it;
/// without any it is free.
struct BodySpec {
  std::string name;
  std::vector<SectionRef> sections;  ///< the bound sections, at least one, none twice
  double penalty = 0.0;  ///< factor of the penalty of the averaged conditions over E A / h [-], auto if <= 0
  double tie = 0.0;  ///< stiffness of the rearrangement tie as a fraction of the penalty [-], auto if <= 0
  int line = 0;      ///< line of the body in the file (for messages)

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<BodySpec>> keys();
};

inline std::span<const Key<BodySpec>> BodySpec::keys() {
  using K = Key<BodySpec>;
  static const K keys[] = {
      K::doc("bodies[].name", KeyType::string, "", "required", "unique among bodies and conditions",
             "name by which conditions refer to the body"),
      K::doc("bodies[].beams", KeyType::list, "", "required", "of beam names, non-empty, each beam once",
             "the fibres whose end sections the body binds"),
      K::doc("bodies[].at", KeyType::choice, "", "required", "start | end",
             "which end section of each of those beams the body binds"),
      K::real("bodies[].penalty", &BodySpec::penalty, "", "> 0 or auto", ranges::positive,
              "stiffness of the averaged conditions as a multiple of E A / h of the bound fibres (h "
              "the element length); the error it leaves is written to steps.csv. auto: 1e3")
          .or_auto(),
      K::real("bodies[].tie", &BodySpec::tie, "", "> 0 or auto", ranges::positive,
              "stiffness, as a fraction of the penalty, of the tie that resists each step's "
              "rearrangement of the bound sections relative to the body (zero at rest and for rigid "
              "motions), so that sections held by nothing else do not make the tangent singular; its "
              "force is written to steps.csv. auto: 1e-10")
          .or_auto(),
  };
  return keys;
}

/// How the rovings sit in a yarn's section.
enum class YarnPacking {
  ring,  ///< evenly on a circle around the yarn axis, at the angles 2 pi k / rovings (docs/yarns.md)
};

/// A twisted yarn before twisting (`yarns`; docs/yarns.md): `rovings` rovings of `fibres_per_roving`
/// straight parallel fibres, laid out in the section by model::yarn_layout with neighbours 2 R + clearance
/// apart. The reader writes its fibres into Scenario::beams, named NAME.rK.fJ (K, J from 1; roving after
/// roving), after the file's own beams, and with `bodies` two rigid bodies per roving into Scenario::bodies,
/// NAME.rK.start and NAME.rK.end, binding the start (node 0) and end (node 2 elements) sections of the
/// roving's fibres. append_yarn (yarn.hpp) does the same for a scenario built in code.
struct YarnSpec {
  std::string name;
  int rovings = 1;                  ///< m, >= 1
  int fibres_per_roving = 1;        ///< n, >= 1
  double fibre_radius = 0.0;        ///< R [mm], > 0
  double length = 0.0;              ///< L [mm], > 0
  int elements = 0;                 ///< 3-node quadratic elements per fibre, >= 1
  int material = 0;                 ///< index into Scenario::materials
  Vec3 start = Vec3::Zero();        ///< the yarn axis at the fibres' start sections [mm]
  Vec3 direction = Vec3::UnitX();   ///< unit axis direction (normalised by the reader)
  std::optional<double> clearance;  ///< c, gap between neighbouring fibres [mm], >= 0; none: 0.01 R
  model::RovingPacking roving_packing = model::RovingPacking::hexagonal;
  YarnPacking yarn_packing = YarnPacking::ring;
  double bending_factor = 1.0;  ///< as beams[].bending_factor, > 0
  bool bodies = true;           ///< also two rigid bodies per roving
  double tie = 0.0;             ///< bodies[].tie of those bodies, auto if <= 0
  int line = 0;                 ///< line of the yarn in the file (for messages)
  /// Where append_yarn put what it made: Scenario::beams [first_beam, first_beam + m n) and, with `bodies`,
  /// Scenario::bodies [first_body, first_body + 2 m) (roving K: its start body, then its end body).
  int first_beam = 0;
  int first_body = 0;

  /// c [mm]: `clearance`, or its default 0.01 R.
  double gap() const { return clearance ? *clearance : kDefaultClearance * fibre_radius; }
  /// The default clearance as a multiple of R: the fibres start apart by half the default max_penetration
  /// (0.02 R), so that no contact is active in the laid state, whatever the round-off, and contact engages
  /// as soon as twisting closes a gap of a fraction of the tolerated penetration.
  static constexpr double kDefaultClearance = 0.01;

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<YarnSpec>> keys();
};

inline std::span<const Key<YarnSpec>> YarnSpec::keys() {
  using K = Key<YarnSpec>;
  static const K keys[] = {
      K::doc("yarns[].name", KeyType::string, "", "required",
             "unique among yarns; NAME.rK.fJ unique among beams, NAME.rK.start|end among bodies",
             "name of the yarn; its fibres are the beams NAME.rK.fJ, its bodies NAME.rK.start and "
             "NAME.rK.end (K, J from 1)"),
      K::whole("yarns[].rovings", &YarnSpec::rovings, ">= 1", ranges::at_least_one,
               "number of rovings m, evenly around the yarn axis")
          .shown_default("required"),
      K::whole("yarns[].fibres_per_roving", &YarnSpec::fibres_per_roving, ">= 1", ranges::at_least_one,
               "number of fibres n of each roving")
          .shown_default("required"),
      K::real("yarns[].fibre_radius", &YarnSpec::fibre_radius, "mm", "> 0", ranges::positive,
              "radius R of every fibre")
          .shown_default("required"),
      K::real("yarns[].length", &YarnSpec::length, "mm", "> 0", ranges::positive, "length of every fibre")
          .shown_default("required"),
      K::whole("yarns[].elements", &YarnSpec::elements, ">= 1", ranges::at_least_one,
               "3-node quadratic elements of every fibre")
          .shown_default("required"),
      K::doc("yarns[].material", KeyType::string, "", "required", "naming a material",
             "the material of every fibre"),
      K::doc("yarns[].start", KeyType::vector, "mm", "[0, 0, 0]", "",
             "the point of the yarn axis in the fibres' start sections"),
      K::doc("yarns[].direction", KeyType::vector, "", "[1, 0, 0]", "with nonzero length",
             "the yarn axis and every fibre's axis; normalised by the reader. The section axes are "
             "director1 of beams (auto) and direction x director1"),
      K::doc("yarns[].clearance", KeyType::number, "mm", "0.01 fibre_radius", ">= 0",
             "gap between neighbouring fibres of the laid yarn (2 R + clearance between axes)"),
      K::choice(
          "yarns[].roving_packing", "hexagonal | ring",
          [](const YarnSpec& y) { return static_cast<int>(y.roving_packing); },
          [](YarnSpec& y, int i) { y.roving_packing = static_cast<model::RovingPacking>(i); },
          "the fibres in a roving's section. hexagonal: the n points of a hexagonal lattice "
          "nearest to a centre, the most compact; ring: n fibres on a circle (docs/yarns.md)"),
      K::choice(
          "yarns[].yarn_packing", "ring", [](const YarnSpec& y) { return static_cast<int>(y.yarn_packing); },
          [](YarnSpec& y, int i) { y.yarn_packing = static_cast<YarnPacking>(i); },
          "the rovings in the yarn's section. ring: at angles 2 pi k / m around the axis, as close "
          "as the clearance allows (m = 1: centred)"),
      K::real("yarns[].bending_factor", &YarnSpec::bending_factor, "", "> 0", ranges::positive,
              "bending_factor of every fibre (beams[].bending_factor)"),
      K::flag("yarns[].bodies", &YarnSpec::bodies,
              "also two rigid bodies per roving, NAME.rK.start and NAME.rK.end, binding the start and "
              "end sections of its fibres (penalty auto)"),
      K::real("yarns[].tie", &YarnSpec::tie, "", "> 0 or auto", ranges::positive,
              "bodies[].tie of the yarn's bodies: the stiffness, as a fraction of the penalty, of the tie "
              "that resists each step's rearrangement of a roving's end sections; the twist of a yarn of "
              "many fibres per roving converges with 1e-6 (docs/yarns.md). auto: 1e-10")
          .or_auto(),
  };
  return keys;
}

/// Index of the nine nodal unknowns: centre r, then directors g1 and g2.
enum Dof : int { kX = 0, kY, kZ, kG1x, kG1y, kG1z, kG2x, kG2y, kG2z };
using DofMask = std::array<bool, 9>;
/// Index of a rigid body's six unknowns: its reference point, then its rotation vector.
enum BodyDof : int { kBodyX = 0, kBodyY, kBodyZ, kBodyRx, kBodyRy, kBodyRz };
using BodyDofMask = std::array<bool, 6>;

enum class ConditionType {
  clamp,   ///< the selected dofs keep the values they have when the condition is activated
  motion,  ///< the selected dofs follow a prescribed translation and rotation of the section (stage targets)
  rigid,   ///< every dof of every node of the beam follows a rigid motion (a tool beam; stage targets)
  load,    ///< dead force on the centre and moment about a fixed axis, applied to the section
  bind,    ///< two or more bodies' translations held together by a penalty (docs/bodies.md)
};

/// A named boundary condition on one cross-section (node) of one beam.
struct ConditionSpec {
  std::string name;
  ConditionType type = ConditionType::clamp;
  int beam = 0;    ///< index into Scenario::beams
  int node = 0;    ///< local node index on the beam, resolved from "at" (start = 0, end = 2n)
  DofMask dofs{};  ///< clamp and motion: the constrained dofs (default: all nine)
  /// Indices into Scenario::bodies: the condition acts on these rigid bodies instead of a beam section (one
  /// body for a load). Their unknowns are then x, y, z of the reference point and the rotation vector.
  std::vector<int> bodies;
  BodyDofMask body_dofs{};       ///< clamp and motion of bodies: the constrained unknowns (default: all six)
  bool initially_active = true;  ///< active from the first stage on, unless false
  Vec3 force = Vec3::Zero();     ///< load: initial force [N]
  Vec3 moment = Vec3::Zero();    ///< load: initial moment [N mm]
  std::optional<Vec3> pivot;     ///< motion, rigid: the point the rotation turns about [mm]
  /// load: the fixed axis of its moment (unit), the direction of its first nonzero moment value in the file
  /// (initial value, stages, then the branches' stages); none if every value is zero. Set by the reader.
  std::optional<Vec3> moment_axis;
  int line = 0;  ///< line of the condition in the file (for messages)

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<ConditionSpec>> keys();
};

inline std::span<const Key<ConditionSpec>> ConditionSpec::keys() {
  using K = Key<ConditionSpec>;
  static const K keys[] = {
      K::doc("conditions[].name", KeyType::string, "", "required", "unique among conditions",
             "name by which stages refer to the condition"),
      K::choice(
          "conditions[].type", "clamp | motion | rigid | load | bind",
          [](const ConditionSpec& c) { return static_cast<int>(c.type); },
          [](ConditionSpec& c, int i) { c.type = static_cast<ConditionType>(i); },
          "clamp: keep the dofs at their values on activation; motion: prescribed "
          "translation and rotation; rigid: the whole beam follows a rigid motion (a tool "
          "beam, never released); load: force and moment; bind: the listed translations of two or more "
          "bodies move together (a penalty, never released)")
          .shown_default("required"),
      K::doc("conditions[].beam", KeyType::string, "", "required without bodies", "naming a beam",
             "the beam the condition acts on"),
      K::doc("conditions[].bodies", KeyType::list, "", "-",
             "of body names, non-empty, each once; one for a load, two or more for a bind; not with beam, "
             "at or type rigid",
             "the rigid bodies the condition acts on instead of a beam section (docs/bodies.md): their "
             "point c and rotation; a motion moves them all with one rigid motion about pivot"),
      K::doc("conditions[].at", KeyType::choice, "", "required without bodies",
             "start | end | an integer in [0, 2 elements]",
             "the cross-section: start (node 0), end (node 2 elements) or a local node index; "
             "not on rigid"),
      K::doc("conditions[].pivot", KeyType::vector, "mm", "-", "motion and rigid only",
             "the fixed point the prescribed rotation turns the section centres about, r = p +"
             " u + Q (r0 - p); default: the section centre (motion), the centre of the beam's "
             "middle node at activation (rigid), the mean of the bodies' points at activation "
             "(bodies)"),
      K::doc("conditions[].dofs", KeyType::list, "", "[all]",
             "of at least one of all | position | directors | x | y | z | g1x | g1y | g1z | "
             "g2x | g2y | g2z; on bodies: all | position | rotation | x | y | z | rx | ry | rz; "
             "bind: position | x | y | z, default position",
             "clamp, motion and bind only: the constrained dofs, the union of the items (position = "
             "x, y, z; directors = the six g*; rotation = rx, ry, rz, a body's rotation vector)"),
      K::flag("conditions[].active", &ConditionSpec::initially_active, "active from the first stage on"),
      K::doc("conditions[].force", KeyType::vector, "N", "[0, 0, 0]", "",
             "load only: initial dead force on the section centre"),
      K::doc("conditions[].moment", KeyType::vector, "N mm", "[0, 0, 0]", "",
             "load only: initial moment about the fixed axis of its vector"),
  };
  return keys;
}

/// A keyframe of a prescribed motion inside a stage, cumulative since the condition was activated.
struct Keyframe {
  double at = 1.0;                  ///< fraction of the stage, in (0, 1], increasing
  Vec3 translation = Vec3::Zero();  ///< of the section centre [mm]
  Vec3 rotation = Vec3::Zero();     ///< rotation vector of the section [degrees]

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<Keyframe>> keys();
};

inline std::span<const Key<Keyframe>> Keyframe::keys() {
  using K = Key<Keyframe>;
  static const K keys[] = {
      K::real("stages[].motions.<condition>.keyframes[].at", &Keyframe::at, "",
              "in (0, 1], increasing, the last one = 1", ranges::fraction,
              "fraction of the stage at which the keyframe is reached")
          .shown_default("required"),
      K::doc("stages[].motions.<condition>.keyframes[].translation", KeyType::vector, "mm", "[0, 0, 0]", "",
             "translation of the section centre, cumulative since activation"),
      K::doc("stages[].motions.<condition>.keyframes[].rotation", KeyType::vector, "deg", "[0, 0, 0]", "",
             "rotation vector of the section, cumulative since activation"),
  };
  return keys;
}

struct MotionTarget {
  int condition = 0;                ///< index into Scenario::conditions (type motion)
  std::vector<Keyframe> keyframes;  ///< at least one; the last one has at = 1

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<MotionTarget>> keys();
};

inline std::span<const Key<MotionTarget>> MotionTarget::keys() {
  using K = Key<MotionTarget>;
  static const K keys[] = {
      K::doc("stages[].motions.<condition>", KeyType::map, "", "required",
             "with translation/rotation or keyframes", "the target of one motion condition"),
      K::doc("stages[].motions.<condition>.translation", KeyType::vector, "mm", "[0, 0, 0]", "",
             "short form: translation of the section centre at stage end, cumulative since "
             "activation"),
      K::doc("stages[].motions.<condition>.rotation", KeyType::vector, "deg", "[0, 0, 0]", "",
             "short form: rotation vector of the section at stage end, cumulative since "
             "activation"),
      K::doc("stages[].motions.<condition>.keyframes", KeyType::list, "", "-",
             "non-empty, not next to translation or rotation", "long form: keyframes inside the stage"),
  };
  return keys;
}

struct LoadTarget {
  int condition = 0;           ///< index into Scenario::conditions (type load)
  Vec3 force = Vec3::Zero();   ///< value reached at the end of the stage [N]
  Vec3 moment = Vec3::Zero();  ///< value reached at the end of the stage [N mm]

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<LoadTarget>> keys();
};

inline std::span<const Key<LoadTarget>> LoadTarget::keys() {
  using K = Key<LoadTarget>;
  static const K keys[] = {
      K::doc("stages[].loads.<condition>", KeyType::map, "", "required", "with force and/or moment",
             "the target of one load condition"),
      K::doc("stages[].loads.<condition>.force", KeyType::vector, "N", "unchanged", "",
             "force at stage end; omitted: keeps its value at stage start"),
      K::doc("stages[].loads.<condition>.moment", KeyType::vector, "N mm", "unchanged",
             "parallel to the load's other nonzero moments",
             "moment at stage end; omitted: keeps its value at stage start"),
  };
  return keys;
}

/// A stage's choice of a solver setting: the `solver` section's, or its own.
enum class StageSwitch { solver, on, off };

/// The linear solver of the solver section (solver.linear_solver), declared with SolverSettings below.
enum class LinearSolverKind;

/// A stage's contact particles: contact.particles (contact), or one of its choices.
enum class StageParticles { contact, fixed, facing, centres };

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
  /// Newton's line search in this stage: solver.line_search (solver), or on or off.
  StageSwitch line_search = StageSwitch::solver;
  /// The linear solver of this stage, one of the serial ones; none: solver.linear_solver
  /// (stage_linear_solver()).
  std::optional<LinearSolverKind> linear_solver;
  /// Where the contact forces act in this stage (as contact.particles); contact: contact.particles.
  StageParticles particles = StageParticles::contact;

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<StageSpec>> keys();
};

inline std::span<const Key<StageSpec>> StageSpec::keys() {
  using K = Key<StageSpec>;
  static const K keys[] = {
      K::doc("stages[].name", KeyType::string, "", "required", "unique among stages",
             "name shown in progress output"),
      K::whole("stages[].steps", &StageSpec::steps, ">= 1", ranges::at_least_one,
               "number of nominal load steps")
          .shown_default("required"),
      K::real("stages[].duration", &StageSpec::duration, "s", "> 0", ranges::positive,
              "length of the stage in load time"),
      K::real("stages[].stabilization", &StageSpec::stabilization, "N s/mm^2", ">= 0", ranges::non_negative,
              "viscous drag per unit length on the beams during the stage, force = -value * "
              "(velocity in load time) on the axis and value * R^2/4 on each director; a "
              "numerical aid to pass snap-throughs, off (0) or vanished (the beams at rest) "
              "where results are read (docs/model.md)"),
      K::real("stages[].stabilization_end", &StageSpec::stabilization_end, "N s/mm^2", ">= 0",
              ranges::non_negative,
              "the drag at the stage end, reached geometrically from stabilization; 0: decays "
              "to 1e-6 of it and is exactly 0 at the stage end")
          .shown_default("stabilization"),
      K::choice(
          "stages[].line_search", "solver | true | false",
          [](const StageSpec& s) { return static_cast<int>(s.line_search); },
          [](StageSpec& s, int i) { s.line_search = static_cast<StageSwitch>(i); },
          "damp the Newton updates of this stage by a line search (solver.line_search); solver: as "
          "solver.line_search. The knot's releases take it, to come to rest (docs/knot.md)"),
      K::choice(
          "stages[].linear_solver", "solver | cholmod | umfpack | mumps | klu",
          // The file's alternatives: "solver" (none), then LinearSolverKind's first four in its order.
          [](const StageSpec& s) { return s.linear_solver ? static_cast<int>(*s.linear_solver) + 1 : 0; },
          [](StageSpec& s, int i) {
            s.linear_solver = i == 0 ? std::nullopt : std::optional(static_cast<LinearSolverKind>(i - 1));
          },
          "the sparse direct solver of this stage (as solver.linear_solver); solver: solver.linear_solver. "
          "Not with solver.linear_solver: petsc. KLU is the faster on a twisted 3x1 yarn, MUMPS where its "
          "knot forms (docs/performance.md)"),
      K::choice(
          "stages[].particles", "contact | fixed | facing | centres",
          [](const StageSpec& s) { return static_cast<int>(s.particles); },
          [](StageSpec& s, int i) { s.particles = static_cast<StageParticles>(i); },
          "where the contact forces act in this stage (as contact.particles); contact: as "
          "contact.particles. Needs a contact section. The 3x1 knot twists its yarn with facing, "
          "2.4 times faster than with the centres it needs to tie it (docs/knot_3x1.md)"),
      K::doc("stages[].activate", KeyType::list, "", "[]", "of condition names",
             "conditions switched on at the start of the stage"),
      K::doc("stages[].release", KeyType::list, "", "[]", "of condition names, none also in activate",
             "conditions switched off at the start of the stage"),
      K::doc("stages[].contact_off", KeyType::list, "", "[]", "of contact beam names",
             "beams taken out of contact at the start of the stage (a tool removed); they stay"
             " where they are"),
      K::doc("stages[].contact_on", KeyType::list, "", "[]",
             "of contact beam names, none also in contact_off",
             "beams put back into contact at the start of the stage"),
      K::doc("stages[].motions", KeyType::map, "", "{}", "from motion or rigid condition names to targets",
             "prescribed motions reached during the stage"),
      K::doc("stages[].loads", KeyType::map, "", "{}", "from load condition names to targets",
             "load values reached at the end of the stage"),
  };
  return keys;
}

/// `automatic` ("auto" in the file) is resolved when the scenario is read or a Simulation is made
/// (choose_linear_solver, linear_solver_choice.hpp): a run never sees it.
enum class LinearSolverKind { cholmod, umfpack, mumps, klu, petsc, automatic };

/// The `solver` section. The Newton and stepping defaults are the library's (solver::NewtonSettings,
/// solver::StepControl); the others equal those of the library structs that take them, which a test checks
/// (tests/scenario/test_scenario_keys.cpp).
struct SolverSettings {
  LinearSolverKind linear_solver = LinearSolverKind::automatic;
  /// Why `auto` chose linear_solver, for the settings echo; empty where the file named a solver.
  std::string linear_solver_reason;
  int max_newton_iterations = ::nodus::solver::NewtonSettings{}.max_iterations;  ///< per step attempt, >= 1
  /// Iterations without a new smallest residual after which a step attempt is given up, >= 0 (0: never).
  int stagnation_iterations = ::nodus::solver::NewtonSettings{}.stagnation_iterations;
  /// A step attempt is given up once the smallest residual of its last `progress_window` iterations is not
  /// below `progress_ratio` times the smallest before them, >= 0 (0: never).
  int progress_window = ::nodus::solver::NewtonSettings{}.progress_window;
  double progress_ratio = ::nodus::solver::NewtonSettings{}.progress_ratio;  ///< in (0, 1)
  double residual_tolerance = 1e-8;   ///< |R| <= tol * force scale [-], > 0
  double increment_tolerance = 1e-6;  ///< |du|_inf <= tol * length scale [-], > 0
  /// Successive halvings of a step before giving up, >= 0.
  int max_cutbacks = ::nodus::solver::StepControl{}.max_cutbacks;
  /// A step converged in at most this many iterations lets the next grow, >= 1.
  int easy_iterations = ::nodus::solver::StepControl{}.easy_iterations;
  /// Damp the Newton updates by a line search: slower on every verification case so far (docs/model.md).
  bool line_search = ::nodus::solver::NewtonSettings{}.line_search;
  /// From this iteration of each Newton solve on, halve a full step that does not reduce the residual, >= 0
  /// (0: never; NewtonSettings::backtrack_from).
  int backtrack_from = ::nodus::solver::NewtonSettings{}.backtrack_from;
  /// Turn the directors by the rigid part of their Newton increments, or add the increments.
  ::nodus::model::DirectorUpdate director_update = ::nodus::model::DirectorUpdate::rotation;
  /// Keep the tangent's factor across iterations and steps, solving with GMRES on it (NewtonSettings).
  bool reuse_factor = ::nodus::solver::NewtonSettings{}.reuse_factor;
  int krylov_iterations = ::nodus::solver::NewtonSettings{}.krylov_iterations;  ///< >= 1
  int gauss_points = 2;         ///< Gauss points per element along the axis, 1..5
  double fold_stiffness = 0.0;  ///< beta of the fold stabilisation (beam_element.hpp), >= 0
  double fold_barrier = 1.0;    ///< gamma of the orientation barrier (beam_element.hpp), >= 0
  /// PETSc options for linear_solver: petsc, as on a command line ("-pc_factor_mat_solver_type
  /// superlu_dist"); the command line's own options win (docs/parallel.md).
  std::string petsc_options;

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<SolverSettings>> keys();
};

inline std::span<const Key<SolverSettings>> SolverSettings::keys() {
  using K = Key<SolverSettings>;
  static const K keys[] = {
      K::choice(
          "solver.linear_solver", "cholmod | umfpack | mumps | klu | petsc | auto",
          [](const SolverSettings& c) { return static_cast<int>(c.linear_solver); },
          [](SolverSettings& c, int i) { c.linear_solver = static_cast<LinearSolverKind>(i); },
          "sparse direct solver: cholmod (Cholesky), umfpack (LU), mumps (multifrontal LDL^T, or LU where "
          "the tangent is not symmetric), klu (sparse LU, keeping its pivots while they serve) or petsc (the "
          "MPI ranks of `mpirun -n N nodus run` together: PETSc's KSP with MUMPS's LDL^T or LU; "
          "docs/parallel.md); auto: petsc on several MPI ranks, else cholmod for a symmetric tangent, "
          "klu for an unsymmetric one of up to 6,000 unknowns, mumps above (docs/scenario.md, \"solver\")"),
      K::whole("solver.max_newton_iterations", &SolverSettings::max_newton_iterations, ">= 1",
               ranges::at_least_one, "iterations per step attempt"),
      K::whole("solver.stagnation_iterations", &SolverSettings::stagnation_iterations, ">= 0",
               ranges::non_negative,
               "a step attempt is given up (and the step cut back) after this many iterations without a "
               "residual smaller than the smallest so far; 0: never (docs/performance.md)"),
      K::whole("solver.progress_window", &SolverSettings::progress_window, ">= 0", ranges::non_negative,
               "a step attempt is given up (and the step cut back) once the smallest residual of its last "
               "progress_window iterations is not below progress_ratio times the smallest before them (at "
               "least two before them), except the last attempt max_cutbacks allows; 0: never "
               "(docs/performance.md)"),
      K::real("solver.progress_ratio", &SolverSettings::progress_ratio, "", "in (0, 1)",
              ranges::proper_fraction, "the reduction of the residual that progress_window asks for"),
      K::real("solver.residual_tolerance", &SolverSettings::residual_tolerance, "", "> 0", ranges::positive,
              "converged when the residual norm <= tolerance times the force scale"),
      K::real("solver.increment_tolerance", &SolverSettings::increment_tolerance, "", "> 0", ranges::positive,
              "converged when the largest increment <= tolerance times the length scale"),
      K::whole("solver.max_cutbacks", &SolverSettings::max_cutbacks, ">= 0", ranges::non_negative,
               "successive halvings of a step before giving up"),
      K::whole("solver.easy_iterations", &SolverSettings::easy_iterations, ">= 1", ranges::at_least_one,
               "a step converged in at most this many iterations lets the next step grow"),
      K::flag("solver.line_search", &SolverSettings::line_search,
              "damp Newton updates by a line search on the energy slope (off: faster on every "
              "verification case, docs/model.md; a stage may choose otherwise, stages[].line_search)"),
      K::whole(
          "solver.backtrack_from", &SolverSettings::backtrack_from, ">= 0", ranges::non_negative,
          "from this iteration of each Newton solve on (a step with contact runs one a pass of its "
          "loops; without line search), a full step that does not reduce the residual is halved, up to 6 "
          "times, and the length with the smallest residual taken: it breaks the cycles of contact "
          "elements switching between stick and slip, or in and out of contact, in a packed yarn; 0: "
          "never (docs/model.md)"),
      K::choice(
          "solver.director_update", "rotation | additive",
          [](const SolverSettings& c) { return static_cast<int>(c.director_update); },
          [](SolverSettings& c, int i) {
            c.director_update = static_cast<::nodus::model::DirectorUpdate>(i);
          },
          "how a Newton increment moves the section directors: rotation (the part of the increment that "
          "is a rigid turn applied as a finite rotation, so that a turn does not stretch the section) or "
          "additive (g + dg) (docs/model.md)"),
      K::flag("solver.reuse_factor", &SolverSettings::reuse_factor,
              "keep the tangent's factorisation across Newton iterations and steps, and solve with GMRES "
              "preconditioned by it while it serves (docs/performance.md); with `linear_solver: petsc`, "
              "PETSc's GMRES on the distributed matrix (docs/parallel.md)"),
      K::whole("solver.krylov_iterations", &SolverSettings::krylov_iterations, ">= 1", ranges::at_least_one,
               "GMRES iterations allowed on a kept factorisation before the tangent is factorised again"),
      K::whole("solver.gauss_points", &SolverSettings::gauss_points, "in 1..5", ranges::one_to_five,
               "Gauss points per element along the axis (2: reduced integration, free of "
               "locking; docs/model.md)"),
      K::real("solver.fold_stiffness", &SolverSettings::fold_stiffness, "", ">= 0", ranges::non_negative,
              "beta of the energy that keeps a 2-point element from folding back on itself at "
              "no cost; 0: none (docs/model.md)"),
      K::real("solver.fold_barrier", &SolverSettings::fold_barrier, "", ">= 0", ranges::non_negative,
              "gamma of the energy against an axis that turns against its section (det[g1, g2, r'] < 1/2), "
              "which keeps every element from folding; zero in any state of small strain; 0: none "
              "(docs/model.md)"),
      K::doc("solver.petsc_options", KeyType::string, "", "\"\"", "PETSc options (-name [value] ...)",
             "options of the petsc linear solver (-pc_factor_mat_solver_type superlu_dist, "
             "-mat_mumps_icntl_14 50, ...); the command line's win (docs/parallel.md)"),
  };
  return keys;
}

/// The linear solver that `stage` runs with: its own, or solver.linear_solver.
inline LinearSolverKind stage_linear_solver(const StageSpec& stage, const SolverSettings& solver) {
  return stage.linear_solver.value_or(solver.linear_solver);
}

struct OutputSettings {
  int vtk_every = 1;    ///< write a VTK file every N converged steps (0: only the final state)
  int tube_sides = 12;  ///< facets around each tube in the VTK output, >= 3
  output::VtkEncoding vtk_format = output::VtkEncoding::binary;  ///< how the VTK files store their arrays
  double progress_seconds = 1.0;  ///< minimum interval between progress lines on stderr [s]
  bool contact_csv = false;       ///< also write contact/contact_NNNNNN.csv at every VTK output step
  int checkpoint_every = 0;  ///< also save the run's state every N converged steps (0: at stage ends only)
  bool hdf5 = true;          ///< also write result.h5 and result.xmf (every output state in one file)

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<OutputSettings>> keys();
};

inline std::span<const Key<OutputSettings>> OutputSettings::keys() {
  using K = Key<OutputSettings>;
  static const K keys[] = {
      K::whole("output.vtk_every", &OutputSettings::vtk_every, ">= 0", ranges::non_negative,
               "write a VTK file every N converged steps; 0: the final state only"),
      K::whole("output.tube_sides", &OutputSettings::tube_sides, ">= 3", ranges::at_least_three,
               "facets around each tube in the VTK output"),
      K::choice(
          "output.vtk_format", "binary | ascii",
          [](const OutputSettings& o) { return static_cast<int>(o.vtk_format); },
          [](OutputSettings& o, int i) { o.vtk_format = static_cast<output::VtkEncoding>(i); },
          "how the VTK files store their arrays. binary: compressed by zlib and appended, as ParaView "
          "writes them; ascii: as text, about ten times larger (docs/output.md)"),
      K::real("output.progress_seconds", &OutputSettings::progress_seconds, "s", ">= 0", ranges::non_negative,
              "minimum interval between progress lines on stderr"),
      K::flag("output.contact_csv", &OutputSettings::contact_csv,
              "with contact: also write contact/contact_NNNNNN.csv (every contact element) at "
              "every VTK output step"),
      K::whole("output.checkpoint_every", &OutputSettings::checkpoint_every, ">= 0", ranges::non_negative,
               "also save the run's complete state every N converged steps, as "
               "checkpoints/latest.nodus-state (the state at the end of every stage is always "
               "saved; docs/output.md); 0: at stage ends only"),
      K::flag("output.hdf5", &OutputSettings::hdf5,
              "also write result.h5 (the run's states, steps, contact and beams in one HDF5 file) "
              "and result.xmf (its XDMF index for ParaView) at every VTK output step"),
  };
  return keys;
}

/// How Newton's tangent linearises the friction force (contact.friction_tangent; docs/contact.md). The force
/// itself is the same either way.
enum class FrictionTangent {
  frozen,   ///< R_N held fixed, as in Durville 2012, Sect. 5.3: symmetric, any linear solver
  varying,  ///< the exact derivative, R_N varying: not symmetric, needs LU (umfpack, mumps or klu)
};

/// How loop 3 of the global algorithm finds the normals (contact.normal_updates; docs/contact.md).
enum class NormalUpdates {
  nested,         ///< the paper's: a Newton solve to convergence after every update of the normals
  inside_newton,  ///< the normals updated between Newton iterations, held fixed in the tangent
  linearized,     ///< the normals are functions of the state, linearised in the tangent (not symmetric)
};

/// Which two sections each contact element pairs (contact.section_pairing): the detection's own choice.
using contact::SectionPairing;

/// A friction coefficient for the contacts between some beams (contact.friction_pairs): those between a
/// beam of `beams` and a beam of `with` (any beam, one of `beams` included, if `with` is empty).
struct FrictionPair {
  std::vector<int> beams;  ///< indices into Scenario::beams, non-empty
  std::vector<int> with;   ///< indices into Scenario::beams; empty: any beam
  double friction = 0.0;   ///< mu [-], >= 0

  /// Whether the contacts between beams i and j (in either order) take this coefficient.
  bool applies(int i, int j) const {
    const auto in = [](const std::vector<int>& list, int b) {
      return std::find(list.begin(), list.end(), b) != list.end();
    };
    return (in(beams, i) && (with.empty() || in(with, j))) || (in(beams, j) && (with.empty() || in(with, i)));
  }
};

/// Contact detection settings: the `contact` section (docs/scenario.md, docs/contact.md). A length (or the
/// penalty) of 0 means "auto": derived from the radii and element lengths when the simulation starts (the
/// library takes any value <= 0 so; validate() refuses negative ones, as the reader does).
struct ContactSettings {
  bool enabled = false;      ///< true when the file has a contact section, unless contact.enabled: false
  bool self_contact = true;  ///< also between separate parts of one beam
  std::vector<int> beams;    ///< indices into Scenario::beams that take part; empty: all beams
  double proximity_distance = 0.0;   ///< delta_prox [mm], auto if <= 0
  double separation_distance = 0.0;  ///< delta_separ [mm], auto if <= 0
  double test_point_spacing = 0.0;   ///< h_dist [mm], auto if <= 0
  double matching_length = 0.0;      ///< l_p [mm], auto if <= 0
  double element_spacing = 0.0;      ///< h_c [mm], auto if <= 0
  /// Which two sections each contact element pairs (contact.section_pairing).
  SectionPairing section_pairing = SectionPairing::plane;
  // Contact mechanics (Sect. 5-6).
  bool forces = true;            ///< apply contact forces; false: detection only
  double penalty = 0.0;          ///< initial k_c per zone [N/mm], auto if <= 0
  double max_penetration = 0.0;  ///< p_max [mm], auto if <= 0
  double regularization = 0.0;   ///< p_reg [mm], auto if <= 0
  double friction = 0.0;         ///< mu [-], >= 0, of the pairs of beams that friction_pairs leaves out
  /// Other coefficients between some beams; where several entries apply to a pair, the last one does.
  std::vector<FrictionPair> friction_pairs;
  double max_reversible_slip = 0.0;  ///< g_rev_max [mm], auto if <= 0
  FrictionTangent friction_tangent = FrictionTangent::frozen;
  /// Particles at the facing points of the sections during Newton (contact.particles: facing); false: the
  /// paper's fixed material particles (fixed).
  bool facing_particles = false;
  /// With facing_particles: facing along the direction between the section centres (contact.particles:
  /// centres) rather than along the normal (facing).
  bool centre_facing = false;
  int max_detections = 4;  ///< loop 2: detections of contact elements per step, >= 1
  NormalUpdates normal_updates = NormalUpdates::nested;  ///< loop 3 (contact.normal_updates)
  int max_normal_iterations = 6;   ///< loop 3: updates of the normals per detection, >= 1
  double normal_tolerance = 1e-3;  ///< loop 3 stops when no normal turns by more than this [rad], > 0
  /// Nested loop 3: its Newton solves stop at |R| <= this fraction of the total normal force, the last one at
  /// the residual tolerance; 0: every solve to the residual tolerance (the paper), >= 0.
  double normal_pass_residual = 0.0;
  /// A converged step in which two axes crossed each other is refused and cut back (contact::find_crossing).
  bool crossing_guard = true;

  /// The friction coefficient between beams i and j: of the last entry of friction_pairs that applies, else
  /// friction.
  double friction_between(int i, int j) const {
    for (auto it = friction_pairs.rbegin(); it != friction_pairs.rend(); ++it)
      if (it->applies(i, j)) return it->friction;
    return friction;
  }

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<ContactSettings>> keys();
};

inline std::span<const Key<ContactSettings>> ContactSettings::keys() {
  using K = Key<ContactSettings>;
  static const K keys[] = {
      K::flag("contact.enabled", &ContactSettings::enabled,
              "false: contact is off although the section is present")
          .shown_default("true"),
      K::flag("contact.self_contact", &ContactSettings::self_contact,
              "also detect contact between separate parts of one beam"),
      K::doc("contact.beams", KeyType::list, "", "all beams", "of beam names, non-empty, each beam once",
             "the beams that take part in contact"),
      K::real("contact.proximity_distance", &ContactSettings::proximity_distance, "mm", "> 0 or auto",
              ranges::positive,
              "delta_prox: largest axis-to-axis distance of a proximity (candidate contact). "
              "auto: 3 R, i.e. 1.5 times the contact distance 2 R")
          .or_auto(),
      K::real("contact.separation_distance", &ContactSettings::separation_distance, "mm",
              "> 0 or auto, > proximity_distance", ranges::positive,
              "delta_separ: smallest distance along one beam between two of its parts paired "
              "for self contact. auto: 4 proximity_distance")
          .or_auto(),
      K::real("contact.test_point_spacing", &ContactSettings::test_point_spacing, "mm", "> 0 or auto",
              ranges::positive,
              "h_dist: spacing of the test points along each beam. auto: "
              "sqrt(proximity_distance^2 - (2 R)^2), at least proximity_distance / 2")
          .or_auto(),
      K::real("contact.matching_length", &ContactSettings::matching_length, "mm",
              "> 0 or auto, >= test_point_spacing", ranges::positive,
              "l_p: length of an elementary matching interval. auto: 2 test_point_spacing")
          .or_auto(),
      K::real("contact.element_spacing", &ContactSettings::element_spacing, "mm", "> 0 or auto",
              ranges::positive,
              "h_c: spacing of the contact elements along a proximity zone. auto: h / 2, h the "
              "smaller element length of the zone's two beams")
          .or_auto(),
      K::choice(
          "contact.section_pairing", "plane | bisector",
          [](const ContactSettings& c) { return static_cast<int>(c.section_pairing); },
          [](ContactSettings& c, int i) { c.section_pairing = static_cast<SectionPairing>(i); },
          "which two sections each contact element pairs. plane: the paper's, the plane normal "
          "to the intermediate geometry cuts both axes (Eq. 33-36). bisector: on the same line "
          "of the zone's linear pairing, the two sections whose centre line is normal to their "
          "mean tangent; it follows the closest points where one strand wraps round another "
          "at a steep angle (a knot pulled tight), where the plane pairs sections far from "
          "them (docs/contact.md)"),
      K::flag("contact.forces", &ContactSettings::forces,
              "apply contact forces (Durville 2012, Sect. 5); false: detect and write out only"),
      K::real("contact.penalty", &ContactSettings::penalty, "N/mm", "> 0 or auto", ranges::positive,
              "initial penalty coefficient k_c of every proximity zone (Eq. 53), then adjusted "
              "per zone so that the largest penetration approaches max_penetration (Eq. 54). "
              "auto: E R, with E the smallest Young's modulus and R the smallest radius of the "
              "contact beams")
          .or_auto(),
      K::real("contact.max_penetration", &ContactSettings::max_penetration, "mm", "> 0 or auto",
              ranges::positive,
              "p_max, the penetration the per-zone penalty adjustment aims at (Eq. 54). auto: "
              "0.02 R (R the smallest radius)")
          .or_auto(),
      K::real("contact.regularization", &ContactSettings::regularization, "mm", "> 0 or auto",
              ranges::positive,
              "p_reg, the depth of the quadratic start of the penalty law (Eq. 53). auto: "
              "max_penetration / 10")
          .or_auto(),
      K::real("contact.friction", &ContactSettings::friction, "", ">= 0", ranges::non_negative,
              "Coulomb friction coefficient mu (Eq. 55-64); 0: frictionless. Between the beams of "
              "an entry of friction_pairs, that entry's"),
      K::doc("contact.friction_pairs", KeyType::list, "", "[]", "of maps",
             "other friction coefficients between some beams (a frictionless tool, another "
             "material); where several entries apply to a pair of beams, the last one does"),
      K::doc("contact.friction_pairs[].beams", KeyType::list, "", "required",
             "of beam names, non-empty, each beam once",
             "the entry applies to the contacts of these beams: with each other, with themselves "
             "and with any other beam, or only with those of with"),
      K::doc("contact.friction_pairs[].with", KeyType::list, "", "any beam",
             "of beam names, non-empty, each beam once",
             "the beams whose contacts with those of beams the entry applies to"),
      K::doc("contact.friction_pairs[].friction", KeyType::number, "", "required", ">= 0",
             "Coulomb friction coefficient mu between those beams; 0: frictionless"),
      K::real("contact.max_reversible_slip", &ContactSettings::max_reversible_slip, "mm", "> 0 or auto",
              ranges::positive,
              "g_rev_max, the tangential displacement taken reversibly before sliding "
              "(regularised Coulomb law). auto: max_penetration / 2")
          .or_auto(),
      K::choice(
          "contact.friction_tangent", "frozen | varying",
          [](const ContactSettings& c) { return static_cast<int>(c.friction_tangent); },
          [](ContactSettings& c, int i) { c.friction_tangent = static_cast<FrictionTangent>(i); },
          "how Newton's tangent linearises the friction force (the force is the same). "
          "frozen: R_N held fixed, a symmetric tangent. varying: the exact derivative with "
          "R_N varying, not symmetric: needs an LU solver, solver.linear_solver: auto, umfpack, mumps or klu "
          "(docs/contact.md)"),
      K::choice(
          "contact.particles", "fixed | facing | centres",
          [](const ContactSettings& c) { return c.facing_particles ? (c.centre_facing ? 2 : 1) : 0; },
          [](ContactSettings& c, int i) {
            c.facing_particles = i >= 1;
            c.centre_facing = i == 2;
          },
          "where the contact forces act during Newton. fixed: the paper's particles, "
          "material points of the section borders placed at detection (Eq. 37-40). facing: "
          "at each evaluation, the points of the borders that face each other along the "
          "normal (no spurious torsional stiffness from the lever arm of a turned section; "
          "for tightened knots). centres: at each evaluation, the points of the borders that "
          "face each other along the direction between the section centres, as detection "
          "places the paper's particles (no spurious torsional stiffness either, and at a "
          "crossing the gap grows away from it as the paper's; docs/contact.md)"),
      K::whole("contact.max_detections", &ContactSettings::max_detections, ">= 1", ranges::at_least_one,
               "loop 2 of the global algorithm (Sect. 6): at most this many detections of the "
               "contact elements per load step"),
      K::choice(
          "contact.normal_updates", "nested | inside_newton | linearized",
          [](const ContactSettings& c) { return static_cast<int>(c.normal_updates); },
          [](ContactSettings& c, int i) { c.normal_updates = static_cast<NormalUpdates>(i); },
          "loop 3 of the global algorithm. nested: the paper's, a Newton solve to convergence "
          "after every update of the normals and penalties. inside_newton: the normals follow "
          "the iterates within one Newton solve, the penalties are adjusted at its converged "
          "states. linearized: within each Newton solve, once near equilibrium, the normals "
          "are functions of the state with their derivative in the tangent (quadratic "
          "convergence where the nested loop's fixed point diverges; not symmetric: needs "
          "an LU solver, solver.linear_solver: auto, umfpack, mumps or klu), the penalties "
          "adjusted at converged "
          "states (docs/contact.md)"),
      K::whole("contact.max_normal_iterations", &ContactSettings::max_normal_iterations, ">= 1",
               ranges::at_least_one,
               "loop 3: at most this many updates of the normal directions and penalties per "
               "detection"),
      K::real("contact.normal_tolerance", &ContactSettings::normal_tolerance, "rad", "> 0", ranges::positive,
              "loop 3 stops when an update turns no normal by more than this and leaves every "
              "zone's penalty as it is: its largest penetration in [max_penetration / 2, "
              "max_penetration], or below max_penetration / 1000 (a zone that only touches)"),
      K::real("contact.normal_pass_residual", &ContactSettings::normal_pass_residual, "", ">= 0",
              ranges::non_negative,
              "nested loop 3: each Newton solve between two updates of the normals and penalties, "
              "or before a further detection of loop 2, stops once |R| <= this fraction of the total "
              "normal force, and the solve that ends the step goes on to the residual tolerance. 0: "
              "every solve to the residual tolerance, as in the paper (docs/contact.md)"),
      K::flag("contact.crossing_guard", &ContactSettings::crossing_guard,
              "refuse a converged step in which the axes of two contact beams, or of two parts of "
              "one more than separation_distance apart along it, passed through each other, and cut "
              "it back (docs/contact.md)"),
  };
  return keys;
}

/// Where the contact forces act in `stage`: its own particles, or contact.particles; as ContactSettings holds
/// them, {facing_particles, centre_facing}.
inline std::pair<bool, bool> stage_particles(const StageSpec& stage, const ContactSettings& contact) {
  if (stage.particles == StageParticles::contact) return {contact.facing_particles, contact.centre_facing};
  return {stage.particles != StageParticles::fixed, stage.particles == StageParticles::centres};
}

/// A run that continues from the state at the end of one stage of Scenario::stages (key `branches`).
struct BranchSpec {
  std::string name;                ///< unique among branches; also its output folder DIR/branches/NAME
  int from = 0;                    ///< index into Scenario::stages: the branch starts from the end of it
  std::optional<double> friction;  ///< overrides contact.friction for the branch's stages [-], >= 0
  std::vector<StageSpec> stages;   ///< run after stage `from`, names unique within the branch
  int line = 0;                    ///< line of the branch in the file (for messages)

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<BranchSpec>> keys();
};

inline std::span<const Key<BranchSpec>> BranchSpec::keys() {
  using K = Key<BranchSpec>;
  static const K keys[] = {
      K::doc("branches[].name", KeyType::string, "", "required",
             "unique among branches, of letters, digits, _ . -",
             "name of the branch and of its output folder DIR/branches/NAME"),
      K::doc("branches[].from", KeyType::string, "", "required", "naming a stage of stages",
             "the branch starts from the state at the end of this stage (load time and step "
             "numbers go on from there)"),
      K::doc("branches[].contact", KeyType::map, "", "-", "with friction only; needs a contact section",
             "overrides of the contact settings for the branch's stages"),
      K::doc("branches[].contact.friction", KeyType::number, "", "unchanged", ">= 0",
             "Coulomb friction coefficient mu of the branch's stages (contact.friction_pairs "
             "keep theirs)"),
      K::doc("branches[].stages", KeyType::list, "", "required", "non-empty, each item as in stages[]",
             "the branch's loading program, run in order after the from stage; stage names "
             "unique within the branch"),
  };
  return keys;
}

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
  std::vector<BodySpec> bodies;
  /// The yarns the reader laid out (their fibres and bodies are in beams and bodies).
  std::vector<YarnSpec> yarns;
  std::vector<ConditionSpec> conditions;
  std::vector<StageSpec> stages;
  SolverSettings solver;
  OutputSettings output;
  ContactSettings contact;
  std::vector<BranchSpec> branches;
  /// Set on the scenario of a branch (branch_scenario), empty for a scenario read from a file.
  std::optional<BranchOrigin> origin;

  /// The keys of the file this struct holds, in file order (key.hpp).
  static std::span<const Key<Scenario>> keys();
};

inline std::span<const Key<Scenario>> Scenario::keys() {
  using K = Key<Scenario>;
  static const K keys[] = {
      K::doc("units", KeyType::map, "", "-", "",
             "the unit system; if present, each of its keys must have exactly the value shown"),
      K::doc("units.length", KeyType::choice, "", "mm", "mm", "length unit"),
      K::doc("units.force", KeyType::choice, "", "N", "N", "force unit"),
      K::doc("units.stress", KeyType::choice, "", "MPa", "MPa", "stress unit"),
      K::doc("units.time", KeyType::choice, "", "s", "s", "time unit"),
      K::doc("materials", KeyType::list, "", "required", "non-empty", "the isotropic elastic materials"),
      K::doc("beams", KeyType::list, "", "required without yarns", "non-empty without yarns",
             "the beams, each straight in its reference configuration"),
      K::doc("yarns", KeyType::list, "", "[]", "",
             "twisted yarns laid out from a few numbers, written as beams (after those of beams) and "
             "rigid bodies (docs/yarns.md)"),
      K::doc("bodies", KeyType::list, "", "[]", "",
             "rigid bodies, each bound to fibre end sections by averaged conditions (docs/bodies.md)"),
      K::doc("conditions", KeyType::list, "", "[]", "",
             "named boundary conditions, each on one cross-section"),
      K::doc("stages", KeyType::list, "", "required", "non-empty", "the loading program, run in order"),
      K::doc("solver", KeyType::map, "", "{}", "", "Newton solver settings"),
      K::doc("output", KeyType::map, "", "{}", "", "output settings"),
      K::doc("contact", KeyType::map, "", "-", "",
             "contact detection and contact forces between the beams (docs/contact.md); "
             "absent: no contact, present (even empty): on. The detection lengths are the "
             "paper's delta_prox, delta_separ, h_dist, l_p, h_c (Durville 2012, Eq. 24-48); "
             "auto ones are derived when the run starts, with R the largest radius of the "
             "contact beams"),
      K::doc("branches", KeyType::list, "", "[]", "-",
             "runs that each continue from the state at the end of one stage of stages, after "
             "all of stages; results in DIR/branches/NAME"),
  };
  return keys;
}

/// Reads and validates a scenario file. Throws ScenarioError with a one-line message on bad input.
Scenario read_scenario(const std::string& path);

/// Same, from YAML text; `path` is used in messages only.
Scenario parse_scenario(const std::string& yaml_text, const std::string& path);

/// The scenario of branch `branch` of `main` as a run of its own: the stages of `main` up to and including
/// the branch's `from`, then the branch's stages; contact.friction overridden if the branch says so; no
/// branches; `origin` set. A run of it that starts from the state of `main` at the end of stage `from`
/// continues `main` as the branch asks.
Scenario branch_scenario(const Scenario& main, std::size_t branch);

/// Load time at the end of stage `stage` (0 based) [s]: the stages' durations up to it, summed.
inline double stage_end_time(const Scenario& scenario, int stage) {
  double t = 0.0;
  for (int i = 0; i <= stage; ++i) t += scenario.stages.at(static_cast<std::size_t>(i)).duration;
  return t;
}

/// The table of all keys of the file format (name, type, unit, default, range, help) as a markdown table;
/// the same table drives the reader's messages (see keys.hpp) and is pasted into docs/scenario.md.
std::string scenario_keys_markdown();

}  // namespace nodus::scenario

// The echo, the fingerprint and the validation of a scenario: part of this header's API, declared in their
// own files.
#include "nodus/scenario/describe.hpp"     // IWYU pragma: export
#include "nodus/scenario/fingerprint.hpp"  // IWYU pragma: export
#include "nodus/scenario/validate.hpp"     // IWYU pragma: export
