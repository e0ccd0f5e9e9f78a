// Tests of the `contact` section of a scenario file: defaults, every key (detection and mechanics), the word
// auto, beams by name, and the exact one-line message "FILE:LINE: KEY: expected ..., got ..." of each kind
// of bad input.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {
namespace {

/// Three beams and no contact section; the tests append one, its first line is line 25.
const std::string kBase = R"(materials:
  - name: nylon
    young_modulus: 4000
    poisson_ratio: 0.3
beams:
  - name: rod
    material: nylon
    radius: 0.1
    length: 20
    elements: 10
  - name: strand
    material: nylon
    radius: 0.2
    length: 10
    elements: 5
    start: [0, 1, 0]
  - name: wire
    material: nylon
    radius: 0.05
    length: 5
    elements: 2
stages:
  - name: hold
    steps: 1
)";

Scenario parse(const std::string& contact_section) {
  return parse_scenario(kBase + contact_section, "knot.yaml");
}

/// The message of the ScenarioError that parsing kBase + `contact_section` throws; a test failure if none.
std::string error_of(const std::string& contact_section) {
  try {
    parse(contact_section);
  } catch (const ScenarioError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "not a ScenarioError: " << error.what();
    return {};
  }
  ADD_FAILURE() << "no error for:\n" << contact_section;
  return {};
}

void expect_all_auto(const ContactSettings& contact) {
  EXPECT_EQ(contact.proximity_distance, 0.0);
  EXPECT_EQ(contact.separation_distance, 0.0);
  EXPECT_EQ(contact.test_point_spacing, 0.0);
  EXPECT_EQ(contact.matching_length, 0.0);
  EXPECT_EQ(contact.element_spacing, 0.0);
}

/// The mechanics keys at their defaults: forces on, auto penalty and lengths, no friction, loops 4 x 6.
void expect_mechanics_defaults(const ContactSettings& contact) {
  EXPECT_TRUE(contact.forces);
  EXPECT_EQ(contact.penalty, 0.0);  // auto
  EXPECT_EQ(contact.max_penetration, 0.0);
  EXPECT_EQ(contact.regularization, 0.0);
  EXPECT_EQ(contact.friction, 0.0);
  EXPECT_EQ(contact.max_reversible_slip, 0.0);
  EXPECT_EQ(contact.friction_tangent, FrictionTangent::frozen);  // symmetric, as in the paper
  EXPECT_FALSE(contact.facing_particles);                        // the paper's fixed particles
  EXPECT_EQ(contact.max_detections, 4);
  EXPECT_EQ(contact.max_normal_iterations, 6);
  EXPECT_EQ(contact.normal_tolerance, 1e-3);
}

// ---- valid input ----

TEST(ScenarioContact, AbsentSectionMeansNoContact) {
  const ContactSettings contact = parse("").contact;
  EXPECT_FALSE(contact.enabled);
  EXPECT_TRUE(contact.self_contact);
  EXPECT_TRUE(contact.beams.empty());
  expect_all_auto(contact);
  expect_mechanics_defaults(contact);
}

TEST(ScenarioContact, EmptySectionEnablesContactWithDefaults) {
  for (const std::string section : {"contact: {}\n", "contact:\n", "contact: # all defaults\n"}) {
    const ContactSettings contact = parse(section).contact;
    EXPECT_TRUE(contact.enabled) << section;
    EXPECT_TRUE(contact.self_contact) << section;
    EXPECT_TRUE(contact.beams.empty()) << section;  // all beams
    expect_all_auto(contact);
    expect_mechanics_defaults(contact);
  }
}

TEST(ScenarioContact, EveryKeyIsRead) {
  const ContactSettings contact = parse(R"(contact:
  enabled: true
  self_contact: false
  beams: [strand, rod]
  proximity_distance: 0.5
  separation_distance: 2.5
  test_point_spacing: 0.25
  matching_length: 0.75
  element_spacing: 0.1
  forces: false
  penalty: 250
  max_penetration: 0.004
  regularization: 0.0005
  friction: 0.3
  max_reversible_slip: 0.002
  friction_tangent: varying
  particles: facing
  max_detections: 2
  max_normal_iterations: 10
  normal_tolerance: 1e-4
solver: {linear_solver: umfpack}
)")
                                      .contact;
  EXPECT_TRUE(contact.enabled);
  EXPECT_FALSE(contact.self_contact);
  EXPECT_EQ(contact.beams, (std::vector<int>{1, 0}));  // in the order given
  EXPECT_DOUBLE_EQ(contact.proximity_distance, 0.5);
  EXPECT_DOUBLE_EQ(contact.separation_distance, 2.5);
  EXPECT_DOUBLE_EQ(contact.test_point_spacing, 0.25);
  EXPECT_DOUBLE_EQ(contact.matching_length, 0.75);
  EXPECT_DOUBLE_EQ(contact.element_spacing, 0.1);
  EXPECT_FALSE(contact.forces);
  EXPECT_DOUBLE_EQ(contact.penalty, 250.0);
  EXPECT_DOUBLE_EQ(contact.max_penetration, 0.004);
  EXPECT_DOUBLE_EQ(contact.regularization, 0.0005);
  EXPECT_DOUBLE_EQ(contact.friction, 0.3);
  EXPECT_DOUBLE_EQ(contact.max_reversible_slip, 0.002);
  EXPECT_EQ(contact.friction_tangent, FrictionTangent::varying);
  EXPECT_TRUE(contact.facing_particles);
  EXPECT_EQ(contact.max_detections, 2);
  EXPECT_EQ(contact.max_normal_iterations, 10);
  EXPECT_DOUBLE_EQ(contact.normal_tolerance, 1e-4);
}

