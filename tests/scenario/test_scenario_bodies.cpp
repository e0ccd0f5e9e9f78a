// Tests of the scenario side of rigid bodies (docs/scenario.md, docs/bodies.md): the `bodies` section and
// conditions on bodies read and resolved (sections, defaults, dof masks, pivot, loads); bad input gives one
// line with file, line and key; validate() refuses bad body data of a scenario built in code; the echo reads
// back as the same scenario (same fingerprint); the fingerprint changes with every body value and a scenario
// without bodies gets no body line in it.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yarn.hpp"

namespace nodus::scenario {
namespace {

// Lines: 1-2 materials, 3 beams, 4 a (2 elements: nodes 0..4), 5 b (3 elements: nodes 0..6), 6 c.
const std::string kHead = R"(materials:
  - {name: pa, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: a, material: pa, radius: 0.1, length: 4, elements: 2}
  - {name: b, material: pa, radius: 0.1, length: 4, elements: 3, start: [0, 0.3, 0]}
  - {name: c, material: pa, radius: 0.1, length: 4, elements: 1, start: [0, 0.6, 0]}
)";
// Lines 7-9.
const std::string kBodies = R"(bodies:
  - {name: left, beams: [a, b], at: start}
  - {name: right, beams: [b, a, c], at: end, penalty: 500, tie: 1e-4}
)";
const std::string kStages = R"(stages:
  - {name: s, steps: 1}
)";

Scenario parse(const std::string& text) {
  return parse_scenario(text, "b.yaml");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ScenarioError& error) {
    return error.what();
  }
  return "no error";
}

TEST(ScenarioBodies, SectionsResolvedFromBeamsAndAt) {
  const Scenario s = parse(kHead + kBodies + kStages);
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodySpec& left = s.bodies[0];
  EXPECT_EQ(left.name, "left");
  EXPECT_EQ(left.line, 8);
  // at: start is node 0 of each beam.
  ASSERT_EQ(left.sections.size(), 2u);
  EXPECT_EQ(left.sections[0].beam, 0);
  EXPECT_EQ(left.sections[0].node, 0);
  EXPECT_EQ(left.sections[1].beam, 1);
  EXPECT_EQ(left.sections[1].node, 0);
  // penalty and tie left out: auto, held as 0.
  EXPECT_EQ(left.penalty, 0.0);
  EXPECT_EQ(left.tie, 0.0);

  // at: end is node 2 elements of each beam, in the order of the list.
  const BodySpec& right = s.bodies[1];
  EXPECT_EQ(right.line, 9);
  ASSERT_EQ(right.sections.size(), 3u);
  EXPECT_EQ(right.sections[0].beam, 1);
  EXPECT_EQ(right.sections[0].node, 6);
  EXPECT_EQ(right.sections[1].beam, 0);
  EXPECT_EQ(right.sections[1].node, 4);
  EXPECT_EQ(right.sections[2].beam, 2);
  EXPECT_EQ(right.sections[2].node, 2);
  EXPECT_EQ(right.penalty, 500.0);
  EXPECT_EQ(right.tie, 1e-4);

  // The word auto reads as 0, as does leaving the key out.
  const Scenario autos =
      parse(kHead + "bodies:\n  - {name: one, beams: [c], at: end, penalty: auto, tie: auto}\n" + kStages);
  EXPECT_EQ(autos.bodies[0].penalty, 0.0);
  EXPECT_EQ(autos.bodies[0].tie, 0.0);

  // No bodies section: none; an empty one is allowed.
  EXPECT_TRUE(parse(kHead + kStages).bodies.empty());
  EXPECT_TRUE(parse(kHead + "bodies: []\n" + kStages).bodies.empty());
}

