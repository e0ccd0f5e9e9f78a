// Tests of the `yarns` section (docs/yarns.md): the paper's three yarns (examples/yarn_3x*.yaml) give the
// element and dof counts of Tables 2-4 of Durville 2012 exactly; the fibres and bodies a yarn makes (names,
// order, geometry, bound sections); the echo reads back as the same scenario; a scenario built in code with
// append_yarn equals the file's and passes validate(); bad input gives one line naming the key.

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/model/model.hpp"
#include "nodus/model/yarn_layout.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yarn.hpp"

namespace nodus::scenario {
namespace {

/// The model of the scenario's beams, as simulation.cpp builds it.
model::Model build_model(const Scenario& s) {
  model::Model model(s.solver.gauss_points, s.solver.fold_stiffness);
  for (const BeamSpec& b : s.beams) {
    const Material& m = s.materials.at(static_cast<std::size_t>(b.material));
    model.add_beam({b.name, b.length, b.radius, b.elements, b.start, b.direction, b.director1,
                    beam::ElasticConstants{m.young_modulus, m.poisson_ratio}, b.bending_factor});
  }
  return model;
}

TEST(ScenarioYarns, PaperTablesTwoToFour) {
  // Durville 2012, Tables 2-4: fibres, radius [mm], elements, dofs; every yarn 6 mm long, E = 4000 MPa,
  // nu = 0.3, 3 rovings of 100-element fibres.
  struct Table {
    const char* file;
    int fibres_per_roving;
    double radius;
    int elements;
    int dofs;
  };
  for (const Table& t : {Table{"yarn_3x1", 1, 0.0564, 300, 5427}, Table{"yarn_3x9", 9, 0.0188, 2700, 48843},
                         Table{"yarn_3x25", 25, 0.0112, 7500, 135675}}) {
    SCOPED_TRACE(t.file);
    const Scenario s = read_scenario(std::string(NODUS_SOURCE_DIR) + "/examples/" + t.file + ".yaml");
    ASSERT_EQ(s.yarns.size(), 1u);
    EXPECT_EQ(s.yarns[0].rovings, 3);
    EXPECT_EQ(s.yarns[0].fibres_per_roving, t.fibres_per_roving);
    ASSERT_EQ(s.beams.size(), static_cast<std::size_t>(3 * t.fibres_per_roving));
    for (const BeamSpec& b : s.beams) {
      EXPECT_EQ(b.radius, t.radius);
      EXPECT_EQ(b.length, 6.0);
      EXPECT_EQ(b.elements, 100);
      EXPECT_EQ(s.materials.at(b.material).young_modulus, 4000.0);
      EXPECT_EQ(s.materials.at(b.material).poisson_ratio, 0.3);
    }
    const model::Model model = build_model(s);
    EXPECT_EQ(model.num_elements(), t.elements);
    EXPECT_EQ(model.num_dofs(), t.dofs);
    EXPECT_EQ(s.bodies.size(), 6u);  // two per roving
  }
}

const std::string kMaterials = R"(materials:
  - {name: pa, young_modulus: 4000, poisson_ratio: 0.3}
)";
const std::string kStages = R"(stages:
  - {name: lay, steps: 1}
)";

/// A yarn of 3 rovings of 3 fibres along `direction`, with `extra` lines appended to the yarn's map.
std::string yarn_text(const std::string& extra = "") {
  return R"(  - name: y
    rovings: 3
    fibres_per_roving: 3
    fibre_radius: 0.05
    length: 4
    elements: 5
    material: pa
)" + extra;
}

Scenario parse(const std::string& text) {
  return parse_scenario(text, "y.yaml");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ScenarioError& error) {
    return error.what();
  }
  return "no error";
}

