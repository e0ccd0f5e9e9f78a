// The linear solve of one Newton iteration of the twisted bundle with contact (bundle_problem.hpp) by a
// Krylov method and algebraic multigrid, against the direct factorisation it would replace. A timed run, not
// a test, on one process (PETSc's sequential matrices):
//
//   bench_amg FIBRES [--no-near-null-space] [--beams-preconditioner] [PETSc options: -ksp_type cg ...]
//
// The tangent's free unknowns are the nine of every node but the fibres' held ends, node after node, so the
// matrix has blocks of 9 (MatSetBlockSize). Unless told not to, the matrix carries the beam node's near-null
// space, the six rigid-body modes written on the nine unknowns of a node: a translation moves the centre
// r; an infinitesimal rotation w x . acts on r - c (c the centroid), g1 and g2 alike. Their span is made
// orthonormal as PETSc asks. The right-hand side is the tangent times a vector x_true uniform in [-1, 1]
// (seed 1), the Krylov method runs to a relative residual of 1e-8 (or the options' -ksp_rtol).
//
// Prints the unknowns and the tangent's entries; for the direct path (nodus's serial mumps LDL^T, as a run of
// the bundle takes it) the factorisation and solve time; for the Krylov path the preconditioner's setup time,
// the iterations, the solve time, |K x - b| / |b| and |x - x_true| / |x_true|; then the time of a second
// solve after the values change on the same pattern (the next Newton iteration's). Results:
// docs/performance.md.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <petscksp.h>

#include "bundle_problem.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/parallel/petsc_check.hpp"
#include "nodus/solver/linear_solver.hpp"

namespace {

constexpr auto check = nodus::parallel::check_petsc;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The six rigid-body modes of the free nodes of `s` (columns), orthonormal.
Eigen::MatrixXd near_null_space(const nodus::bench::Setup& s) {
  const nodus::model::Model& model = s.bundle.model;
  const std::vector<bool> prescribed = s.conditions.prescribed(model.num_dofs());
  std::vector<int> free_nodes;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const Eigen::Index f = model.node_dof(n);
    int held = 0;
    for (int k = 0; k < 9; ++k) held += prescribed[static_cast<std::size_t>(f + k)] ? 1 : 0;
    if (held != 0 && held != 9) throw std::logic_error("a node partly held: the blocks are not of 9");
    if (held == 0) free_nodes.push_back(n);
  }
  const Eigen::Index size = 9 * static_cast<Eigen::Index>(free_nodes.size());
  if (size != s.problem->size()) throw std::logic_error("the free unknowns are not the free nodes' nine");
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int n : free_nodes) centroid += s.bundle.x.segment<3>(model.node_dof(n));
  centroid /= static_cast<double>(free_nodes.size());
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(size, 6);
  for (std::size_t k = 0; k < free_nodes.size(); ++k) {
    const Eigen::Index f = model.node_dof(free_nodes[k]);
    const Eigen::Index row = 9 * static_cast<Eigen::Index>(k);
    const Eigen::Vector3d r = s.bundle.x.segment<3>(f) - centroid;
    const Eigen::Vector3d g1 = s.bundle.x.segment<3>(f + 3), g2 = s.bundle.x.segment<3>(f + 6);
    for (int a = 0; a < 3; ++a) {
      modes(row + a, a) = 1.0;
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(a);
      modes.block<3, 1>(row, 3 + a) = w.cross(r);
      modes.block<3, 1>(row + 3, 3 + a) = w.cross(g1);
      modes.block<3, 1>(row + 6, 3 + a) = w.cross(g2);
    }
  }
  return Eigen::HouseholderQR<Eigen::MatrixXd>(modes).householderQ() * Eigen::MatrixXd::Identity(size, 6);
}

}  // namespace