TEST(ScenarioBodies, FileBodiesComeAfterTheYarnsAndMayBindTheirFibres) {
  const std::string text = kHead + R"(yarns:
  - {name: y, rovings: 2, fibres_per_roving: 1, fibre_radius: 0.05, length: 4, elements: 2, material: pa}
bodies:
  - {name: clip, beams: [y.r1.f1, a], at: end}
conditions:
  - {name: hold, type: clamp, bodies: [y.r2.start, clip]}
)" + kStages;
  const Scenario s = parse(text);
  ASSERT_EQ(s.beams.size(), 5u);   // a b c, then y.r1.f1 y.r2.f1
  ASSERT_EQ(s.bodies.size(), 5u);  // y.r1.start y.r1.end y.r2.start y.r2.end, then clip
  EXPECT_EQ(s.bodies[4].name, "clip");
  ASSERT_EQ(s.bodies[4].sections.size(), 2u);
  EXPECT_EQ(s.bodies[4].sections[0].beam, 3);
  EXPECT_EQ(s.bodies[4].sections[0].node, 4);
  EXPECT_EQ(s.bodies[4].sections[1].beam, 0);
  EXPECT_EQ(s.bodies[4].sections[1].node, 4);
  EXPECT_EQ(s.conditions[0].bodies, (std::vector<int>{2, 4}));
}

TEST(ScenarioBodies, ConditionsOnBodies) {
  const std::string text = kHead + kBodies + R"(conditions:
  - {name: all, type: clamp, bodies: [left]}
  - {name: pos, type: clamp, bodies: [right], dofs: [position], active: false}
  - {name: rot, type: motion, bodies: [left, right], dofs: [rotation], active: false}
  - {name: some, type: motion, bodies: [right], dofs: [x, rz, ry], pivot: [4, 0.3, 0.5], active: false}
  - {name: every, type: clamp, bodies: [right, left], dofs: [x, all], active: false}
  - {name: pull, type: load, bodies: [right], force: [1, 2, 3], moment: [0, 0, -2], active: false}
  - {name: rest, type: load, bodies: [left]}
  - {name: tip, type: clamp, beam: c, at: end, active: false}
)" + R"(stages:
  - name: s
    steps: 1
    loads: {rest: {moment: [0, 5, 0]}}
)";
  const Scenario s = parse(text);
  ASSERT_EQ(s.conditions.size(), 8u);
  const auto mask = [](std::initializer_list<int> on) {
    BodyDofMask m{};
    for (int d : on) m[static_cast<std::size_t>(d)] = true;
    return m;
  };
  const ConditionSpec& all = s.conditions[0];
  EXPECT_EQ(all.bodies, (std::vector<int>{0}));
  EXPECT_EQ(all.body_dofs, mask({kBodyX, kBodyY, kBodyZ, kBodyRx, kBodyRy, kBodyRz}));  // default: all six
  EXPECT_TRUE(all.initially_active);
  EXPECT_FALSE(all.pivot.has_value());
  EXPECT_EQ(s.conditions[1].body_dofs, mask({kBodyX, kBodyY, kBodyZ}));
  EXPECT_FALSE(s.conditions[1].initially_active);
  EXPECT_EQ(s.conditions[2].bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(s.conditions[2].body_dofs, mask({kBodyRx, kBodyRy, kBodyRz}));
  EXPECT_EQ(s.conditions[3].body_dofs, mask({kBodyX, kBodyRy, kBodyRz}));  // the union, in any order
  ASSERT_TRUE(s.conditions[3].pivot.has_value());
  EXPECT_EQ(*s.conditions[3].pivot, Vec3(4, 0.3, 0.5));
  EXPECT_EQ(s.conditions[4].bodies, (std::vector<int>{1, 0}));
  EXPECT_EQ(s.conditions[4].body_dofs, mask({kBodyX, kBodyY, kBodyZ, kBodyRx, kBodyRy, kBodyRz}));

  // Loads on one body: force, moment and its fixed axis (the first nonzero moment, here the stage's).
  const ConditionSpec& pull = s.conditions[5];
  EXPECT_EQ(pull.type, ConditionType::load);
  EXPECT_EQ(pull.bodies, (std::vector<int>{1}));
  EXPECT_EQ(pull.force, Vec3(1, 2, 3));
  EXPECT_EQ(pull.moment, Vec3(0, 0, -2));
  ASSERT_TRUE(pull.moment_axis.has_value());
  EXPECT_EQ(*pull.moment_axis, Vec3(0, 0, -1));
  ASSERT_TRUE(s.conditions[6].moment_axis.has_value());
  EXPECT_EQ(*s.conditions[6].moment_axis, Vec3(0, 1, 0));
  EXPECT_EQ(s.conditions[6].force, Vec3::Zero());

  // A condition on a beam section beside them keeps its own fields, and no bodies.
  EXPECT_TRUE(s.conditions[7].bodies.empty());
  EXPECT_EQ(s.conditions[7].beam, 2);
  EXPECT_EQ(s.conditions[7].node, 2);
}