TEST(ScenarioYarns, FibresAndBodiesAfterTheFilesOwn) {
  const std::string text =
      kMaterials + R"(beams:
  - {name: rod, material: pa, radius: 0.1, length: 4, elements: 2}
yarns:
)" +
      yarn_text(
          "    start: [1, 2, 3]\n    direction: [0, 0, 2]\n    clearance: 0.002\n    bending_factor: 0.5\n"
          "    tie: 1e-6\n") +
      R"(conditions:
  - {name: hold, type: clamp, beam: y.r2.f3, at: start}
)" + kStages +
      "contact: {beams: [y.r1.f1, rod]}\n";
  const Scenario s = parse(text);
  ASSERT_EQ(s.beams.size(), 10u);
  EXPECT_EQ(s.beams[0].name, "rod");  // the file's beams first
  EXPECT_EQ(s.beams[1].name, "y.r1.f1");
  EXPECT_EQ(s.beams[3].name, "y.r1.f3");
  EXPECT_EQ(s.beams[4].name, "y.r2.f1");
  EXPECT_EQ(s.beams[9].name, "y.r3.f3");
  EXPECT_EQ(s.conditions[0].beam, 6);  // conditions and contact name fibres
  EXPECT_EQ(s.contact.beams, (std::vector<int>{1, 0}));
  ASSERT_EQ(s.yarns.size(), 1u);
  const YarnSpec& yarn = s.yarns[0];
  EXPECT_EQ(yarn.first_beam, 1);
  EXPECT_EQ(yarn.direction, Vec3(0, 0, 1));  // normalised
  EXPECT_EQ(yarn.gap(), 0.002);

  // Every fibre: parallel to the axis, started in the section plane through start, the same director1, the
  // yarn's properties; section points 2 R + c apart at least, and exactly so for the closest pair.
  const double d = 2 * 0.05 + 0.002;
  double closest = 1e300;
  for (int i = 1; i < 10; ++i) {
    const BeamSpec& b = s.beams[static_cast<std::size_t>(i)];
    EXPECT_EQ(b.direction, Vec3(0, 0, 1));
    EXPECT_NEAR((b.start - Vec3(1, 2, 3)).dot(b.direction), 0.0, 1e-15);
    EXPECT_EQ(b.director1, s.beams[1].director1);
    EXPECT_NEAR(b.director1.dot(b.direction), 0.0, 1e-15);
    EXPECT_EQ(b.radius, 0.05);
    EXPECT_EQ(b.length, 4.0);
    EXPECT_EQ(b.elements, 5);
    EXPECT_EQ(b.bending_factor, 0.5);
    for (int j = i + 1; j < 10; ++j) closest = std::min(closest, (b.start - s.beams[j].start).norm());
  }
  EXPECT_NEAR(closest, d, 1e-14);

  // Bodies: the start then the end body of each roving, binding node 0 / node 2 elements of its fibres.
  ASSERT_EQ(s.bodies.size(), 6u);
  EXPECT_EQ(s.bodies[0].name, "y.r1.start");
  EXPECT_EQ(s.bodies[1].name, "y.r1.end");
  EXPECT_EQ(s.bodies[5].name, "y.r3.end");
  for (int k = 0; k < 3; ++k) {
    for (int end = 0; end < 2; ++end) {
      const BodySpec& body = s.bodies[static_cast<std::size_t>(2 * k + end)];
      EXPECT_EQ(body.penalty, 0.0);  // auto
      EXPECT_EQ(body.tie, 1e-6);     // the yarn's
      ASSERT_EQ(body.sections.size(), 3u);
      for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(body.sections[j].beam, 1 + 3 * k + j);
        EXPECT_EQ(body.sections[j].node, end == 0 ? 0 : 10);
      }
    }
  }

  // Without bodies: none.
  const Scenario bare = parse(kMaterials + "yarns:\n" + yarn_text("    bodies: false\n") + kStages);
  EXPECT_EQ(bare.beams.size(), 9u);
  EXPECT_TRUE(bare.bodies.empty());
}

