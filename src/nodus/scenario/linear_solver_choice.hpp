#pragma once
/// `solver.linear_solver: auto`, the default: the linear solver chosen from the tangent's symmetry, the
/// number of unknowns and the number of MPI ranks (docs/scenario.md, "solver").

namespace nodus::scenario {

struct Scenario;

/// Above this many unknowns an unsymmetric tangent goes to MUMPS's LU rather than KLU. Measured on this
/// project's tangents (docs/performance.md, "KLU or MUMPS"): KLU factorises the twisted 3x1 yarn's (5,463
/// unknowns) 1.5 times as fast as MUMPS, but a packed bundle's 1.3 times slower at 5,373 unknowns, 2.9 times
/// at 12,537 and 23 times at 48,357: its scalar LU without dense kernels falls behind the multifrontal one as
/// the fronts grow.
inline constexpr int kKluLargestUnknowns = 6000;

/// The unknowns of the scenario's beams: nine per node, two nodes per element and one more per beam.
int beam_unknowns(const Scenario& scenario);

/// Replaces solver.linear_solver = auto by the solver it stands for, and says why in
/// solver.linear_solver_reason: petsc on more than one MPI rank (in a build with PETSc, and where no stage
/// names a solver of its own); otherwise cholmod
/// where the tangent is symmetric, and klu or mumps (by kKluLargestUnknowns) where it is not (the varying
/// friction tangent, the linearized normals). A named solver is left as it is.
void choose_linear_solver(Scenario& scenario);

}  // namespace nodus::scenario