TEST(ScenarioBodies, BadInputOneLineNamingTheKey) {
  // Line 10: the first condition (after "conditions:" on line 10 the item is line 11).
  const std::string conditions = kHead + kBodies + "conditions:\n";
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      // The bodies section.
      {kHead + "bodies:\n  - {name: x, beams: [a, d], at: start}\n" + kStages,
       "b.yaml:8: bodies[0].beams[1]: expected the name of a beam (a | b | c), got d"},
      {kHead + "bodies:\n  - {name: x, beams: [a, b, a], at: start}\n" + kStages,
       "b.yaml:8: bodies[0].beams[2]: expected each beam once in beams, got a"},
      {kHead + "bodies:\n  - {name: x, beams: [], at: start}\n" + kStages,
       "b.yaml:8: bodies[0].beams: expected a list of beam names, non-empty, each beam once, got []"},
      {kHead + "bodies:\n  - {name: x, beams: [a], at: 0}\n" + kStages,
       "b.yaml:8: bodies[0].at: expected one of start | end, got 0"},
      {kHead + "bodies:\n  - {name: x, beams: [a]}\n" + kStages,
       "b.yaml:8: bodies[0].at: expected one of start | end, got nothing (missing key)"},
      {kHead + "bodies:\n  - {name: x, beams: [a], at: end, penalty: 0}\n" + kStages,
       "b.yaml:8: bodies[0].penalty: expected a number > 0 or auto, got 0"},
      {kHead + "bodies:\n  - {name: x, beams: [a], at: end, tie: -1}\n" + kStages,
       "b.yaml:8: bodies[0].tie: expected a number > 0 or auto, got -1"},
      {kHead + "bodies:\n  - {name: x, beams: [a], at: end}\n  - {name: x, beams: [b], at: end}\n" + kStages,
       "b.yaml:9: bodies[1].name: expected a name unique among bodies (already used at line 8), got x"},
      // A body named like a yarn's body.
      {kHead +
           "yarns:\n  - {name: y, rovings: 1, fibres_per_roving: 1, fibre_radius: 0.05, length: 4, "
           "elements: 2, material: pa}\nbodies:\n  - {name: y.r1.end, beams: [a], at: end}\n" +
           kStages,
       "b.yaml:10: bodies[0].name: expected a name unique among bodies (already used at line 8), got "
       "y.r1.end"},
      // A body and a condition of one name, whichever comes first in the file.
      {conditions + "  - {name: left, type: clamp, beam: c, at: start}\n" + kStages,
       "b.yaml:11: conditions[0].name: expected a name unique among conditions and bodies (already used at "
       "line 8), got left"},
      {kHead + "conditions:\n  - {name: left, type: clamp, beam: c, at: start}\n" + kBodies + kStages,
       "b.yaml:8: conditions[0].name: expected a name unique among conditions and bodies (already used at "
       "line 10), got left"},

      // Conditions on bodies.
      {conditions + "  - {name: k, type: clamp, bodies: [middle]}\n" + kStages,
       "b.yaml:11: conditions[0].bodies[0]: expected the name of a body (left | right), got middle"},
      {conditions + "  - {name: k, type: clamp, bodies: [left, right, left]}\n" + kStages,
       "b.yaml:11: conditions[0].bodies[2]: expected each body once in bodies, got left"},
      {conditions + "  - {name: k, type: clamp, bodies: []}\n" + kStages,
       "b.yaml:11: conditions[0].bodies: expected a list of body names, non-empty, each once; one for a "
       "load, two or more for a bind; not with beam, at or type rigid, got []"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], beam: a}\n" + kStages,
       "b.yaml:11: conditions[0].beam: expected no beam next to bodies (the condition acts on the bodies), "
       "got a"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], at: start}\n" + kStages,
       "b.yaml:11: conditions[0].at: expected no at next to bodies (the condition acts on the bodies), got "
       "start"},
      {conditions + "  - {name: k, type: rigid, bodies: [left]}\n" + kStages,
       "b.yaml:11: conditions[0].bodies: expected no bodies on a rigid condition (bodies are for clamp, "
       "motion, load and bind conditions), got [left]"},
      {conditions + "  - {name: k, type: load, bodies: [left, right]}\n" + kStages,
       "b.yaml:11: conditions[0].bodies[1]: expected one body for a load condition, got right"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], pivot: [0, 0, 0]}\n" + kStages,
       "b.yaml:11: conditions[0].pivot: expected no pivot on a clamp condition (pivot is for motion and "
       "rigid conditions), got [0, 0, 0]"},
      {conditions + "  - {name: k, type: load, bodies: [left], pivot: [0, 0, 0]}\n" + kStages,
       "b.yaml:11: conditions[0].pivot: expected no pivot on a load condition (pivot is for motion and "
       "rigid conditions), got [0, 0, 0]"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], dofs: [x, g1x]}\n" + kStages,
       "b.yaml:11: conditions[0].dofs[1]: expected one of all | position | rotation | x | y | z | rx | ry | "
       "rz (on bodies), got g1x"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], dofs: [directors]}\n" + kStages,
       "b.yaml:11: conditions[0].dofs[0]: expected one of all | position | rotation | x | y | z | rx | ry | "
       "rz (on bodies), got directors"},
      {conditions + "  - {name: k, type: clamp, bodies: [left], dofs: []}\n" + kStages,
       "b.yaml:11: conditions[0].dofs: expected a list of at least one of all | position | directors | x | y "
       "| z | g1x | g1y | g1z | g2x | g2y | g2z; on bodies: all | position | rotation | x | y | z | rx | ry "
       "| rz; bind: position | x | y | z, default position, got []"},
      // And rotation items on a beam section.
      {conditions + "  - {name: k, type: clamp, beam: a, at: start, dofs: [rx]}\n" + kStages,
       "b.yaml:11: conditions[0].dofs[0]: expected one of all | position | directors | x | y | z | g1x | "
       "g1y | g1z | g2x | g2y | g2z, got rx"},
      {conditions + "  - {name: k, type: load, bodies: [left], dofs: [x]}\n" + kStages,
       "b.yaml:11: conditions[0].dofs: expected no dofs on a load condition (dofs are for clamp and motion "
       "conditions), got [x]"},
      {conditions + "  - {name: k, type: motion, bodies: [left], force: [1, 0, 0]}\n" + kStages,
       "b.yaml:11: conditions[0].force: expected no force on a motion condition (force is for load "
       "conditions only), got [1, 0, 0]"},
      {conditions + "  - {name: k, type: load, bodies: [left], moment: [0, 0, 1]}\n" +
           "stages:\n  - {name: s, steps: 1, loads: {k: {moment: [0, 1, 0]}}}\n",
       "b.yaml:13: stages[0].loads.k.moment: expected a moment parallel to [0, 0, 1] given at "
       "conditions[0].moment (line 11) (moment axis must stay fixed), got [0, 1, 0]"},
      // Releasing a condition that holds several bodies.
      {conditions + "  - {name: k, type: motion, bodies: [left, right], dofs: [x]}\n" +
           "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, release: [k]}\n",
       "b.yaml:14: stages[1].release[0]: expected a condition on one body (a clamp or motion of several "
       "bodies is released body by body: give each its own condition), got k"},
      // A bind: two or more bodies, their translations, never released.
      {conditions + "  - {name: k, type: bind, bodies: [left]}\n" + kStages,
       "b.yaml:11: conditions[0].bodies: expected two or more bodies for a bind condition, got [left]"},
      {conditions + "  - {name: k, type: bind, bodies: [left, right], dofs: [x, rx]}\n" + kStages,
       "b.yaml:11: conditions[0].dofs: expected dofs among position | x | y | z for a bind condition, got "
       "[x, rx]"},
      {conditions + "  - {name: k, type: bind, beam: a, at: end}\n" + kStages,
       "b.yaml:11: conditions[0].type: expected a type other than bind without bodies (a bind holds the "
       "translations of two or more bodies together), got bind"},
      {conditions + "  - {name: k, type: bind, bodies: [left, right], force: [1, 0, 0]}\n" + kStages,
       "b.yaml:11: conditions[0].force: expected no force on a bind condition (force is for load "
       "conditions only), got [1, 0, 0]"},
      {conditions + "  - {name: k, type: bind, bodies: [left, right]}\n" +
           "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, release: [k]}\n",
       "b.yaml:14: stages[1].release[0]: expected a condition that is not a bind (a bind holds its bodies "
       "together to the end of the run), got k"},
  };
  for (const Case& c : cases) EXPECT_EQ(error_of(c.text), c.expected) << c.text;

  // Releasing a condition on one body, or a load, is fine.
  EXPECT_NO_THROW(parse(conditions + "  - {name: k, type: motion, bodies: [left], dofs: [x]}\n" +
                        "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, release: [k]}\n"));
}