TEST(ScenarioContact, MechanicsKeysAcceptTheirLimits) {
  // friction may be 0 (frictionless); the loops may run once; any positive value is taken as it is.
  const ContactSettings contact = parse(
                                      "contact:\n  friction: 0\n  max_detections: 1\n"
                                      "  max_normal_iterations: 1\n  normal_tolerance: 1e-12\n"
                                      "  penalty: 1e-9\n  forces: True\n")
                                      .contact;
  EXPECT_EQ(contact.friction, 0.0);
  EXPECT_EQ(contact.max_detections, 1);
  EXPECT_EQ(contact.max_normal_iterations, 1);
  EXPECT_DOUBLE_EQ(contact.normal_tolerance, 1e-12);
  EXPECT_DOUBLE_EQ(contact.penalty, 1e-9);
  EXPECT_TRUE(contact.forces);
  EXPECT_DOUBLE_EQ(parse("contact: {friction: 1.5}\n").contact.friction, 1.5);  // no upper limit
  EXPECT_EQ(parse("contact: {max_detections: +3}\n").contact.max_detections, 3);
  // The mechanics keys are independent of the detection keys and of enabled.
  const ContactSettings off = parse("contact:\n  enabled: false\n  friction: 0.2\n").contact;
  EXPECT_FALSE(off.enabled);
  EXPECT_DOUBLE_EQ(off.friction, 0.2);
  EXPECT_FALSE(parse("contact: {forces: false}\n").contact.forces);
}

TEST(ScenarioContact, DocsExampleOfTheMechanicsKeys) {
  // The example of the contact section of docs/scenario.md.
  const ContactSettings contact = parse(R"(contact:
  friction: 0.3
  max_penetration: 0.002   # mm; omit for auto (0.02 R)
  max_detections: 6
)")
                                      .contact;
  EXPECT_TRUE(contact.forces);
  EXPECT_DOUBLE_EQ(contact.friction, 0.3);
  EXPECT_DOUBLE_EQ(contact.max_penetration, 0.002);
  EXPECT_EQ(contact.penalty, 0.0);
  EXPECT_EQ(contact.regularization, 0.0);
  EXPECT_EQ(contact.max_reversible_slip, 0.0);
  EXPECT_EQ(contact.max_detections, 6);
  EXPECT_EQ(contact.max_normal_iterations, 6);
}

TEST(ScenarioContact, EnabledFalseKeepsTheOtherSettings) {
  const ContactSettings contact = parse("contact:\n  enabled: false\n  proximity_distance: 0.4\n").contact;
  EXPECT_FALSE(contact.enabled);
  EXPECT_DOUBLE_EQ(contact.proximity_distance, 0.4);
  EXPECT_FALSE(parse("contact: {enabled: False}\n").contact.enabled);
  EXPECT_TRUE(parse("contact: {enabled: true}\n").contact.enabled);
}

TEST(ScenarioContact, AutoIsAccepted) {
  const ContactSettings contact = parse(R"(contact:
  proximity_distance: auto
  separation_distance: auto
  test_point_spacing: auto
  matching_length: auto
  element_spacing: auto
  penalty: auto
  max_penetration: auto
  regularization: auto
  max_reversible_slip: auto
)")
                                      .contact;
  EXPECT_TRUE(contact.enabled);
  expect_all_auto(contact);
  expect_mechanics_defaults(contact);
}

