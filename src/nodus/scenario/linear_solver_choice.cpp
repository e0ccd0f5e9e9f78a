#include "nodus/scenario/linear_solver_choice.hpp"

#include <fmt/format.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

int beam_unknowns(const Scenario& scenario) {
  int unknowns = 0;
  for (const BeamSpec& beam : scenario.beams) unknowns += 9 * (2 * beam.elements + 1);
  return unknowns;
}

void choose_linear_solver(Scenario& scenario) {
  SolverSettings& solver = scenario.solver;
  if (solver.linear_solver != LinearSolverKind::automatic) return;
  // Stages with solvers of their own run in one process (PETSc's ranks share the rows of one solver): with
  // any, the serial choice below, and the run says once that every rank repeats it.
  bool stage_solvers = false;
  for (const StageSpec& stage : scenario.stages) stage_solvers = stage_solvers || stage.linear_solver;
  for (const BranchSpec& branch : scenario.branches)
    for (const StageSpec& stage : branch.stages) stage_solvers = stage_solvers || stage.linear_solver;
  if (parallel::size() > 1 && parallel::available() && !stage_solvers) {
    solver.linear_solver = LinearSolverKind::petsc;
    solver.linear_solver_reason = fmt::format("auto: {} MPI ranks share the factorisation", parallel::size());
    return;
  }
  const ContactSettings& contact = scenario.contact;
  const char* unsymmetric =
      contact.friction_tangent == FrictionTangent::varying  ? "contact.friction_tangent: varying"
      : contact.normal_updates == NormalUpdates::linearized ? "contact.normal_updates: linearized"
                                                            : nullptr;
  if (!unsymmetric) {
    solver.linear_solver = LinearSolverKind::cholmod;
    solver.linear_solver_reason = "auto: the tangent is symmetric";
    return;
  }
  const int unknowns = beam_unknowns(scenario);
  const bool small = unknowns <= kKluLargestUnknowns;
  solver.linear_solver = small ? LinearSolverKind::klu : LinearSolverKind::mumps;
  solver.linear_solver_reason =
      fmt::format("auto: the tangent is not symmetric ({}), {} beam unknowns ({} {} {})", unsymmetric,
                  unknowns, small ? "klu up to" : "mumps above", kKluLargestUnknowns, "unknowns");
}

}  // namespace nodus::scenario