/// A valid scenario with bodies and conditions on them, built in code as the reader would make it.
Scenario made_in_code() {
  Scenario s = parse(kHead + kBodies + R"(conditions:
  - {name: hold, type: clamp, bodies: [left, right], dofs: [x, y]}
  - {name: pull, type: load, bodies: [right], force: [1, 0, 0]}
  - {name: together, type: bind, bodies: [left, right], dofs: [x]}
)" + kStages);
  s.path = "in code";
  return s;
}

std::string validate_error(const Scenario& s) {
  try {
    validate(s);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenarioBodies, ValidateRefusesBadBodyDataBuiltInCode) {
  EXPECT_EQ(validate_error(made_in_code()), "no error");
  const auto error = [](auto change) {
    Scenario s = made_in_code();
    change(s);
    return validate_error(s);
  };
  EXPECT_EQ(
      error([](Scenario& s) { s.bodies[1].name = "left"; }),
      "in code: bodies[1].name: expected a name unique among bodies (already used by bodies[0].name), got "
      "left");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].name = ""; }),
            "in code: bodies[0].name: expected a string unique among bodies and conditions, got \"\"");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].name = "pull"; }),
            "in code: bodies[0].name: expected a name unique among conditions and bodies, got pull");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].sections.clear(); }),
            "in code: bodies[0].beams: expected a list of beam names, non-empty, each beam once, got []");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].sections[1].beam = 3; }),
            "in code: bodies[0].beams[1]: expected an index into beams (0 .. 2), got 3");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].sections[1].node = 2; }),
            "in code: bodies[0].at: expected one of start | end (node 0 or 2 elements of each beam), got 2");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[0].sections[1] = s.bodies[0].sections[0]; }),
            "in code: bodies[0].beams[1]: expected each section once, got a");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[1].penalty = -1.0; }),
            "in code: bodies[1].penalty: expected a number > 0 or auto, got -1");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[1].tie = std::nan(""); }),
            "in code: bodies[1].tie: expected a number > 0 or auto, got nan");

  // Conditions on bodies.
  EXPECT_EQ(error([](Scenario& s) { s.conditions[0].bodies[1] = 2; }),
            "in code: conditions[0].bodies[1]: expected an index into bodies (0 .. 1), got 2");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[0].bodies[1] = 0; }),
            "in code: conditions[0].bodies[1]: expected each body once in bodies, got 0");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[0].type = ConditionType::rigid; }),
            "in code: conditions[0].bodies: expected no bodies on a rigid condition (bodies are for clamp, "
            "motion, load and bind conditions), got a list");
  EXPECT_EQ(error([](Scenario& s) {
              s.conditions[1].bodies = {0, 1};
            }),
            "in code: conditions[1].bodies: expected one body for a load condition, got 2");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[0].pivot = Vec3::Zero(); }),
            "in code: conditions[0].pivot: expected no pivot on a clamp condition on bodies (pivot is for "
            "motion conditions), got [0, 0, 0]");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[2].pivot = Vec3::Zero(); }),
            "in code: conditions[2].pivot: expected no pivot on a bind condition on bodies (pivot is for "
            "motion conditions), got [0, 0, 0]");
  EXPECT_EQ(
      error([](Scenario& s) { s.conditions[0].body_dofs = {}; }),
      "in code: conditions[0].dofs: expected a list of at least one of all | position | directors | x | "
      "y | z | g1x | g1y | g1z | g2x | g2y | g2z; on bodies: all | position | rotation | x | y | z | rx | "
      "ry | rz; bind: position | x | y | z, default position, got []");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[0].moment = Vec3(0, 0, 1); }),
            "in code: conditions[0].moment: expected no moment on a clamp condition (moment is for load "
            "conditions only), got [0, 0, 1]");
  EXPECT_EQ(error([](Scenario& s) { s.conditions[1].force.x() = std::nan(""); }),
            "in code: conditions[1].force: expected a list of 3 numbers (N), got [nan, 0, 0]");
  // A clamp of several bodies released.
  EXPECT_EQ(error([](Scenario& s) {
              StageSpec next;
              next.name = "t";
              next.release = {0};
              s.stages.push_back(next);
            }),
            "in code: stages[1].release[0]: expected a condition on one body (a clamp or motion of several "
            "bodies is released body by body: give each its own condition), got hold");
  // A bind of one body, of a rotation, on a beam section, released.
  const auto bind = [](Scenario& s) {
    s.conditions[0].type = ConditionType::bind;
    s.conditions[0].body_dofs = {true, false, false, false, false, false};
  };
  EXPECT_EQ(error([&](Scenario& s) {
              bind(s);
              s.conditions[0].bodies = {0};
            }),
            "in code: conditions[0].bodies: expected two or more bodies for a bind condition, got 1");
  EXPECT_EQ(error([&](Scenario& s) {
              bind(s);
              s.conditions[0].body_dofs[kBodyRy] = true;
            }),
            "in code: conditions[0].dofs: expected dofs among position | x | y | z for a bind condition, got "
            "a rotation");
  EXPECT_EQ(error([&](Scenario& s) {
              bind(s);
              s.conditions[0].bodies.clear();
            }),
            "in code: conditions[0].type: expected a type other than bind without bodies (a bind holds the "
            "translations of two or more bodies together), got bind");
  EXPECT_EQ(error([&](Scenario& s) {
              bind(s);
              StageSpec next;
              next.name = "t";
              next.release = {0};
              s.stages.push_back(next);
            }),
            "in code: stages[1].release[0]: expected a condition that is not a bind (a bind holds its bodies "
            "together to the end of the run), got hold");
}

