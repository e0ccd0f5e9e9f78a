// Sparse direct solvers on the assembled tangent of a single straight beam (L = 20 mm, R = 0.1 mm,
// E = 4000 MPa, nu = 0.3), two matrix cases:
//   pd         - bent into an arc (pi/3) and stretched by 1e-3, first node clamped: positive definite;
//   indefinite - straight column with every centre compressed by a uniform axial strain -1e-3, both end
//                nodes clamped. Clamped-clamped Euler strain is pi^2 R^2 / L^2 = 2.5e-4, so this is four
//                times past the first buckling load: the tangent has negative eigenvalues.
// The symbolic analysis is timed once (counter analyze_ms); each iteration is factorize + solve. The solution
// is checked after the timed loop: counter rel_residual = |A x - b| / |b| with b = A x_true, x_true uniform
// random (fixed seed). Counter neg_pivots is the number of negative pivots of an LDL^T factorisation (Eigen's
// own SimplicialLDLT, Sylvester inertia): 0 means CHOLMOD's supernodal LL^T path succeeds, > 0 means the
// `cholmod` solver falls back to simplicial LDL^T; the mumps solvers pivot. See docs/performance.md.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_beam.hpp"

using nodus::bench::kLength;
using nodus::bench::kRadius;
#include <Eigen/SparseCholesky>

#include "nodus/model/model.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace {

using nodus::beam::kNodeDofs;
using nodus::model::Model;
using nodus::solver::LinearSolverKind;
using nodus::solver::SparseMatrix;

enum class Case { pd, indefinite };

Model make_model(int elements) {
  Model model;
  model.add_beam(nodus::bench::benchmark_beam(elements));
  return model;
}

Eigen::VectorXd arc_state(const Model& model, double angle, double stretch) {
  const nodus::beam::Beam& beam = model.beam(0);
  const double rho = kLength / angle;
  Eigen::VectorXd x = model.reference();
  for (int i = 0; i < beam.num_nodes(); ++i) {
    const double theta = beam.abscissa(i) / rho;
    auto q = x.segment<kNodeDofs>(kNodeDofs * beam.node(i));
    q.segment<3>(0) = (1.0 + stretch) * rho * Eigen::Vector3d(std::sin(theta), 1.0 - std::cos(theta), 0.0);
    q.segment<3>(3) = Eigen::Vector3d(-std::sin(theta), std::cos(theta), 0.0);
    q.segment<3>(6) = Eigen::Vector3d::UnitZ();
  }
  return x;
}

Eigen::VectorXd compressed_state(const Model& model, double strain) {
  Eigen::VectorXd x = model.reference();
  for (int n = 0; n < model.num_nodes(); ++n) x[kNodeDofs * n] *= 1.0 + strain;  // start is the origin
  return x;
}

struct System {
  SparseMatrix a;
  Eigen::VectorXd x_true, b;
  int dofs = 0;
  int neg_pivots = -1;
};

/// The tangent of each (case, size), built once per process and shared by all solvers.
const System& system_for(Case c, int elements) {
  static std::map<std::pair<int, int>, System> cache;
  const auto key = std::make_pair(static_cast<int>(c), elements);
  if (auto it = cache.find(key); it != cache.end()) return it->second;

  const Model model = make_model(elements);
  const int last = model.num_nodes() - 1;
  std::vector<int> free_index(static_cast<std::size_t>(model.num_dofs()), -1);
  int next = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    const bool clamped = n == 0 || (c == Case::indefinite && n == last);
    for (int k = 0; k < kNodeDofs; ++k)
      if (!clamped) free_index[static_cast<std::size_t>(kNodeDofs * n + k)] = next++;
  }
  nodus::solver::SparseAssembler assembler(kNodeDofs, std::move(free_index), model.element_nodes());
  const Eigen::VectorXd x =
      c == Case::pd ? arc_state(model, std::numbers::pi / 3, 1e-3) : compressed_state(model, -1e-3);
  Eigen::VectorXd f;
  model.internal_force(x, f, &assembler);

  System s;
  s.a = assembler.matrix();
  s.dofs = model.num_dofs();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  s.x_true.resize(s.a.rows());
  for (Eigen::Index i = 0; i < s.x_true.size(); ++i) s.x_true[i] = u(rng);
  s.b = s.a * s.x_true;

  Eigen::SimplicialLDLT<SparseMatrix> ldlt(s.a);
  if (ldlt.info() == Eigen::Success) s.neg_pivots = static_cast<int>((ldlt.vectorD().array() < 0).count());
  const double asym = SparseMatrix(s.a - SparseMatrix(s.a.transpose())).norm() / s.a.norm();
  std::fprintf(stderr,
               "# matrix %s, %d elements: n = %ld, nnz = %ld, negative pivots = %d, |A-A^T|/|A| = %.1e\n",
               c == Case::pd ? "pd" : "indefinite", elements, static_cast<long>(s.a.rows()),
               static_cast<long>(s.a.nonZeros()), s.neg_pivots, asym);
  return cache.emplace(key, std::move(s)).first->second;
}