TEST(ScenarioYarns, DefaultsAndLayout) {
  const Scenario s = parse(kMaterials + "yarns:\n" + yarn_text() + kStages);
  const YarnSpec& yarn = s.yarns[0];
  EXPECT_FALSE(yarn.clearance.has_value());
  EXPECT_EQ(yarn.gap(), 0.01 * 0.05);  // the default clearance
  EXPECT_EQ(yarn.start, Vec3::Zero());
  EXPECT_EQ(yarn.direction, Vec3::UnitX());
  EXPECT_EQ(yarn.roving_packing, model::RovingPacking::hexagonal);
  EXPECT_EQ(yarn.bending_factor, 1.0);
  EXPECT_TRUE(yarn.bodies);
  EXPECT_EQ(yarn.tie, 0.0);  // auto: the bodies' own default
  for (const BodySpec& body : s.bodies) EXPECT_EQ(body.tie, 0.0);
  // Along x the section axes are e1 = y (beams' auto director1) and e2 = x cross y = z.
  const model::YarnLayout layout = model::yarn_layout(model::RovingPacking::hexagonal, 3, 3, 0.1005);
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) {
      const model::Vec2& p = layout.fibres[k][j];
      EXPECT_EQ(s.beams[static_cast<std::size_t>(3 * k + j)].start, Vec3(0, p.x(), p.y()));
      EXPECT_EQ(s.beams[static_cast<std::size_t>(3 * k + j)].director1, Vec3::UnitY());
    }
  }
}

TEST(ScenarioYarns, EchoReadsBackAsTheSameScenario) {
  const std::string text =
      kMaterials + R"(beams:
  - {name: rod, material: pa, radius: 0.1, length: 4, elements: 2}
yarns:
)" + yarn_text("    direction: [1, 1, 0]\n    tie: 1e-6\n") +
      yarn_text("    start: [0, 1, 0]\n    bodies: false\n    roving_packing: ring\n").replace(10, 1, "z") +
      kStages;
  const Scenario original = parse(text);
  const std::string echo = describe(original);
  EXPECT_NE(echo.find("name: z  # made beams z.r1.f1 .. z.r3.f3 (9), bodies none"), std::string::npos)
      << echo;
  EXPECT_NE(echo.find("bodies y.r1.start .. y.r3.end (6)"), std::string::npos) << echo;
  EXPECT_NE(echo.find("clearance: 0.0005  # mm (default: 0.01 fibre_radius)"), std::string::npos) << echo;
  Scenario again;
  ASSERT_NO_THROW(again = parse_scenario(echo, "echo.yaml")) << echo;
  ASSERT_EQ(again.beams.size(), original.beams.size());
  for (std::size_t b = 0; b < original.beams.size(); ++b) {
    EXPECT_EQ(again.beams[b].name, original.beams[b].name);
    EXPECT_EQ(again.beams[b].start, original.beams[b].start) << b;
    EXPECT_EQ(again.beams[b].direction, original.beams[b].direction) << b;
    EXPECT_EQ(again.beams[b].director1, original.beams[b].director1) << b;
  }
  ASSERT_EQ(again.bodies.size(), original.bodies.size());
  for (std::size_t b = 0; b < original.bodies.size(); ++b)
    EXPECT_EQ(again.bodies[b].name, original.bodies[b].name);
  ASSERT_EQ(again.yarns.size(), 2u);
  for (std::size_t y = 0; y < 2; ++y) {
    EXPECT_EQ(again.yarns[y].gap(), original.yarns[y].gap());  // the default clearance, written out
    EXPECT_EQ(again.yarns[y].roving_packing, original.yarns[y].roving_packing);
    EXPECT_EQ(again.yarns[y].bodies, original.yarns[y].bodies);
    EXPECT_EQ(again.yarns[y].first_beam, original.yarns[y].first_beam);
    EXPECT_EQ(again.yarns[y].tie, original.yarns[y].tie);
  }
  EXPECT_NE(echo.find("    tie: 1e-06\n"), std::string::npos) << echo;
  EXPECT_NE(echo.find("    tie: auto  # 1e-10\n"), std::string::npos) << echo;

  // Only yarns: beams: [] reads back.
  const Scenario only = parse(kMaterials + "yarns:\n" + yarn_text() + kStages);
  EXPECT_NE(describe(only).find("beams: []\n"), std::string::npos);
  EXPECT_EQ(parse_scenario(describe(only), "echo.yaml").beams.size(), 9u);
}

