// solver.linear_solver: auto, the default: the solver it resolves to for a symmetric and an unsymmetric
// tangent, small and large, the reason the echo gives, a named solver kept, and the checkpoints of scenarios
// that relied on the old default (cholmod) still valid.

#include <string>

#include <gtest/gtest.h>

#include "nodus/scenario/fingerprint.hpp"
#include "nodus/scenario/linear_solver_choice.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {
namespace {

/// One beam of `elements` elements, clamped, with a contact section `contact` and a solver section `solver`.
std::string text(int elements, const std::string& contact, const std::string& solver) {
  return "materials:\n  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}\nbeams:\n"
         "  - {name: rod, material: nylon, radius: 0.1, length: 10, elements: " +
         std::to_string(elements) +
         "}\nconditions:\n  - {name: hold, type: clamp, beam: rod, at: start}\nstages:\n"
         "  - {name: hold, steps: 1}\n" +
         contact + solver;
}

TEST(LinearSolverChoice, SymmetricTangentGoesToCholmod) {
  const Scenario s = parse_scenario(text(10, "contact: {friction: 0.3}\n", ""), "s.yaml");
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::cholmod);
  EXPECT_EQ(s.solver.linear_solver_reason, "auto: the tangent is symmetric");
  EXPECT_NE(describe(s).find("  linear_solver: cholmod  # auto: the tangent is symmetric\n"),
            std::string::npos)
      << describe(s);
}

TEST(LinearSolverChoice, UnsymmetricTangentGoesToKluThenMumpsBySize) {
  // 9 (2 n + 1) unknowns: 332 elements give 5,985 (<= 6,000), 333 give 6,003.
  const std::string varying = "contact: {friction: 0.3, friction_tangent: varying}\n";
  const Scenario small = parse_scenario(text(332, varying, ""), "s.yaml");
  EXPECT_EQ(beam_unknowns(small), 5985);
  EXPECT_EQ(small.solver.linear_solver, LinearSolverKind::klu);
  EXPECT_EQ(
      small.solver.linear_solver_reason,
      "auto: the tangent is not symmetric (contact.friction_tangent: varying), 5985 beam unknowns (klu up "
      "to 6000 unknowns)");
  const Scenario large = parse_scenario(text(333, varying, ""), "s.yaml");
  EXPECT_EQ(beam_unknowns(large), 6003);
  EXPECT_EQ(large.solver.linear_solver, LinearSolverKind::mumps);
  const Scenario linearized =
      parse_scenario(text(10, "contact: {normal_updates: linearized}\n", ""), "s.yaml");
  EXPECT_EQ(linearized.solver.linear_solver, LinearSolverKind::klu);
  EXPECT_NE(linearized.solver.linear_solver_reason.find("contact.normal_updates: linearized"),
            std::string::npos);
}

TEST(LinearSolverChoice, NamedSolverIsKept) {
  for (const auto& [name, kind] :
       {std::pair{"cholmod", LinearSolverKind::cholmod}, std::pair{"umfpack", LinearSolverKind::umfpack},
        std::pair{"mumps", LinearSolverKind::mumps}}) {
    const Scenario s =
        parse_scenario(text(10, "", std::string("solver: {linear_solver: ") + name + "}\n"), "s.yaml");
    EXPECT_EQ(s.solver.linear_solver, kind) << name;
    EXPECT_TRUE(s.solver.linear_solver_reason.empty()) << name;
  }
  const Scenario named = parse_scenario(text(10, "", "solver: {linear_solver: auto}\n"), "s.yaml");
  EXPECT_EQ(named.solver.linear_solver, LinearSolverKind::cholmod);
}

TEST(LinearSolverChoice, ScenarioBuiltInCodeIsResolvedByTheCall) {
  Scenario s = parse_scenario(text(10, "", ""), "s.yaml");
  s.solver.linear_solver = LinearSolverKind::automatic;
  s.solver.linear_solver_reason.clear();
  s.contact.friction_tangent = FrictionTangent::varying;
  choose_linear_solver(s);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::klu);
}

TEST(LinearSolverChoice, OldDefaultCheckpointsStayValid) {
  // A checkpoint written when the default was cholmod carries the fingerprint of the scenario with cholmod
  // named; auto resolves to it where the tangent is symmetric, and the fingerprints agree.
  const Scenario chosen = parse_scenario(text(10, "contact: {friction: 0.3}\n", ""), "s.yaml");
  const Scenario named =
      parse_scenario(text(10, "contact: {friction: 0.3}\n", "solver: {linear_solver: cholmod}\n"), "s.yaml");
  EXPECT_EQ(state_fingerprint_text(chosen, 1), state_fingerprint_text(named, 1));
  // The line the old default wrote, as checkpoints hold it; the reason the echo gives is not part of it.
  const std::string text = state_fingerprint_text(chosen, 1);
  EXPECT_NE(text.find("\nsolver.linear_solver = cholmod\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("auto"), std::string::npos) << text;
}

}  // namespace
}  // namespace nodus::scenario
