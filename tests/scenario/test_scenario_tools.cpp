// Tests of the keys for tool beams and pivoted motions: conditions of type rigid, conditions[].pivot, and
// stages[].contact_off / contact_on, with the one-line message of each kind of bad input.

#include <string>

#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {
namespace {

/// A rod and a tool; conditions and stages are appended by each test.
const std::string kBeams = R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: nylon, radius: 0.1, length: 10, elements: 10}
  - {name: tool, material: nylon, radius: 0.5, length: 4, elements: 2, start: [5, -2, 1], direction: [0, 1, 0]}
)";

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "tool.yaml");
  } catch (const ScenarioError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return {};
}

TEST(ScenarioTools, RigidConditionPivotAndContactSwitches) {
  const Scenario s = parse_scenario(kBeams + R"(conditions:
  - {name: press, type: rigid, beam: tool, pivot: [5, 0, 1]}
  - {name: turn, type: motion, beam: rod, at: end, pivot: [10, 0, 1]}
stages:
  - name: in
    steps: 1
    motions:
      press: {translation: [0, 0, -0.5]}
      turn: {rotation: [0, 0, 90]}
  - {name: out, steps: 1, contact_off: [tool]}
  - {name: back, steps: 1, contact_on: [tool]}
contact: {}
)",
                                    "tool.yaml");
  ASSERT_EQ(s.conditions.size(), 2u);
  EXPECT_EQ(s.conditions[0].type, ConditionType::rigid);
  ASSERT_TRUE(s.conditions[0].pivot.has_value());
  EXPECT_EQ(*s.conditions[0].pivot, Vec3(5, 0, 1));
  EXPECT_EQ(s.conditions[1].type, ConditionType::motion);
  EXPECT_EQ(*s.conditions[1].pivot, Vec3(10, 0, 1));
  ASSERT_EQ(s.stages[0].motions.size(), 2u);  // a rigid condition takes motion targets
  EXPECT_EQ(s.stages[0].motions[0].condition, 0);
  EXPECT_EQ(s.stages[1].contact_off, std::vector<int>{1});
  EXPECT_TRUE(s.stages[1].contact_on.empty());
  EXPECT_EQ(s.stages[2].contact_on, std::vector<int>{1});
  // The settings echo names them again.
  const std::string echo = describe(s);
  EXPECT_NE(echo.find("type: rigid"), std::string::npos);
  EXPECT_NE(echo.find("pivot: [5, 0, 1]"), std::string::npos);
  EXPECT_NE(echo.find("contact_off: [tool]"), std::string::npos);
}

TEST(ScenarioTools, BadInputGivesOneLine) {
  const std::string stage = "stages:\n  - {name: s, steps: 1}\n";
  // A rigid condition moves the whole beam: no at, no dofs.
  std::string e =
      error_of(kBeams + "conditions:\n  - {name: t, type: rigid, beam: tool, at: start}\n" + stage);
  EXPECT_NE(e.find("tool.yaml:7: conditions[0].at: expected no at on a rigid condition"), std::string::npos)
      << e;
  e = error_of(kBeams + "conditions:\n  - {name: t, type: rigid, beam: tool, dofs: [x]}\n" + stage);
  EXPECT_NE(e.find("conditions[0].dofs: expected no dofs on a rigid condition"), std::string::npos) << e;
  // A pivot is for motions.
  e = error_of(kBeams + "conditions:\n  - {name: c, type: clamp, beam: rod, at: start, pivot: [0, 0, 0]}\n" +
               stage);
  EXPECT_NE(e.find("conditions[0].pivot: expected no pivot on a clamp condition"), std::string::npos) << e;
  // A rigid condition is never released.
  e = error_of(kBeams + "conditions:\n  - {name: t, type: rigid, beam: tool}\n" +
               "stages:\n  - {name: s, steps: 1, release: [t]}\n");
  EXPECT_NE(e.find("stages[0].release[0]: expected a condition that is not rigid"), std::string::npos) << e;
  // contact_off needs contact, a contact beam, and each beam once.
  e = error_of(kBeams + "stages:\n  - {name: s, steps: 1, contact_off: [tool]}\n");
  EXPECT_NE(e.find("stages[0].contact_off: expected no contact_off or contact_on without a contact section"),
            std::string::npos)
      << e;
  e = error_of(kBeams + "stages:\n  - {name: s, steps: 1, contact_off: [hammer]}\ncontact: {}\n");
  EXPECT_NE(e.find("stages[0].contact_off[0]: expected the name of a beam (rod | tool), got hammer"),
            std::string::npos)
      << e;
  e = error_of(kBeams + "stages:\n  - {name: s, steps: 1, contact_off: [tool]}\ncontact: {beams: [rod]}\n");
  EXPECT_NE(e.find("stages[0].contact_off[0]: expected a beam listed in contact.beams"), std::string::npos)
      << e;
  e = error_of(kBeams + "stages:\n  - {name: s, steps: 1, contact_off: [tool], contact_on: [tool]}\n" +
               "contact: {}\n");
  EXPECT_NE(e.find("stages[0].contact_off[0]: expected a beam that is not also in contact_on"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace nodus::scenario