/// The echo of `s` read back.
Scenario echoed(const Scenario& s) {
  return parse_scenario(describe(s), "echo.yaml");
}

TEST(ScenarioBodies, EchoReadsBackAsTheSameScenario) {
  // Numbers that print with many digits, every kind of condition on bodies, and a yarn's bodies beside the
  // file's own.
  const std::string text = kHead + R"(yarns:
  - {name: y, rovings: 2, fibres_per_roving: 2, fibre_radius: 0.05, length: 4, elements: 2, material: pa}
bodies:
  - {name: left, beams: [a, b], at: start}
  - {name: right, beams: [b, a, c, y.r2.f1], at: end, penalty: 0.1, tie: 3.3333333333333335e-05}
conditions:
  - {name: hold, type: clamp, bodies: [left, y.r1.start], dofs: [position, rz]}
  - {name: turn, type: motion, bodies: [right], dofs: [rotation], pivot: [0.30000000000000004, 0, 1e-17]}
  - {name: slide, type: motion, bodies: [y.r2.end], active: false}
  - {name: pull, type: load, bodies: [y.r1.end], force: [0.1, 0.2, 0.7], moment: [0, 0, 0], active: false}
  - {name: tip, type: clamp, beam: c, at: 1, dofs: [x, g2y]}
  - {name: together, type: bind, bodies: [y.r1.end, y.r2.end, right], dofs: [x, z], active: false}
stages:
  - name: s
    steps: 2
    motions: {turn: {rotation: [0, 0, 33.333333333333336]}}
  - name: t
    steps: 1
    activate: [slide, pull, together]
    release: [turn]
    motions: {slide: {translation: [0.1, 0, 0]}}
    loads: {pull: {moment: [1, 2, 2]}}
)";
  const Scenario original = parse(text);
  const std::string echo = describe(original);
  const Scenario again = parse_scenario(echo, "echo.yaml");
  EXPECT_EQ(state_fingerprint_text(again, 2), state_fingerprint_text(original, 2)) << echo;
  // The yarn's bodies are the yarn's in the echo, not written out again.
  EXPECT_EQ(echo.find("name: y.r1.start"), std::string::npos) << echo;
  EXPECT_NE(echo.find("    penalty: auto  # 1e3\n    tie: auto  # 1e-10\n"), std::string::npos) << echo;
  ASSERT_EQ(again.bodies.size(), original.bodies.size());
  for (std::size_t b = 0; b < original.bodies.size(); ++b) {
    EXPECT_EQ(again.bodies[b].name, original.bodies[b].name);
    EXPECT_EQ(again.bodies[b].penalty, original.bodies[b].penalty);
    EXPECT_EQ(again.bodies[b].tie, original.bodies[b].tie);
  }
  // The echo is a fixed point: the echo of the echo read back is the echo, but for the path line.
  const auto body_of = [](const std::string& e) { return e.substr(e.find('\n')); };
  EXPECT_EQ(body_of(describe(echoed(again))), body_of(describe(again)));
}