TEST(ScenarioYarns, BuiltInCodeEqualsTheFileAndIsValidated) {
  const Scenario file = parse(kMaterials + "yarns:\n" + yarn_text() + kStages);
  Scenario made;
  made.path = "in code";
  made.materials.push_back({"pa", 4000.0, 0.3});
  YarnSpec yarn;
  yarn.name = "y";
  yarn.rovings = 3;
  yarn.fibres_per_roving = 3;
  yarn.fibre_radius = 0.05;
  yarn.length = 4.0;
  yarn.elements = 5;
  append_yarn(made, yarn);
  StageSpec stage;
  stage.name = "lay";
  made.stages.push_back(stage);
  EXPECT_NO_THROW(validate(made));
  ASSERT_EQ(made.beams.size(), file.beams.size());
  for (std::size_t b = 0; b < made.beams.size(); ++b) {
    EXPECT_EQ(made.beams[b].name, file.beams[b].name);
    EXPECT_EQ(made.beams[b].start, file.beams[b].start);
  }
  EXPECT_EQ(state_fingerprint_text(made, 1), state_fingerprint_text(file, 1));

  const auto error = [&](auto change) {
    Scenario changed = made;
    change(changed);
    try {
      validate(changed);
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error([](Scenario& s) { s.yarns[0].rovings = 0; }),
            "in code: yarns[0].rovings: expected an integer >= 1, got 0");
  EXPECT_EQ(error([](Scenario& s) { s.yarns[0].clearance = -1.0; }),
            "in code: yarns[0].clearance: expected a number >= 0 (mm), got -1");
  EXPECT_EQ(error([](Scenario& s) { s.beams[4].start.x() += 1e-9; }),
            "in code: beams[4]: expected fibre y.r2.f2 of yarn y as append_yarn makes it, got y.r2.f2");
  EXPECT_EQ(error([](Scenario& s) { s.yarns[0].fibre_radius = 0.06; }),
            "in code: beams[0]: expected fibre y.r1.f1 of yarn y as append_yarn makes it, got y.r1.f1");
  EXPECT_EQ(
      error([](Scenario& s) { s.bodies.pop_back(); }),
      "in code: yarns[0].first_body: expected the index of its first body in bodies, with room for 6, got 0");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[2].sections[0].node = 1; }),
            "in code: bodies[2]: expected body y.r2.start of yarn y as append_yarn makes it, got y.r2.start");
  EXPECT_EQ(error([](Scenario& s) { s.bodies[3].tie = 1e-6; }),  // the yarn's tie is auto
            "in code: bodies[3]: expected body y.r2.end of yarn y as append_yarn makes it, got y.r2.end");
  // What the layout cannot use (a clearance whose square overflows hung it), a fibre wider than long, and a
  // model larger than this machine builds: refused before the layout is made.
  EXPECT_EQ(error([](Scenario& s) { s.yarns[0].clearance = 1e200; }),
            "in code: yarns[0].clearance: expected a number >= 0 (mm), got 1e+200");
  EXPECT_EQ(error([](Scenario& s) { s.yarns[0].fibre_radius = 1e308; }),
            "in code: yarns[0].fibre_radius: expected a number > 0 (mm), got 1e+308");
  EXPECT_EQ(
      error([](Scenario& s) { s.yarns[0].fibre_radius = 5.0; }),
      "in code: yarns[0].fibre_radius: expected a number > 0 (mm), at most the fibre's length (4), got 5");
  EXPECT_EQ(error([](Scenario& s) { s.beams[8].elements = static_cast<int>(max_model_elements()); }),
            "in code: beams[8].elements: expected " + model_elements_expected("beams[].elements", 8 * 5) +
                ", got " + std::to_string(max_model_elements()));
  EXPECT_EQ(
      error([](Scenario& s) { s.yarns.push_back(s.yarns[0]); }),
      "in code: yarns[1].name: expected a name unique among yarns (already used by yarns[0].name), got y");
}

