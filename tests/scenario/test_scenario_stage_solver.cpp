// stages[].linear_solver: a stage's own sparse direct solver. Read in the main stages and the branches', it
// falls back to solver.linear_solver; cholmod is refused where the tangent is not symmetric, and any choice
// where solver.linear_solver is petsc (whose ranks share the rows). The reader names the line of the key;
// validate() the same for a scenario built in code. stages[].particles: a stage's own contact particles,
// falling back to contact.particles, refused without a contact section.

#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/validate.hpp"

namespace nodus::scenario {
namespace {

/// A scenario whose stage `second` and branch stage `third` take the lines `second` (line 12) and `third`
/// (line 19) as their linear_solver, with `tail` appended (contact and solver sections).
std::string text(const std::string& second, const std::string& third, const std::string& tail) {
  return R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: rod, material: nylon, radius: 0.1, length: 10, elements: 4}
conditions:
  - {name: hold, type: clamp, beam: rod, at: start}
stages:
  - name: first
    steps: 1
  - name: second
    steps: 1
)" + second +
         R"(
branches:
  - name: other
    from: first
    stages:
      - name: third
        steps: 1
)" + third +
         "\n" + tail;
}

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "s.yaml");
  } catch (const ScenarioError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return {};
}

TEST(StageLinearSolver, ReadInStagesAndBranchesAndFallingBackToTheSolverSection) {
  const Scenario s = parse_scenario(
      text("    linear_solver: klu", "        linear_solver: mumps", "solver: {linear_solver: umfpack}\n"),
      "s.yaml");
  EXPECT_EQ(s.stages[0].linear_solver, std::nullopt);
  EXPECT_EQ(stage_linear_solver(s.stages[0], s.solver), LinearSolverKind::umfpack);
  EXPECT_EQ(s.stages[1].linear_solver, LinearSolverKind::klu);
  EXPECT_EQ(stage_linear_solver(s.stages[1], s.solver), LinearSolverKind::klu);
  ASSERT_EQ(s.branches.size(), 1U);
  EXPECT_EQ(stage_linear_solver(s.branches[0].stages[0], s.solver), LinearSolverKind::mumps);
  // Each name of the file reads as the LinearSolverKind of that name.
  for (const auto& [name, kind] :
       {std::pair{"cholmod", LinearSolverKind::cholmod}, std::pair{"umfpack", LinearSolverKind::umfpack},
        std::pair{"mumps", LinearSolverKind::mumps}, std::pair{"klu", LinearSolverKind::klu}}) {
    const Scenario read = parse_scenario(
        text(std::string("    linear_solver: ") + name, "", "solver: {linear_solver: umfpack}\n"), "s.yaml");
    EXPECT_EQ(stage_linear_solver(read.stages[1], read.solver), kind) << name;
  }
  // "solver" is the default, written or not.
  const Scenario same =
      parse_scenario(text("    linear_solver: solver", "", "solver: {linear_solver: klu}\n"), "s.yaml");
  EXPECT_EQ(stage_linear_solver(same.stages[1], same.solver), LinearSolverKind::klu);
}

TEST(StageLinearSolver, CholmodIsRefusedWhereTheTangentIsNotSymmetric) {
  const std::string varying =
      "contact: {friction: 0.3, friction_tangent: varying}\nsolver: {linear_solver: umfpack}\n";
  const std::string expected =
      "expected solver, umfpack, mumps or klu (the tangent is not symmetric with contact.friction_tangent: "
      "varying or contact.normal_updates: linearized, and cholmod reads one triangle), got cholmod";
  EXPECT_EQ(error_of(text("    linear_solver: cholmod", "", varying)),
            "s.yaml:12: stages[1].linear_solver: " + expected);
  EXPECT_EQ(error_of(text("", "        linear_solver: cholmod", varying)),
            "s.yaml:19: branches[0].stages[0].linear_solver: " + expected);
  // With the frozen (symmetric) tangent it is accepted.
  const Scenario frozen = parse_scenario(
      text("    linear_solver: cholmod", "", "contact: {friction: 0.3}\nsolver: {linear_solver: umfpack}\n"),
      "s.yaml");
  EXPECT_EQ(stage_linear_solver(frozen.stages[1], frozen.solver), LinearSolverKind::cholmod);
  // validate(): the same message, without the line.
  Scenario built = parse_scenario(text("", "", varying), "s.yaml");
  built.stages[1].linear_solver = LinearSolverKind::cholmod;
  try {
    validate(built);
    ADD_FAILURE() << "validate() accepted cholmod with the varying tangent";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(std::string(error.what()), "s.yaml: stages[1].linear_solver: " + expected);
  }
}