TEST(ScenarioBodies, FingerprintChangesWithEveryBodyValue) {
  const Scenario base = parse(kHead + kBodies + R"(conditions:
  - {name: hold, type: clamp, bodies: [left], dofs: [x, y]}
  - {name: pull, type: load, bodies: [right], force: [1, 0, 0]}
)" + kStages);
  const std::string fingerprint = state_fingerprint_text(base, 1);
  const auto changed = [&](auto change) {
    Scenario s = base;
    change(s);
    validate(s);  // still a valid scenario: only the value differs
    return state_fingerprint_text(s, 1) != fingerprint;
  };
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[1].penalty = 501.0; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[0].penalty = 1e3; }));  // auto (0) is not its value 1e3
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[1].tie = 2e-4; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[0].name = "other"; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[0].sections.pop_back(); }));
  EXPECT_TRUE(changed([](Scenario& s) { std::swap(s.bodies[0].sections[0], s.bodies[0].sections[1]); }));
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[0].sections = {{2, 0}, {1, 0}}; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.bodies[0].sections = {{0, 4}, {1, 6}}; }));  // the other end
  EXPECT_TRUE(changed([](Scenario& s) { s.conditions[0].bodies = {1}; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.conditions[0].bodies = {0, 1}; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.conditions[0].body_dofs[kBodyRz] = true; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.conditions[0].body_dofs[kBodyY] = false; }));
  EXPECT_TRUE(changed([](Scenario& s) { s.conditions[1].bodies = {0}; }));
  // The line of a body is not part of it.
  EXPECT_FALSE(changed([](Scenario& s) { s.bodies[0].line = 99; }));
}