TEST(ScenarioContact, BeamsByNameResolveToIndices) {
  EXPECT_EQ(parse("contact: {beams: [wire]}\n").contact.beams, std::vector<int>{2});
  EXPECT_EQ(parse("contact:\n  beams:\n    - rod\n    - wire\n    - strand\n").contact.beams,
            (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(parse("contact: {beams: [\"strand\"]}\n").contact.beams, std::vector<int>{1});  // quoted name
}

TEST(ScenarioContact, FrictionPairsGiveTheCoefficientOfEachPairTheLastEntryWins) {
  const Scenario s = parse(
      "contact:\n  friction: 0.3\n  friction_pairs:\n    - {beams: [wire], friction: 0}\n"
      "    - {beams: [rod], with: [strand, wire], friction: 0.5}\n");
  const ContactSettings& c = s.contact;
  ASSERT_EQ(c.friction_pairs.size(), 2u);
  EXPECT_EQ(c.friction_pairs[0].beams, std::vector<int>{2});
  EXPECT_TRUE(c.friction_pairs[0].with.empty());
  EXPECT_EQ(c.friction_pairs[0].friction, 0.0);
  EXPECT_EQ(c.friction_pairs[1].beams, std::vector<int>{0});
  EXPECT_EQ(c.friction_pairs[1].with, (std::vector<int>{1, 2}));
  EXPECT_EQ(c.friction_pairs[1].friction, 0.5);
  const int rod = 0, strand = 1, wire = 2;
  EXPECT_EQ(c.friction_between(wire, wire), 0.0);    // the first entry: wire with any beam, itself included
  EXPECT_EQ(c.friction_between(strand, wire), 0.0);  // the first entry, in either order
  EXPECT_EQ(c.friction_between(wire, strand), 0.0);
  EXPECT_EQ(c.friction_between(rod, wire), 0.5);  // both entries apply: the last one
  EXPECT_EQ(c.friction_between(wire, rod), 0.5);
  EXPECT_EQ(c.friction_between(rod, strand), 0.5);
  EXPECT_EQ(c.friction_between(strand, rod), 0.5);
  EXPECT_EQ(c.friction_between(rod, rod), 0.3);  // rod's entry is only with strand and wire
  EXPECT_EQ(c.friction_between(strand, strand), 0.3);
  EXPECT_TRUE(parse("contact: {friction: 0.2}\n").contact.friction_pairs.empty());
}

TEST(ScenarioContact, ConsistencyRulesAcceptTheLimitsAndAutoValues) {
  // matching_length may equal test_point_spacing; separation_distance just above proximity_distance.
  const ContactSettings contact =
      parse(
          "contact:\n  test_point_spacing: 0.2\n  matching_length: 0.2\n  proximity_distance: 0.3\n"
          "  separation_distance: 0.31\n")
          .contact;
  EXPECT_DOUBLE_EQ(contact.matching_length, 0.2);
  EXPECT_DOUBLE_EQ(contact.separation_distance, 0.31);
  // Only explicit values are compared: an auto partner is derived when the run starts.
  EXPECT_NO_THROW(parse("contact:\n  matching_length: 0.01\n  separation_distance: 0.01\n"));
  EXPECT_NO_THROW(parse("contact:\n  test_point_spacing: 5\n  matching_length: auto\n"));
  EXPECT_NO_THROW(parse("contact:\n  proximity_distance: 5\n  separation_distance: auto\n"));
}

// ---- errors ----

TEST(ScenarioContact, FrictionTangentIsItsOwnKey) {
  // The default is frozen whatever the linear solver: choosing umfpack no longer changes the tangent.
  EXPECT_EQ(parse("contact: {friction: 0.3}\n").contact.friction_tangent, FrictionTangent::frozen);
  const Scenario lu = parse("contact: {friction: 0.3}\nsolver: {linear_solver: umfpack}\n");
  EXPECT_EQ(lu.solver.linear_solver, LinearSolverKind::umfpack);
  EXPECT_EQ(lu.contact.friction_tangent, FrictionTangent::frozen);
  EXPECT_EQ(parse("contact: {friction_tangent: frozen}\nsolver: {linear_solver: umfpack}\n")
                .contact.friction_tangent,
            FrictionTangent::frozen);
  EXPECT_EQ(parse("contact: {friction_tangent: frozen}\n").contact.friction_tangent, FrictionTangent::frozen);
  EXPECT_EQ(parse("contact: {friction_tangent: varying}\nsolver: {linear_solver: umfpack}\n")
                .contact.friction_tangent,
            FrictionTangent::varying);
  // MUMPS factorises it by LU.
  const Scenario mumps = parse("contact: {friction_tangent: varying}\nsolver: {linear_solver: mumps}\n");
  EXPECT_EQ(mumps.solver.linear_solver, LinearSolverKind::mumps);
  EXPECT_EQ(mumps.contact.friction_tangent, FrictionTangent::varying);
  // Without friction the key is accepted and changes nothing.
  EXPECT_EQ(parse("contact:\n  friction: 0\n  friction_tangent: varying\nsolver: {linear_solver: umfpack}\n")
                .contact.friction_tangent,
            FrictionTangent::varying);
}

TEST(ScenarioContactErrors, VaryingFrictionTangentNeedsLu) {
  const std::string expected =
      "contact.friction_tangent: expected frozen with solver.linear_solver: cholmod (the varying tangent is "
      "not "
      "symmetric and needs LU: set solver.linear_solver: umfpack, mumps or klu), got varying";
  // CHOLMOD named; the line is that of friction_tangent. By default (auto) an LU solver is chosen instead
  // (test_linear_solver_choice.cpp).
  EXPECT_EQ(
      error_of("contact:\n  friction: 0.3\n  friction_tangent: varying\nsolver: {linear_solver: cholmod}\n"),
      "knot.yaml:27: " + expected);
  EXPECT_EQ(error_of("contact: {friction_tangent: varying}\nsolver: {linear_solver: cholmod}\n"),
            "knot.yaml:25: " + expected);
  EXPECT_EQ(error_of("contact:\n  friction_tangent: exact\n"),
            "knot.yaml:26: contact.friction_tangent: expected one of frozen | varying, got exact");
}

TEST(ScenarioContact, ParticlesFacingAlongTheCentres) {
  const ContactSettings fixed = parse("contact: {particles: fixed}\n").contact;
  EXPECT_FALSE(fixed.facing_particles);
  EXPECT_FALSE(fixed.centre_facing);
  const ContactSettings facing = parse("contact: {particles: facing}\n").contact;
  EXPECT_TRUE(facing.facing_particles);
  EXPECT_FALSE(facing.centre_facing);
  const ContactSettings centres = parse("contact: {particles: centres}\n").contact;
  EXPECT_TRUE(centres.facing_particles);
  EXPECT_TRUE(centres.centre_facing);
}

TEST(ScenarioContact, LinearizedNormalsWithLu) {
  EXPECT_EQ(parse("contact: {}\n").contact.normal_updates, NormalUpdates::nested);
  EXPECT_EQ(
      parse("contact: {normal_updates: linearized}\nsolver: {linear_solver: klu}\n").contact.normal_updates,
      NormalUpdates::linearized);
  EXPECT_EQ(parse("contact: {normal_updates: inside_newton}\n").contact.normal_updates,
            NormalUpdates::inside_newton);
}

TEST(ScenarioContactErrors, LinearizedNormalsNeedLu) {
  const std::string expected =
      "contact.normal_updates: expected nested or inside_newton with solver.linear_solver: cholmod (the "
      "linearized normals' tangent is not symmetric and needs LU: set solver.linear_solver: umfpack, mumps "
      "or "
      "klu), got linearized";
  EXPECT_EQ(error_of("contact:\n  normal_updates: linearized\nsolver: {linear_solver: cholmod}\n"),
            "knot.yaml:26: " + expected);
  EXPECT_EQ(error_of("contact:\n  normal_updates: exact\n"),
            "knot.yaml:26: contact.normal_updates: expected one of nested | inside_newton | linearized, got "
            "exact");
}

TEST(ScenarioContactErrors, UnknownBeam) {
  EXPECT_EQ(error_of("contact:\n  beams: [rod, rdo]\n"),
            "knot.yaml:26: contact.beams[1]: expected the name of a beam (rod | strand | wire), got rdo");
  EXPECT_EQ(error_of("contact:\n  beams:\n    - wire\n    - [rod]\n"),
            "knot.yaml:28: contact.beams[1]: expected the name of a beam (rod | strand | wire), got [rod]");
}

TEST(ScenarioContactErrors, DuplicateBeam) {
  EXPECT_EQ(error_of("contact:\n  beams:\n    - rod\n    - strand\n    - rod\n"),
            "knot.yaml:29: contact.beams[2]: expected each beam once in contact.beams, got rod");
}

TEST(ScenarioContactErrors, BeamsNotANonEmptyList) {
  const std::string expected = "expected a list of beam names, non-empty, each beam once";
  EXPECT_EQ(error_of("contact:\n  beams: []\n"), "knot.yaml:26: contact.beams: " + expected + ", got []");
  EXPECT_EQ(error_of("contact:\n  beams:\n"),
            "knot.yaml:26: contact.beams: " + expected + ", got nothing (null)");
  EXPECT_EQ(error_of("contact:\n  beams: rod\n"), "knot.yaml:26: contact.beams: " + expected + ", got rod");
}

TEST(ScenarioContactErrors, FrictionPairs) {
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {beams: [rod, rdo], friction: 0}\n"),
            "knot.yaml:27: contact.friction_pairs[0].beams[1]: expected the name of a beam (rod | strand | "
            "wire), got rdo");
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {beams: [rod], with: [wire, wire], friction: 0}\n"),
            "knot.yaml:27: contact.friction_pairs[0].with[1]: expected each beam once in "
            "contact.friction_pairs[].with, got wire");
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {beams: [rod]}\n"),
            "knot.yaml:27: contact.friction_pairs[0].friction: expected a number >= 0, got nothing (missing "
            "key)");
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {friction: 0.1}\n"),
            "knot.yaml:27: contact.friction_pairs[0].beams: expected a list of beam names, non-empty, each "
            "beam once, got nothing (missing key)");
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {beams: [], friction: 0.1}\n"),
            "knot.yaml:27: contact.friction_pairs[0].beams: expected a list of beam names, non-empty, each "
            "beam once, got []");
  EXPECT_EQ(error_of("contact:\n  friction_pairs:\n    - {beams: [rod], friction: -0.1}\n"),
            "knot.yaml:27: contact.friction_pairs[0].friction: expected a number >= 0, got -0.1");
  EXPECT_EQ(
      error_of("contact:\n  friction_pairs:\n    - {beams: [rod], friction: 0, mu: 1}\n"),
      "knot.yaml:27: contact.friction_pairs[0].mu: expected one of the keys beams | with | friction, got "
      "an unknown key");
  EXPECT_EQ(error_of("contact:\n  friction_pairs: {beams: [rod], friction: 0}\n"),
            "knot.yaml:26: contact.friction_pairs: expected a list of maps, got a map");
}