int main(int argc, char** argv) {
  const nodus::parallel::SplitArguments split = nodus::parallel::split_petsc_options(argc, argv);
  nodus::parallel::initialize(split.petsc);
  const std::vector<std::string>& args = split.rest;
  if (args.size() < 2 || !nodus::parallel::available()) {
    std::fprintf(stderr,
                 "usage: bench_amg FIBRES [--no-near-null-space] [PETSc options] (a build with PETSc)\n");
    nodus::parallel::finalize();
    return 2;
  }
  const int fibres = std::atoi(args[1].c_str());
  bool with_modes = true, beams_only = false;
  for (const std::string& a : args) {
    with_modes = with_modes && a != "--no-near-null-space";
    beams_only = beams_only || a == "--beams-preconditioner";
  }

  nodus::bench::Setup s(fibres);
  Eigen::VectorXd r;
  s.problem->evaluate(r, true);
  const nodus::solver::SparseMatrix& k = s.problem->tangent();
  const Eigen::Index n = k.rows();
  std::mt19937 random(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x_true(n);
  for (Eigen::Index i = 0; i < n; ++i) x_true[i] = uniform(random);
  const Eigen::VectorXd b = k * x_true;
  std::printf("fibres %d, unknowns %ld, tangent entries %ld, contact elements %zu\n", fibres,
              static_cast<long>(n), static_cast<long>(k.nonZeros()), s.geometry.elements.size());

  {  // The direct path.
    auto direct = nodus::solver::make_linear_solver(nodus::solver::LinearSolverKind::mumps_ldlt);
    auto start = std::chrono::steady_clock::now();
    direct->analyze(k);
    const double analysis = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const bool ok = direct->factorize(k);
    const Eigen::VectorXd x = direct->solve(b);
    const double factor_solve = seconds_since(start);
    std::printf(
        "direct (mumps LDL^T): analysis %.3f s, factorisation and solve %.3f s, |x - x_true|/|x_true| "
        "%.1e%s\n",
        analysis, factor_solve, (x - x_true).norm() / x_true.norm(), ok ? "" : " (failed)");
  }

  // The Krylov path: the tangent as a PETSc matrix with blocks of 9.
  const Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt> rows = k;
  Mat a = nullptr;
  check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, static_cast<PetscInt>(n), static_cast<PetscInt>(n),
                                  const_cast<PetscInt*>(rows.outerIndexPtr()),
                                  const_cast<PetscInt*>(rows.innerIndexPtr()),
                                  const_cast<double*>(rows.valuePtr()), &a),
        "MatCreateSeqAIJWithArrays");
  check(MatSetBlockSize(a, 9), "MatSetBlockSize");
  // With --beams-preconditioner the preconditioner is built from the beams' tangent alone (the same problem
  // without its contact elements: one independent block per fibre), the Krylov method runs on the whole.
  Mat p = a;
  nodus::solver::SparseMatrix beam_tangent;
  Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt> beam_rows;
  if (beams_only) {
    nodus::simulation::EquilibriumProblem beams(s.bundle.model, s.conditions,
                                                nodus::simulation::Tolerances{});
    beams.set_time(0.0);
    beams.set_unknowns(s.problem->unknowns());
    Eigen::VectorXd unused;
    beams.evaluate(unused, true);
    beam_rows = beams.tangent();
    check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, static_cast<PetscInt>(n), static_cast<PetscInt>(n),
                                    beam_rows.outerIndexPtr(), beam_rows.innerIndexPtr(),
                                    beam_rows.valuePtr(), &p),
          "MatCreateSeqAIJWithArrays");
    check(MatSetBlockSize(p, 9), "MatSetBlockSize");
    std::printf("preconditioner from the beams' tangent alone: %ld entries\n",
                static_cast<long>(beam_rows.nonZeros()));
  }
  std::vector<Vec> vectors;
  MatNullSpace space = nullptr;
  if (with_modes) {
    const Eigen::MatrixXd modes = near_null_space(s);
    std::printf("near-null space: 6 modes, |K modes| / |K| |modes| = %.1e (the contact and the held ends)\n",
                (k * modes).norm() / (k.norm() * modes.norm()));
    for (int m = 0; m < 6; ++m) {
      Vec v = nullptr;
      check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(n), &v), "VecCreateSeq");
      PetscScalar* values = nullptr;
      check(VecGetArray(v, &values), "VecGetArray");
      for (Eigen::Index i = 0; i < n; ++i) values[i] = modes(i, m);
      check(VecRestoreArray(v, &values), "VecRestoreArray");
      vectors.push_back(v);
    }
    check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, 6, vectors.data(), &space), "MatNullSpaceCreate");
    check(MatSetNearNullSpace(p, space), "MatSetNearNullSpace");
  }
  Vec pb = nullptr, px = nullptr;
  check(MatCreateVecs(a, &px, &pb), "MatCreateVecs");
  {
    PetscScalar* values = nullptr;
    check(VecGetArray(pb, &values), "VecGetArray");
    for (Eigen::Index i = 0; i < n; ++i) values[i] = b[i];
    check(VecRestoreArray(pb, &values), "VecRestoreArray");
  }
  KSP ksp = nullptr;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, a, p), "KSPSetOperators");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  auto start = std::chrono::steady_clock::now();
  check(KSPSetUp(ksp), "KSPSetUp");
  const double setup = seconds_since(start);
  start = std::chrono::steady_clock::now();
  check(KSPSolve(ksp, pb, px), "KSPSolve");
  const double solve = seconds_since(start);
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(ksp, &iterations), "KSPGetIterationNumber");
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  Eigen::VectorXd x(n);
  {
    const PetscScalar* values = nullptr;
    check(VecGetArrayRead(px, &values), "VecGetArrayRead");
    for (Eigen::Index i = 0; i < n; ++i) x[i] = values[i];
    check(VecRestoreArrayRead(px, &values), "VecRestoreArrayRead");
  }
  KSPType type = nullptr;
  PCType pc_type = nullptr;
  check(KSPGetType(ksp, &type), "KSPGetType");
  check(PCGetType(pc, &pc_type), "PCGetType");
  std::printf(
      "krylov (%s, %s, %s): setup %.3f s, %d iterations (%s), solve %.3f s, |K x - b|/|b| %.1e, "
      "|x - x_true|/|x_true| %.1e\n",
      type, pc_type, with_modes ? "near-null space" : "no near-null space", setup,
      static_cast<int>(iterations), KSPConvergedReasons[reason], solve, (k * x - b).norm() / b.norm(),
      (x - x_true).norm() / x_true.norm());
  // A next Newton iteration: new values on the same pattern (here the same tangent scaled), the
  // preconditioner set up again inside KSPSolve; with -pc_gamg_reuse_interpolation the hierarchy's
  // prolongators are kept.
  check(MatScale(a, 1.001), "MatScale");
  check(VecScale(pb, 1.001), "VecScale");
  if (beams_only) check(MatScale(p, 1.001), "MatScale");
  check(KSPSetOperators(ksp, a, p), "KSPSetOperators");
  start = std::chrono::steady_clock::now();
  check(KSPSolve(ksp, pb, px), "KSPSolve");
  const double again = seconds_since(start);
  check(KSPGetIterationNumber(ksp, &iterations), "KSPGetIterationNumber");
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  std::printf("krylov, new values on the same pattern: setup and solve %.3f s, %d iterations (%s)\n", again,
              static_cast<int>(iterations), KSPConvergedReasons[reason]);
  KSPDestroy(&ksp);
  VecDestroy(&px);
  VecDestroy(&pb);
  MatNullSpaceDestroy(&space);
  for (Vec& v : vectors) VecDestroy(&v);
  if (p != a) MatDestroy(&p);
  MatDestroy(&a);
  nodus::parallel::finalize();
  return 0;
}