TEST(ScenarioBodies, NoBodyLinesInTheFingerprintWithoutBodies) {
  // The fingerprint of a scenario without bodies is what it was before bodies existed (so that its
  // checkpoints stay valid): no line of it names a body. By construction: the text with bodies, less the
  // lines of the bodies and of the body fields of conditions, is the text without them.
  const std::string conditions = "conditions:\n  - {name: tip, type: clamp, beam: c, at: end}\n";
  const Scenario without = parse(kHead + conditions + kStages);
  const std::string text = state_fingerprint_text(without, 1);
  EXPECT_EQ(text.find("bod"), std::string::npos) << text;

  const Scenario with = parse(kHead + kBodies + conditions + kStages);
  std::string kept;
  std::size_t begin = 0;
  const std::string with_text = state_fingerprint_text(with, 1);
  while (begin < with_text.size()) {
    const std::size_t end = with_text.find('\n', begin) + 1;
    const std::string line = with_text.substr(begin, end - begin);
    if (line.find("bod") == std::string::npos) kept += line;
    begin = end;
  }
  EXPECT_NE(kept, with_text);
  EXPECT_EQ(kept, text);

  // A condition on a body adds only its .bodies and .body_dofs lines to those of a beam condition's.
  Scenario on_body = with;
  on_body.conditions[0].bodies = {0};
  on_body.conditions[0].body_dofs.fill(true);
  on_body.conditions[0].beam = 0;
  on_body.conditions[0].node = 0;
  validate(on_body);
  const std::string on_body_text = state_fingerprint_text(on_body, 1);
  EXPECT_NE(on_body_text.find("conditions[0].bodies = [0]\nconditions[0].body_dofs = 111111\n"),
            std::string::npos)
      << on_body_text;
}

}  // namespace
}  // namespace nodus::scenario