TEST(ScenarioContactErrors, NonPositiveLengths) {
  EXPECT_EQ(error_of("contact:\n  proximity_distance: -0.3\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got -0.3");
  EXPECT_EQ(error_of("contact:\n  self_contact: true\n  test_point_spacing: 0\n"),
            "knot.yaml:27: contact.test_point_spacing: expected a number > 0 or auto (mm), got 0");
  EXPECT_EQ(error_of("contact:\n  element_spacing: -1e-3\n"),
            "knot.yaml:26: contact.element_spacing: expected a number > 0 or auto (mm), got -1e-3");
  EXPECT_EQ(error_of("contact:\n  matching_length: -2\n"),
            "knot.yaml:26: contact.matching_length: expected a number > 0 or auto, >= test_point_spacing "
            "(mm), got -2");
  EXPECT_EQ(error_of("contact:\n  separation_distance: 0\n"),
            "knot.yaml:26: contact.separation_distance: expected a number > 0 or auto, > proximity_distance "
            "(mm), got 0");
}

TEST(ScenarioContactErrors, NonPositivePenaltyAndMechanicsLengths) {
  EXPECT_EQ(error_of("contact:\n  penalty: -100\n"),
            "knot.yaml:26: contact.penalty: expected a number > 0 or auto (N/mm), got -100");
  EXPECT_EQ(error_of("contact:\n  forces: true\n  penalty: 0\n"),
            "knot.yaml:27: contact.penalty: expected a number > 0 or auto (N/mm), got 0");
  EXPECT_EQ(error_of("contact:\n  max_penetration: -0.002\n"),
            "knot.yaml:26: contact.max_penetration: expected a number > 0 or auto (mm), got -0.002");
  EXPECT_EQ(error_of("contact:\n  max_penetration: 0\n"),
            "knot.yaml:26: contact.max_penetration: expected a number > 0 or auto (mm), got 0");
  EXPECT_EQ(error_of("contact:\n  particles: moving\n"),
            "knot.yaml:26: contact.particles: expected one of fixed | facing | centres, got moving");
  EXPECT_EQ(error_of("contact:\n  regularization: -1e-4\n"),
            "knot.yaml:26: contact.regularization: expected a number > 0 or auto (mm), got -1e-4");
  EXPECT_EQ(error_of("contact:\n  beams: [rod]\n  max_reversible_slip: 0\n"),
            "knot.yaml:27: contact.max_reversible_slip: expected a number > 0 or auto (mm), got 0");
  EXPECT_EQ(error_of("contact:\n  normal_tolerance: 0\n"),
            "knot.yaml:26: contact.normal_tolerance: expected a number > 0 (rad), got 0");
  EXPECT_EQ(error_of("contact:\n  normal_tolerance: -0.01\n"),
            "knot.yaml:26: contact.normal_tolerance: expected a number > 0 (rad), got -0.01");
}

TEST(ScenarioContactErrors, NegativeFriction) {
  EXPECT_EQ(error_of("contact:\n  friction: -0.3\n"),
            "knot.yaml:26: contact.friction: expected a number >= 0, got -0.3");
  EXPECT_EQ(error_of("contact:\n  self_contact: false\n  friction: -1e-9\n"),
            "knot.yaml:27: contact.friction: expected a number >= 0, got -1e-9");
}

TEST(ScenarioContactErrors, LoopCountsBelowOne) {
  EXPECT_EQ(error_of("contact:\n  max_detections: 0\n"),
            "knot.yaml:26: contact.max_detections: expected an integer >= 1, got 0");
  EXPECT_EQ(error_of("contact:\n  max_detections: -2\n"),
            "knot.yaml:26: contact.max_detections: expected an integer >= 1, got -2");
  EXPECT_EQ(error_of("contact:\n  friction: 0.1\n  max_normal_iterations: 0\n"),
            "knot.yaml:27: contact.max_normal_iterations: expected an integer >= 1, got 0");
  EXPECT_EQ(error_of("contact:\n  max_normal_iterations: -1\n"),
            "knot.yaml:26: contact.max_normal_iterations: expected an integer >= 1, got -1");
}

TEST(ScenarioContactErrors, MechanicsKeysOfTheWrongType) {
  EXPECT_EQ(error_of("contact:\n  forces: yes\n"),
            "knot.yaml:26: contact.forces: expected true or false, got yes");
  EXPECT_EQ(error_of("contact:\n  forces: 0\n"),
            "knot.yaml:26: contact.forces: expected true or false, got 0");
  EXPECT_EQ(error_of("contact:\n  penalty: stiff\n"),
            "knot.yaml:26: contact.penalty: expected a number > 0 or auto (N/mm), got stiff");
  EXPECT_EQ(error_of("contact:\n  penalty: \"100\"\n"),  // quoted: a string
            "knot.yaml:26: contact.penalty: expected a number > 0 or auto (N/mm), got \"100\"");
  EXPECT_EQ(error_of("contact:\n  max_penetration: [0.002]\n"),
            "knot.yaml:26: contact.max_penetration: expected a number > 0 or auto (mm), got [0.002]");
  EXPECT_EQ(error_of("contact:\n  regularization:\n"),
            "knot.yaml:26: contact.regularization: expected a number > 0 or auto (mm), got nothing (null)");
  EXPECT_EQ(error_of("contact:\n  max_reversible_slip: AUTO\n"),
            "knot.yaml:26: contact.max_reversible_slip: expected a number > 0 or auto (mm), got AUTO");
  // friction, the loop counts and normal_tolerance have a plain default: auto is not a value of theirs
  EXPECT_EQ(error_of("contact:\n  friction: auto\n"),
            "knot.yaml:26: contact.friction: expected a number >= 0, got auto");
  EXPECT_EQ(error_of("contact:\n  friction: high\n"),
            "knot.yaml:26: contact.friction: expected a number >= 0, got high");
  EXPECT_EQ(error_of("contact:\n  max_detections: 2.5\n"),
            "knot.yaml:26: contact.max_detections: expected an integer >= 1, got 2.5");
  EXPECT_EQ(error_of("contact:\n  max_detections: auto\n"),
            "knot.yaml:26: contact.max_detections: expected an integer >= 1, got auto");
  EXPECT_EQ(error_of("contact:\n  max_normal_iterations: 1e1\n"),
            "knot.yaml:26: contact.max_normal_iterations: expected an integer >= 1, got 1e1");
  EXPECT_EQ(error_of("contact:\n  max_normal_iterations: \"6\"\n"),
            "knot.yaml:26: contact.max_normal_iterations: expected an integer >= 1, got \"6\"");
  EXPECT_EQ(error_of("contact:\n  normal_tolerance: auto\n"),
            "knot.yaml:26: contact.normal_tolerance: expected a number > 0 (rad), got auto");
  EXPECT_EQ(error_of("contact:\n  normal_tolerance: .inf\n"),
            "knot.yaml:26: contact.normal_tolerance: expected a number > 0 (rad), got .inf");
}

TEST(ScenarioContactErrors, LengthsThatAreNotNumbers) {
  EXPECT_EQ(error_of("contact:\n  proximity_distance: thick\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got thick");
  EXPECT_EQ(error_of("contact:\n  proximity_distance: \"0.3\"\n"),  // quoted: a string
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got \"0.3\"");
  EXPECT_EQ(error_of("contact:\n  proximity_distance: \"auto\"\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got \"auto\"");
  EXPECT_EQ(error_of("contact:\n  proximity_distance: Auto\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got Auto");
  EXPECT_EQ(error_of("contact:\n  proximity_distance: [0.3]\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got [0.3]");
  EXPECT_EQ(
      error_of("contact:\n  proximity_distance:\n"),
      "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got nothing (null)");
  EXPECT_EQ(error_of("contact:\n  proximity_distance: .nan\n"),
            "knot.yaml:26: contact.proximity_distance: expected a number > 0 or auto (mm), got .nan");
}

TEST(ScenarioContactErrors, Booleans) {
  EXPECT_EQ(error_of("contact:\n  enabled: yes\n"),
            "knot.yaml:26: contact.enabled: expected true or false, got yes");
  EXPECT_EQ(error_of("contact:\n  beams: [rod]\n  self_contact: 1\n"),
            "knot.yaml:27: contact.self_contact: expected true or false, got 1");
}

TEST(ScenarioContactErrors, UnknownKey) {
  const std::string keys =
      "one of the keys enabled | self_contact | beams | proximity_distance | separation_distance | "
      "test_point_spacing | matching_length | element_spacing | section_pairing | forces | penalty | "
      "max_penetration | "
      "regularization | friction | friction_pairs | max_reversible_slip | friction_tangent | particles | "
      "max_detections | "
      "normal_updates | max_normal_iterations | normal_tolerance | normal_pass_residual | crossing_guard";
  EXPECT_EQ(error_of("contact:\n  self_contact: true\n  proximity: 0.3\n"),
            "knot.yaml:27: contact.proximity: expected " + keys + ", got an unknown key");
  EXPECT_EQ(error_of("contact: {coulomb: 0.2}\n"),
            "knot.yaml:25: contact.coulomb: expected " + keys + ", got an unknown key");
  EXPECT_EQ(error_of("contact:\n  friction: 0.2\n  stiffness: 100\n"),
            "knot.yaml:27: contact.stiffness: expected " + keys + ", got an unknown key");
}

TEST(ScenarioContactErrors, RepeatedKey) {
  EXPECT_EQ(
      error_of("contact:\n  proximity_distance: 0.3\n  proximity_distance: 0.4\n"),
      "knot.yaml:27: contact.proximity_distance: expected each key once (first given at line 26), got a "
      "repeated key");
}

TEST(ScenarioContactErrors, SectionNotAMap) {
  EXPECT_EQ(error_of("contact: [rod, strand]\n"), "knot.yaml:25: contact: expected a map, got [rod, strand]");
  EXPECT_EQ(error_of("contact: true\n"), "knot.yaml:25: contact: expected a map, got true");
}

TEST(ScenarioContactErrors, MatchingIntervalsMustOverlap) {
  EXPECT_EQ(error_of("contact:\n  test_point_spacing: 0.2\n  matching_length: 0.15\n"),
            "knot.yaml:27: contact.matching_length: expected >= test_point_spacing (successive matching "
            "intervals must overlap), got 0.15");
  // reported at matching_length whichever comes first
  EXPECT_EQ(error_of("contact:\n  matching_length: 0.15\n  beams: [rod]\n  test_point_spacing: 0.2\n"),
            "knot.yaml:26: contact.matching_length: expected >= test_point_spacing (successive matching "
            "intervals must overlap), got 0.15");
}

TEST(ScenarioContactErrors, SeparationMustExceedProximity) {
  EXPECT_EQ(
      error_of("contact:\n  proximity_distance: 0.3\n  separation_distance: 0.3\n"),
      "knot.yaml:27: contact.separation_distance: expected > proximity_distance (neighbouring parts of a "
      "beam would be paired), got 0.3");
  EXPECT_EQ(
      error_of("contact:\n  separation_distance: 0.2\n  proximity_distance: 0.3\n"),
      "knot.yaml:26: contact.separation_distance: expected > proximity_distance (neighbouring parts of a "
      "beam would be paired), got 0.2");
}

// ---- describe ----

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ScenarioContactDescribe, ShowsTheSectionAfterOutput) {
  const std::string text = describe(parse("contact:\n  beams: [wire, rod]\n  proximity_distance: 0.3\n"));
  const auto output = text.find("\noutput:\n");
  const auto contact = text.find("\ncontact:\n");
  ASSERT_NE(output, std::string::npos) << text;
  ASSERT_NE(contact, std::string::npos) << text;
  EXPECT_LT(output, contact) << text;
  EXPECT_TRUE(contains(text,
                       "contact:\n"
                       "  enabled: true\n"
                       "  self_contact: true\n"
                       "  beams: [wire, rod]\n"
                       "  proximity_distance: 0.3  # mm\n"
                       "  separation_distance: auto  # mm\n"
                       "  test_point_spacing: auto  # mm\n"
                       "  matching_length: auto  # mm\n"
                       "  element_spacing: auto  # mm\n"
                       "  section_pairing: plane\n"
                       "  forces: true\n"
                       "  penalty: auto  # N/mm\n"
                       "  max_penetration: auto  # mm\n"
                       "  regularization: auto  # mm\n"
                       "  friction: 0\n"
                       "  max_reversible_slip: auto  # mm\n"
                       "  friction_tangent: frozen\n"
                       "  particles: fixed\n"
                       "  max_detections: 4\n"
                       "  normal_updates: nested\n"
                       "  max_normal_iterations: 6\n"
                       "  normal_tolerance: 0.001  # rad\n"))
      << text;

  const std::string given = describe(
      parse("contact:\n  forces: false\n  penalty: 250\n  max_penetration: 0.004\n  regularization: 0.0005\n"
            "  friction: 0.3\n  max_reversible_slip: 0.002\n  particles: facing\n  max_detections: 2\n"
            "  max_normal_iterations: 10\n  normal_tolerance: 1e-4\n"));
  EXPECT_TRUE(contains(given,
                       "  element_spacing: auto  # mm\n"
                       "  section_pairing: plane\n"
                       "  forces: false\n"
                       "  penalty: 250  # N/mm\n"
                       "  max_penetration: 0.004  # mm\n"
                       "  regularization: 0.0005  # mm\n"
                       "  friction: 0.3\n"
                       "  max_reversible_slip: 0.002  # mm\n"
                       "  friction_tangent: frozen\n"
                       "  particles: facing\n"
                       "  max_detections: 2\n"
                       "  normal_updates: nested\n"
                       "  max_normal_iterations: 10\n"
                       "  normal_tolerance: 0.0001  # rad\n"))
      << given;

  const std::string absent = describe(parse(""));
  EXPECT_TRUE(contains(
      absent,
      "contact:\n  enabled: false\n  self_contact: true\n  beams: [rod, strand, wire]  # all beams\n"))
      << absent;
}

TEST(ScenarioContactDescribe, RoundTrips) {
  for (const std::string section :
       {"", "contact: {}\n", "contact: {enabled: false, self_contact: false}\n",
        "contact:\n  beams: [strand]\n  proximity_distance: 0.5\n  separation_distance: 2.5\n"
        "  test_point_spacing: 0.25\n  matching_length: 0.75\n  element_spacing: 0.125\n",
        "contact:\n  forces: false\n  penalty: 123.456\n  max_penetration: 0.0021\n  regularization: auto\n"
        "  friction: 0.3\n  max_reversible_slip: 1e-3\n  particles: facing\n  max_detections: 7\n"
        "  max_normal_iterations: 1\n  normal_tolerance: 2.5e-4\n",
        "contact: {enabled: false, friction: 0.1, penalty: 1e5, max_penetration: auto}\n",
        "contact: {friction: 0.2, friction_tangent: varying}\nsolver: {linear_solver: umfpack}\n",
        "contact:\n  friction: 0.3\n  friction_pairs:\n    - {beams: [wire, rod], friction: 0}\n"
        "    - {beams: [strand], with: [rod], friction: 0.125}\n"}) {
    const Scenario original = parse(section);
    Scenario again;
    ASSERT_NO_THROW(again = parse_scenario(describe(original), "described.yaml")) << describe(original);
    const ContactSettings& a = original.contact;
    const ContactSettings& b = again.contact;
    EXPECT_EQ(a.enabled, b.enabled) << section;
    EXPECT_EQ(a.self_contact, b.self_contact) << section;
    // describe names every beam when all take part
    const std::vector<int> all_beams{0, 1, 2};
    EXPECT_EQ(a.beams.empty() ? all_beams : a.beams, b.beams) << section;
    EXPECT_EQ(a.proximity_distance, b.proximity_distance) << section;
    EXPECT_EQ(a.separation_distance, b.separation_distance) << section;
    EXPECT_EQ(a.test_point_spacing, b.test_point_spacing) << section;
    EXPECT_EQ(a.matching_length, b.matching_length) << section;
    EXPECT_EQ(a.element_spacing, b.element_spacing) << section;
    EXPECT_EQ(a.forces, b.forces) << section;
    EXPECT_EQ(a.penalty, b.penalty) << section;
    EXPECT_EQ(a.max_penetration, b.max_penetration) << section;
    EXPECT_EQ(a.regularization, b.regularization) << section;
    EXPECT_EQ(a.friction, b.friction) << section;
    EXPECT_EQ(a.max_reversible_slip, b.max_reversible_slip) << section;
    EXPECT_EQ(a.friction_tangent, b.friction_tangent) << section;
    EXPECT_EQ(a.facing_particles, b.facing_particles) << section;
    EXPECT_EQ(a.centre_facing, b.centre_facing) << section;
    EXPECT_EQ(a.max_detections, b.max_detections) << section;
    EXPECT_EQ(a.max_normal_iterations, b.max_normal_iterations) << section;
    EXPECT_EQ(a.normal_tolerance, b.normal_tolerance) << section;
    ASSERT_EQ(a.friction_pairs.size(), b.friction_pairs.size()) << section;
    for (std::size_t k = 0; k < a.friction_pairs.size(); ++k) {
      EXPECT_EQ(a.friction_pairs[k].beams, b.friction_pairs[k].beams) << section;
      EXPECT_EQ(a.friction_pairs[k].with, b.friction_pairs[k].with) << section;
      EXPECT_EQ(a.friction_pairs[k].friction, b.friction_pairs[k].friction) << section;
    }
  }
}

}  // namespace
}  // namespace nodus::scenario
