// One Newton iteration of the equilibrium problem of a cantilever (L = 20 mm, R = 0.1 mm, E = 4000 MPa,
// nu = 0.3; node 0 clamped in all nine unknowns, dead tip force) at a deformed state (the beam bent into an
// arc of pi/3): assembly of residual + tangent (EquilibriumProblem::evaluate), numerical factorisation and
// solve. The state is not updated, so every iteration does the same work. Split into
//   BM_NewtonAssembly        evaluate(r, true)
//   BM_NewtonFactorizeSolve  factorize(tangent) + solve(r)   (analyze once, outside the loop)
//   BM_NewtonIteration       all three
// for the `cholmod` (default) and `umfpack` linear solvers. See docs/performance.md.

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_beam.hpp"

using nodus::bench::kLength;
using nodus::bench::kRadius;
#include <Eigen/SparseCholesky>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/linear_solver.hpp"

namespace {

using nodus::beam::kNodeDofs;
using nodus::model::Model;
using nodus::solver::LinearSolverKind;

/// Model, conditions and problem in one place (the problem keeps references to the other two).
struct Setup {
  Model model;
  nodus::loading::Conditions conditions;
  std::unique_ptr<nodus::simulation::EquilibriumProblem> problem;

  explicit Setup(int elements) {
    model.add_beam(nodus::bench::benchmark_beam(elements));
    const int tip = model.num_nodes() - 1;
    const int clamp =
        conditions.add_motion("clamp", 0, {true, true, true, true, true, true, true, true, true});
    // A quarter of the cantilever's Euler load pi^2 EI / (4 L^2) = 1.9e-3 N; it only sets f_ext.
    const int load =
        conditions.add_load("tip", tip, Eigen::Vector3d(0.0, -5e-4, 0.0), Eigen::Vector3d::UnitZ(), 0.0);
    conditions.activate(clamp, 0.0, model.reference());
    conditions.activate(load, 0.0, model.reference());
    problem = std::make_unique<nodus::simulation::EquilibriumProblem>(model, conditions,
                                                                      nodus::simulation::Tolerances{});
    problem->set_time(0.0);

    // Deformed state: arc of pi/3 in the x-y plane, directors normal to it (node 0 stays at its clamp).
    const nodus::beam::Beam& beam = model.beam(0);
    const double rho = kLength / (std::numbers::pi / 3);
    Eigen::VectorXd x = model.reference();
    for (int i = 0; i < beam.num_nodes(); ++i) {
      const double theta = beam.abscissa(i) / rho;
      auto q = x.segment<kNodeDofs>(kNodeDofs * beam.node(i));
      q.segment<3>(0) = rho * Eigen::Vector3d(std::sin(theta), 1.0 - std::cos(theta), 0.0);
      q.segment<3>(3) = Eigen::Vector3d(-std::sin(theta), std::cos(theta), 0.0);
    }
    Eigen::VectorXd u(problem->size());
    for (int i = 0, k = 0; i < model.num_dofs(); ++i)
      if (i >= kNodeDofs) u[k++] = x[i];
    problem->set_unknowns(u);
  }
};

void set_counters(benchmark::State& state, const Setup& s) {
  state.SetItemsProcessed(state.iterations() * s.model.num_elements());
  state.counters["elements"] = s.model.num_elements();
  state.counters["dofs"] = s.model.num_dofs();
  state.counters["free_dofs"] = s.problem->size();
}

void BM_NewtonAssembly(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  Eigen::VectorXd r;
  for (auto _ : state) {
    s.problem->evaluate(r, true);
    benchmark::DoNotOptimize(r.data());
    benchmark::DoNotOptimize(s.problem->tangent().valuePtr());
    benchmark::ClobberMemory();
  }
  set_counters(state, s);
}

/// Once, untimed: negative pivots of the tangent (0: CHOLMOD's LL^T path is taken) and the solve's accuracy.
void check(benchmark::State& state, const Setup& s, const Eigen::VectorXd& r, const Eigen::VectorXd& du) {
  const auto& k = s.problem->tangent();
  Eigen::SimplicialLDLT<nodus::solver::SparseMatrix> ldlt(k);
  state.counters["neg_pivots"] =
      ldlt.info() == Eigen::Success ? static_cast<double>((ldlt.vectorD().array() < 0).count()) : -1.0;
  // |K du - r| / |r| grows with the condition number when r excites the soft modes; the normwise backward
  // error |K du - r| / (|K| |du| + |r|) is the solver's own accuracy.
  const double misfit = (k * du - r).norm();
  state.counters["rel_residual"] = misfit / r.norm();
  state.counters["backward_error"] = misfit / (k.norm() * du.norm() + r.norm());
}

void BM_NewtonFactorizeSolve(benchmark::State& state, LinearSolverKind kind) {
  Setup s(static_cast<int>(state.range(0)));
  auto linear = nodus::solver::make_linear_solver(kind);
  Eigen::VectorXd r, du;
  s.problem->evaluate(r, true);
  linear->analyze(s.problem->tangent());
  bool ok = true;
  for (auto _ : state) {
    ok = linear->factorize(s.problem->tangent()) && ok;
    du = linear->solve(r);
    benchmark::DoNotOptimize(du.data());
    benchmark::ClobberMemory();
  }
  if (!ok) {
    state.SkipWithError("factorize reported a singular matrix");
    return;
  }
  set_counters(state, s);
  check(state, s, r, du);
  state.SetLabel(linear->name());
}

void BM_NewtonIteration(benchmark::State& state, LinearSolverKind kind) {
  Setup s(static_cast<int>(state.range(0)));
  auto linear = nodus::solver::make_linear_solver(kind);
  Eigen::VectorXd r, du;
  s.problem->evaluate(r, true);
  linear->analyze(s.problem->tangent());
  bool ok = true;
  for (auto _ : state) {
    s.problem->evaluate(r, true);
    ok = linear->factorize(s.problem->tangent()) && ok;
    du = linear->solve(r);
    benchmark::DoNotOptimize(du.data());
    benchmark::ClobberMemory();
  }
  if (!ok) {
    state.SkipWithError("factorize reported a singular matrix");
    return;
  }
  set_counters(state, s);
  check(state, s, r, du);
  state.SetLabel(linear->name());
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_NewtonAssembly)->Apply(sizes);
BENCHMARK_CAPTURE(BM_NewtonFactorizeSolve, cholmod, LinearSolverKind::cholmod)->Apply(sizes);
BENCHMARK_CAPTURE(BM_NewtonFactorizeSolve, umfpack, LinearSolverKind::umfpack)->Apply(sizes);
BENCHMARK_CAPTURE(BM_NewtonIteration, cholmod, LinearSolverKind::cholmod)->Apply(sizes);
BENCHMARK_CAPTURE(BM_NewtonIteration, umfpack, LinearSolverKind::umfpack)->Apply(sizes);