TEST(StageLinearSolver, NoChoiceWithPetsc) {
  if (!parallel::available())
    GTEST_SKIP() << "no PETSc in this build: solver.linear_solver: petsc is refused";
  EXPECT_EQ(
      error_of(text("    linear_solver: mumps", "", "solver: {linear_solver: petsc}\n")),
      "s.yaml:12: stages[1].linear_solver: expected solver (with solver.linear_solver: petsc every stage "
      "runs on PETSc, which shares the rows among the MPI ranks), got mumps");
  EXPECT_NO_THROW(
      parse_scenario(text("    linear_solver: solver", "", "solver: {linear_solver: petsc}\n"), "s.yaml"));
}

TEST(StageLinearSolver, OnlyTheDeclaredChoices) {
  EXPECT_EQ(
      error_of(text("    linear_solver: petsc", "", "")),
      "s.yaml:12: stages[1].linear_solver: expected one of solver | cholmod | umfpack | mumps | klu, got "
      "petsc");
}

TEST(StageParticles, ReadInStagesAndBranchesAndFallingBackToTheContactSection) {
  const Scenario s = parse_scenario(
      text("    particles: facing", "        particles: centres", "contact: {particles: fixed}\n"), "s.yaml");
  EXPECT_EQ(s.stages[0].particles, StageParticles::contact);
  EXPECT_EQ(s.stages[1].particles, StageParticles::facing);
  ASSERT_EQ(s.branches.size(), 1U);
  EXPECT_EQ(s.branches[0].stages[0].particles, StageParticles::centres);
  // As the run takes them: {facing, centres}, the contact section's (fixed) where the stage has none.
  EXPECT_EQ(stage_particles(s.stages[0], s.contact), std::make_pair(false, false));
  EXPECT_EQ(stage_particles(s.stages[1], s.contact), std::make_pair(true, false));
  EXPECT_EQ(stage_particles(s.branches[0].stages[0], s.contact), std::make_pair(true, true));
  EXPECT_EQ(parse_scenario(text("    particles: fixed", "", "contact: {particles: centres}\n"), "s.yaml")
                .stages[1]
                .particles,
            StageParticles::fixed);
  const Scenario centres = parse_scenario(text("", "", "contact: {particles: centres}\n"), "s.yaml");
  EXPECT_EQ(stage_particles(centres.stages[1], centres.contact), std::make_pair(true, true));
  EXPECT_EQ(
      error_of(text("    particles: sideways", "", "contact: {}\n")),
      "s.yaml:12: stages[1].particles: expected one of contact | fixed | facing | centres, got sideways");
}

TEST(StageParticles, RefusedWithoutAContactSection) {
  const std::string expected = "expected no particles in a stage without a contact section, got facing";
  EXPECT_EQ(error_of(text("    particles: facing", "", "")), "s.yaml:12: stages[1].particles: " + expected);
  EXPECT_EQ(error_of(text("", "        particles: facing", "")),
            "s.yaml:19: branches[0].stages[0].particles: " + expected);
  // validate(): the same message, without the line.
  Scenario built = parse_scenario(text("", "", ""), "s.yaml");
  built.stages[1].particles = StageParticles::facing;
  try {
    validate(built);
    ADD_FAILURE() << "validate() accepted particles without a contact section";
  } catch (const ScenarioError& error) {
    EXPECT_EQ(std::string(error.what()), "s.yaml: stages[1].particles: " + expected);
  }
}

}  // namespace
}  // namespace nodus::scenario