void BM_FactorizeSolve(benchmark::State& state, Case c, LinearSolverKind kind) {
  const System& s = system_for(c, static_cast<int>(state.range(0)));
  auto solver = nodus::solver::make_linear_solver(kind);
  const auto t0 = std::chrono::steady_clock::now();
  solver->analyze(s.a);
  const auto t1 = std::chrono::steady_clock::now();

  Eigen::VectorXd x;
  bool ok = true;
  for (auto _ : state) {
    ok = solver->factorize(s.a) && ok;
    x = solver->solve(s.b);
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  if (!ok) {
    state.SkipWithError("factorize reported a singular matrix");
    return;
  }
  const double residual = (s.a * x - s.b).norm() / s.b.norm();
  state.counters["analyze_ms"] = std::chrono::duration<double, std::milli>(t1 - t0).count();
  state.counters["rel_residual"] = residual;
  state.counters["backward_error"] = (s.a * x - s.b).norm() / (s.a.norm() * x.norm() + s.b.norm());
  state.counters["rel_error"] = (x - s.x_true).norm() / s.x_true.norm();
  state.counters["residual_ok"] = residual < 1e-8 ? 1 : 0;
  state.counters["neg_pivots"] = s.neg_pivots;
  state.counters["dofs"] = s.dofs;
  state.counters["free_dofs"] = static_cast<double>(s.a.rows());
  state.counters["nnz"] = static_cast<double>(s.a.nonZeros());
  state.SetLabel(solver->name());
  if (residual >= 1e-8) std::fprintf(stderr, "# WARNING: residual %.2e >= 1e-8\n", residual);
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_cholmod, Case::pd, LinearSolverKind::cholmod)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_cholmod_ldlt, Case::pd, LinearSolverKind::cholmod_ldlt)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_umfpack, Case::pd, LinearSolverKind::umfpack)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_cholmod, Case::indefinite, LinearSolverKind::cholmod)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_cholmod_ldlt, Case::indefinite,
                  LinearSolverKind::cholmod_ldlt)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_umfpack, Case::indefinite, LinearSolverKind::umfpack)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_mumps_ldlt, Case::pd, LinearSolverKind::mumps_ldlt)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_mumps_lu, Case::pd, LinearSolverKind::mumps_lu)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_mumps_ldlt, Case::indefinite, LinearSolverKind::mumps_ldlt)
    ->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_mumps_lu, Case::indefinite, LinearSolverKind::mumps_lu)
    ->Apply(sizes);
// KLU pivots in the first factorisation after the analysis and keeps those pivots in the next ones
// (klu_refactor): the iterations measure the refactorisation.
BENCHMARK_CAPTURE(BM_FactorizeSolve, pd_klu, Case::pd, LinearSolverKind::klu)->Apply(sizes);
BENCHMARK_CAPTURE(BM_FactorizeSolve, indefinite_klu, Case::indefinite, LinearSolverKind::klu)->Apply(sizes);