TEST(ScenarioYarns, BadInputOneLineNamingTheKey) {
  const std::string head = kMaterials + "yarns:\n";
  struct Case {
    std::string text, expected;
  };
  // Line numbers: 1-2 materials, 3 yarns, 4 name, 5 rovings, 6 fibres_per_roving, 7 fibre_radius, 8 length,
  // 9 elements, 10 material, 11 the first extra line.
  const std::vector<Case> cases = {
      {kMaterials + kStages,
       "y.yaml:1: beams: expected a list, non-empty without yarns, got nothing (missing key)"},
      {kMaterials + "beams: []\n" + kStages,
       "y.yaml:3: beams: expected a list, non-empty without yarns, got []"},
      {kMaterials + "yarns: []\n" + kStages,
       "y.yaml:3: yarns: expected a non-empty list (there are no beams), got []"},
      {head + yarn_text().replace(yarn_text().find("rovings: 3"), 10, "rovings: 0") + kStages,
       "y.yaml:5: yarns[0].rovings: expected an integer >= 1, got 0"},
      {head + yarn_text().replace(yarn_text().find("fibre_radius: 0.05"), 18, "fibre_radius: -1") + kStages,
       "y.yaml:7: yarns[0].fibre_radius: expected a number > 0 (mm), got -1"},
      {head + yarn_text().replace(yarn_text().find("    length: 4\n"), 14, "") + kStages,
       "y.yaml:4: yarns[0].length: expected a number > 0 (mm), got nothing (missing key)"},
      {head + yarn_text().replace(yarn_text().find("material: pa"), 12, "material: steel") + kStages,
       "y.yaml:10: yarns[0].material: expected the name of a material (pa), got steel"},
      {head + yarn_text("    clearance: -0.1\n") + kStages,
       "y.yaml:11: yarns[0].clearance: expected a number >= 0 (mm), got -0.1"},
      {head + yarn_text("    direction: [0, 0, 0]\n") + kStages,
       "y.yaml:11: yarns[0].direction: expected a list of 3 numbers with nonzero length, got [0, 0, 0]"},
      {head + yarn_text("    roving_packing: square\n") + kStages,
       "y.yaml:11: yarns[0].roving_packing: expected one of hexagonal | ring, got square"},
      {head + yarn_text("    yarn_packing: hexagonal\n") + kStages,
       "y.yaml:11: yarns[0].yarn_packing: expected exactly ring, got hexagonal"},
      {head + yarn_text("    bodies: 1\n") + kStages,
       "y.yaml:11: yarns[0].bodies: expected true or false, got 1"},
      {head + yarn_text("    twist: 30\n") + kStages,
       "y.yaml:11: yarns[0].twist: expected one of the keys name | rovings | fibres_per_roving | "
       "fibre_radius | "
       "length | elements | material | start | direction | clearance | roving_packing | yarn_packing | "
       "bending_factor | bodies | tie, got an unknown key"},
      {head + yarn_text("    tie: 0\n") + kStages,
       "y.yaml:11: yarns[0].tie: expected a number > 0 or auto, got 0"},
      {head + yarn_text().replace(yarn_text().find("fibres_per_roving: 3"), 20, "fibres_per_roving: 400") +
           kStages,
       "y.yaml:6: yarns[0].fibres_per_roving: expected an integer >= 1, with rovings x fibres_per_roving at "
       "most "
       "1000 (rovings: 3), got 400"},
      {head + yarn_text() + yarn_text() + kStages,
       "y.yaml:11: yarns[1].name: expected a name unique among yarns (already used at line 4), got y"},
      // A fibre's name taken by a beam of the file.
      {kMaterials +
           "beams:\n  - {name: y.r2.f1, material: pa, radius: 0.1, length: 4, elements: 2}\nyarns:\n" +
           yarn_text() + kStages,
       "y.yaml:6: yarns[0].name: expected a yarn name whose fibres NAME.rK.fJ are unique among beams "
       "(y.r2.f1 is "
       "already used at line 4), got y"},
  };
  for (const Case& c : cases) EXPECT_EQ(error_of(c.text), c.expected) << c.text;
}

// Values the yarn's layout or the model cannot use, found by the scenario fuzzer (tests/fuzz): each refused
// with its line and key, where before the layout hung (a clearance of 1e308), failed without a line (a fibre
// radius of 1e308: "roving_pattern: needs ... a finite spacing"), or the first contact detection ran for
// hours (a length of 6e6 mm: 4e9 test points).
TEST(ScenarioYarns, WhatTheLayoutCannotUseIsRefusedWithItsLine) {
  const std::string head = kMaterials + "yarns:\n";
  const auto with = [&](const std::string& from, const std::string& to, const std::string& tail = kStages) {
    std::string text = yarn_text();
    text.replace(text.find(from), from.size(), to);
    return head + text + tail;
  };
  EXPECT_EQ(
      error_of(with("fibre_radius: 0.05", "fibre_radius: 1e308")),
      "y.yaml:7: yarns[0].fibre_radius: expected a number > 0 (mm); every number 0 or of magnitude 1e-20 "
      "to 1e20, got 1e308");
  EXPECT_EQ(
      error_of(with("fibre_radius: 0.05", "fibre_radius: 1e-300")),
      "y.yaml:7: yarns[0].fibre_radius: expected a number > 0 (mm); every number 0 or of magnitude 1e-20 "
      "to 1e20, got 1e-300");
  EXPECT_EQ(
      error_of(head + yarn_text("    clearance: 1e308\n") + kStages),
      "y.yaml:11: yarns[0].clearance: expected a number >= 0 (mm); every number 0 or of magnitude 1e-20 "
      "to 1e20, got 1e308");
  EXPECT_EQ(error_of(head + yarn_text("    start: [0, 1e21, 0]\n") + kStages),
            "y.yaml:11: yarns[0].start[1]: expected a list of 3 numbers (mm); every number 0 or of magnitude "
            "1e-20 to 1e20, got 1e21");
  EXPECT_EQ(
      error_of(with("fibre_radius: 0.05", "fibre_radius: 5")),
      "y.yaml:7: yarns[0].fibre_radius: expected a number > 0 (mm), at most the fibre's length (4), got 5");
  // 9 fibres of as many elements as the machine's memory allows in all.
  const long long most = max_model_elements() / 9 + 1;
  EXPECT_EQ(error_of(with("elements: 5", "elements: " + std::to_string(most))),
            "y.yaml:9: yarns[0].elements: expected " + model_elements_expected("yarns[].elements", 0) +
                ", got " + std::to_string(most));
  // Test points every 0.1118 mm (auto: sqrt((3 R)^2 - (2 R)^2)) along 9 fibres 1e6 mm long.
  const std::string error =
      error_of(with("length: 4", "length: 1e6", kStages + "contact: {friction: 0.1}\n"));
  EXPECT_EQ(
      error.rfind("y.yaml:13: contact.test_point_spacing: expected a number > 0 or auto (mm), with at most "
                  "",
                  0),
      0u)
      << error;
  EXPECT_NE(error.find("(their lengths over the spacing, 0.1118 mm here: 8.05e+07 points), got auto"),
            std::string::npos)
      << error;
  // The paper's 3x25 yarn with a fibre radius of 1e308.
  std::ifstream in(std::string(NODUS_SOURCE_DIR) + "/examples/yarn_3x25.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("fibre_radius: 0.0112"), 20, "fibre_radius: 1e308");
  const std::string paper = [&] {
    try {
      parse_scenario(text, "yarn_3x25.yaml");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  }();
  EXPECT_EQ(paper.rfind("yarn_3x25.yaml:", 0), 0u) << paper;
  EXPECT_NE(paper.find(": yarns[0].fibre_radius: expected a number > 0 (mm); every number 0 or of magnitude"),
            std::string::npos)
      << paper;
}

}  // namespace
}  // namespace nodus::scenario
