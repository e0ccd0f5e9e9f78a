// One Newton iteration of a twisted bundle of fibres in contact (bench/twisted_bundle.hpp with the lattice
// spacing 1.99 R: neighbours overlap by 0.01 R = p_max / 2 with the default laws; both ends of every fibre
// clamped in the twisted state), split as the global algorithm spends it [Durville 2012, Sect. 6]:
//   BM_ContactDetection       detect(): proximity zones, intermediate geometries, contact elements (once per
//                             loop-2 iteration, i.e. once per few Newton iterations)
//   BM_BundleDetection        detect() alone on 75, 300 and 1,000 fibres, without the equilibrium problem
//   BM_ContactAssembly        EquilibriumProblem::evaluate(r, true): beams and contact elements, residual and
//                             tangent
//   BM_ContactFactorizeSolve  factorisation and solve by each sparse direct solver (analysis once, outside
//                             the loop)
//   BM_ContactNewtonIteration one whole Newton iteration with `cholmod` (the bundles' solver): evaluate,
//                             factorise, solve, each part timed (counters assembly_ms, factorize_ms,
//                             solve_ms), the ratio of the iteration to its factorisation (iteration_ratio),
//                             and the Cholesky factor's non-zeros and flops by CHOLMOD's analysis (METIS
//                             ordering)
//   BM_BundleFactorAnalysis   the Cholesky factor's non-zeros and flops at 27 to 1,000 fibres from the
//                             analysis of the graph of the beam nodes (no tangent assembled)
//   BM_ContactInstall         EquilibriumProblem::set_contact after a detection: /0 the same beam elements in
//                             contact (the pattern is kept: its blocks' adjacency compared), /1 one zone's
//                             elements more or fewer than the last time (a new pattern is built); the
//                             counter analyze_ms is the CHOLMOD analysis a new pattern also costs
// The state is not updated, so every iteration does the same work. Argument: number of fibres (100 elements
// each). Results and commands: docs/performance.md.

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/CholmodSupport>

#include "bundle_problem.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/internal_forces_term.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace {

using nodus::beam::kNodeDofs;

using nodus::bench::Setup;

void set_counters(benchmark::State& state, const Setup& s) {
  state.counters["zones"] = static_cast<double>(s.geometry.zones.size());
  state.counters["contact_elements"] = static_cast<double>(s.geometry.elements.size());
  state.counters["free_dofs"] = s.problem->size();
}

void BM_ContactDetection(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    nodus::contact::ContactGeometry g =
        nodus::contact::detect(s.bundle.model, s.bundle.x, {}, {}, &s.geometry);
    benchmark::DoNotOptimize(g.elements.data());
  }
  set_counters(state, s);
}

/// Detection alone on bundles too large for the whole problem (1,000 fibres: 909,000 unknowns): the cost of
/// the replicated detection of a distributed run (docs/parallel.md), where every rank detects on its own
/// threads. The bundle's state, no equilibrium problem; the first detection gives the previous geometry.
void BM_BundleDetection(benchmark::State& state) {
  const nodus::bench::Bundle bundle = nodus::bench::twisted_bundle(static_cast<int>(state.range(0)));
  const nodus::contact::ContactGeometry first = nodus::contact::detect(bundle.model, bundle.x, {});
  for (auto _ : state) {
    nodus::contact::ContactGeometry g = nodus::contact::detect(bundle.model, bundle.x, {}, {}, &first);
    benchmark::DoNotOptimize(g.elements.data());
  }
  state.counters["zones"] = static_cast<double>(first.zones.size());
  state.counters["contact_elements"] = static_cast<double>(first.elements.size());
  state.counters["dofs"] = static_cast<double>(bundle.model.num_dofs());
}

void BM_ContactAssembly(benchmark::State& state) {
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

/// Second argument: the solver (nodus::solver::LinearSolverKind: 0 cholmod, 1 cholmod_ldlt, 2 umfpack, 3
/// mumps_ldlt, 4 mumps_lu, 5 klu). The bundle has no friction, so its tangent is symmetric: the LU solvers
/// factorise the whole matrix as they would the varying friction tangent, which has the same pattern.
void BM_ContactFactorizeSolve(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  const auto kind = static_cast<nodus::solver::LinearSolverKind>(state.range(1));
  auto linear = nodus::solver::make_linear_solver(kind);
  Eigen::VectorXd r, du;
  s.problem->evaluate(r, true);
  const auto start = std::chrono::steady_clock::now();
  linear->analyze(s.problem->tangent());
  state.counters["analyze_ms"] =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  bool ok = true;
  for (auto _ : state) {
    ok = linear->factorize(s.problem->tangent()) && ok;
    du = linear->solve(r);
    benchmark::DoNotOptimize(du.data());
    benchmark::ClobberMemory();
  }
  if (!ok) state.SkipWithError("factorize reported a singular matrix");
  // The Newton increment solves K du = r: its relative residual says the factor is sound.
  state.counters["rel_residual"] = (s.problem->tangent() * du - r).norm() / r.norm();
  set_counters(state, s);
  state.SetLabel(linear->name());
}

struct FactorCounts {
  double nnz_l = 0.0;
  double flops = 0.0;
};

/// The Cholesky factor of `tangent` as CHOLMOD's analysis gives it (METIS ordering): nnz(L) and the
/// factorisation's flops.
FactorCounts cholmod_factor_counts(const nodus::solver::SparseMatrix& tangent) {
  Eigen::CholmodSupernodalLLT<nodus::solver::SparseMatrix, Eigen::Upper> llt;
  cholmod_common& c = llt.cholmod();
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  llt.analyzePattern(tangent);
  return {c.lnz, c.fl};
}

/// One Newton iteration as NewtonSolver spends it without a line search: the residual and the tangent in one
/// pass, one factorisation (the pattern analysed once, outside the loop, as a run does until its contact
/// pattern changes), one solve. The ratio iteration / factorisation is what issue 17 asks to keep at 1.3 or
/// below.
void BM_ContactNewtonIteration(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  auto linear = nodus::solver::make_linear_solver(nodus::solver::LinearSolverKind::cholmod);
  Eigen::VectorXd r, du;
  s.problem->evaluate(r, true);
  linear->analyze(s.problem->tangent());
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  double assembly = 0.0, factorize = 0.0, solve = 0.0;
  bool ok = true;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    s.problem->evaluate(r, true);
    const auto t1 = Clock::now();
    ok = linear->factorize(s.problem->tangent()) && ok;
    const auto t2 = Clock::now();
    du = linear->solve(r);
    const auto t3 = Clock::now();
    benchmark::DoNotOptimize(du.data());
    benchmark::ClobberMemory();
    assembly += ms(t0, t1);
    factorize += ms(t1, t2);
    solve += ms(t2, t3);
  }
  if (!ok) state.SkipWithError("factorize reported a matrix that is not positive definite");
  const double n = static_cast<double>(state.iterations());
  state.counters["assembly_ms"] = assembly / n;
  state.counters["factorize_ms"] = factorize / n;
  state.counters["solve_ms"] = solve / n;
  state.counters["iteration_ratio"] = (assembly + factorize + solve) / factorize;
  const FactorCounts factor = cholmod_factor_counts(s.problem->tangent());
  state.counters["nnz_K"] = static_cast<double>(s.problem->tangent().nonZeros());
  state.counters["nnz_L"] = factor.nnz_l;
  state.counters["factor_flops"] = factor.flops;
  set_counters(state, s);
}

/// The Cholesky factor of the bundle's tangent from the analysis of its nodes, for bundles too large to
/// assemble (1,000 fibres: about 530 M tangent entries): CHOLMOD's symbolic analysis (METIS ordering) of the
/// graph of the free beam nodes (an edge where an element or a contact element couples two nodes), then every
/// node's nine unknowns counted in. In block column J of the factor with C_J blocks (its diagonal one
/// included) the k-th of the node's nine columns (k = 0..8) holds 9 - k + 9 (C_J - 1) entries: nnz_L is their
/// sum, factor_flops the sum of their squares, as CHOLMOD counts a factorisation's flops (the sum over L's
/// columns of their counts squared). At 27 and 75 fibres the counters scalar_nnz_L and scalar_flops give
/// CHOLMOD's analysis of the assembled tangent itself (BM_ContactNewtonIteration's), for comparison: the
/// orderings differ (METIS on nodes or on unknowns). Also largest_front (the order of the largest dense front
/// of a multifrontal factorisation, in unknowns) and update_GB (the sum of the fronts' contribution blocks,
/// lower triangles in doubles: of the order of what the ranks of a distributed factorisation send each other;
/// CHOLMOD's supernodes, relaxed over nodes' columns, make both somewhat larger). analyze_ms: the analysis of
/// the nodes' graph.
void BM_BundleFactorAnalysis(benchmark::State& state) {
  const int fibres = static_cast<int>(state.range(0));
  const nodus::bench::Bundle bundle = nodus::bench::contact_bundle(fibres);
  const nodus::model::Model& model = bundle.model;
  const nodus::contact::ContactGeometry geometry = nodus::contact::detect(model, bundle.x, {});
  const std::size_t elements = geometry.elements.size();
  std::vector<std::vector<int>> groups = nodus::bench::contact_couplings(model, geometry);
  nodus::model::InternalForcesTerm(model).couplings(groups);
  const nodus::solver::BlockAdjacency adjacency = nodus::solver::block_adjacency(model.num_nodes(), groups);
  // The held nodes have no free unknowns.
  std::vector<int> free_node(static_cast<std::size_t>(model.num_nodes()), 0);
  for (int node : nodus::bench::held_nodes(model)) free_node[static_cast<std::size_t>(node)] = -1;
  int n = 0;
  for (int& index : free_node) index = index < 0 ? -1 : n++;
  std::vector<Eigen::Triplet<double, int>> upper;
  for (int a = 0; a < model.num_nodes(); ++a)
    for (int b : adjacency.neighbours[static_cast<std::size_t>(a)]) {
      const int i = free_node[static_cast<std::size_t>(a)], j = free_node[static_cast<std::size_t>(b)];
      if (i >= 0 && j >= 0 && i <= j) upper.emplace_back(i, j, 1.0);
    }
  nodus::solver::SparseMatrix nodes(n, n);
  nodes.setFromTriplets(upper.begin(), upper.end());
  double nnz_l = 0.0, flops = 0.0, analyze_ms = 0.0, largest_front = 0.0, update_bytes = 0.0;
  for (auto _ : state) {
    cholmod_common c;
    cholmod_start(&c);
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
    c.postorder = 1;
    c.supernodal = CHOLMOD_SUPERNODAL;
    cholmod_sparse a = Eigen::viewAsCholmod(nodes);
    a.stype = 1;  // the upper triangle
    const auto start = std::chrono::steady_clock::now();
    cholmod_factor* factor = cholmod_analyze(&a, &c);
    analyze_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (factor == nullptr) {
      state.SkipWithError("CHOLMOD's analysis failed");
      cholmod_finish(&c);
      return;
    }
    const int* counts = static_cast<const int*>(factor->ColCount);
    nnz_l = flops = 0.0;
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < kNodeDofs; ++k) {
        const double column = kNodeDofs - k + kNodeDofs * (counts[j] - 1.0);
        nnz_l += column;
        flops += column * column;
      }
    // The supernodes (CHOLMOD's, relaxed): a multifrontal factorisation (MUMPS) eliminates each one's columns
    // in a dense front of its rows and passes the rest of the front, its contribution block, to its parent.
    // The contribution blocks' sum is of the order of what the ranks send in one factorisation: more where a
    // front is shared by ranks (its pivot rows go to each) and at the root, less where a parent is on its
    // child's rank. The largest front is the densest step.
    const auto* super = static_cast<const int*>(factor->super);
    const auto* rows = static_cast<const int*>(factor->pi);
    largest_front = update_bytes = 0.0;
    for (std::size_t s = 0; s < factor->nsuper; ++s) {
      const double front = kNodeDofs * static_cast<double>(rows[s + 1] - rows[s]);
      const double pivots = kNodeDofs * static_cast<double>(super[s + 1] - super[s]);
      largest_front = std::max(largest_front, front);
      update_bytes += 8.0 * (front - pivots) * (front - pivots + 1.0) / 2.0;
    }
    cholmod_free_factor(&factor, &c);
    cholmod_finish(&c);
  }
  state.counters["largest_front"] = largest_front;
  state.counters["update_GB"] = update_bytes / 1e9;
  state.counters["analyze_ms"] = analyze_ms;
  state.counters["free_nodes"] = n;
  state.counters["node_pairs"] = static_cast<double>(nodes.nonZeros());
  state.counters["contact_elements"] = static_cast<double>(elements);
  state.counters["nnz_L"] = nnz_l;
  state.counters["factor_flops"] = flops;
  if (fibres <= 75) {
    const FactorCounts factor = cholmod_factor_counts(Setup(fibres).problem->tangent());
    state.counters["scalar_nnz_L"] = factor.nnz_l;
    state.counters["scalar_flops"] = factor.flops;
  }
}

void BM_ContactInstall(benchmark::State& state) {
  Setup s(static_cast<int>(state.range(0)));
  const bool change = state.range(1) != 0;
  // The last zone's elements left out (a pair of fibres no longer in contact; the zone's own count is not
  // read by set_contact).
  nodus::contact::ContactGeometry fewer = s.geometry;
  const int last_zone = static_cast<int>(s.geometry.zones.size()) - 1;
  std::erase_if(fewer.elements, [&](const nodus::contact::ContactElement& e) { return e.zone == last_zone; });
  const std::size_t zones = s.geometry.zones.size();
  bool full = true;
  int rebuilt = 0;
  for (auto _ : state) {
    const nodus::contact::ContactGeometry& g = change && full ? fewer : s.geometry;
    full = !full;
    rebuilt +=
        s.problem->set_contact(g, std::vector<double>(zones, 400.0),
                               std::vector<Eigen::Vector3d>(g.elements.size(), Eigen::Vector3d::Zero()))
            ? 1
            : 0;
    benchmark::DoNotOptimize(s.problem->tangent().valuePtr());
  }
  if (change != (rebuilt > 0)) state.SkipWithError("the pattern was not rebuilt as the case says");
  auto linear = nodus::solver::make_linear_solver(nodus::solver::LinearSolverKind::cholmod);
  const auto start = std::chrono::steady_clock::now();
  linear->analyze(s.problem->tangent());
  state.counters["analyze_ms"] =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  state.counters["nnz"] = static_cast<double>(s.problem->tangent().nonZeros());
  set_counters(state, s);
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(7)->Arg(27)->Arg(75)->Unit(benchmark::kMillisecond);
}

/// CHOLMOD's simplicial LDL^T (the `cholmod` solver's fallback for indefinite tangents until MUMPS took its
/// place) and UMFPACK are left out at 75 fibres, where one factorisation takes minutes.
void sizes_and_solvers(benchmark::internal::Benchmark* b) {
  using nodus::solver::LinearSolverKind;
  // 3 fibres: only the two LU solvers that solver.linear_solver: auto chooses between (KLU and MUMPS's LU);
  // KLU up to 27 fibres (its factor at 75 would take minutes).
  for (int fibres : {3, 7, 27, 75})
    for (LinearSolverKind kind :
         {LinearSolverKind::cholmod, LinearSolverKind::cholmod_ldlt, LinearSolverKind::umfpack,
          LinearSolverKind::mumps_ldlt, LinearSolverKind::mumps_lu, LinearSolverKind::klu}) {
      const bool lu_pair = kind == LinearSolverKind::mumps_lu || kind == LinearSolverKind::klu;
      if (fibres == 3 && !lu_pair) continue;
      if (fibres == 75 && kind != LinearSolverKind::cholmod && kind != LinearSolverKind::mumps_ldlt &&
          kind != LinearSolverKind::mumps_lu)
        continue;
      b->Args({fibres, static_cast<int>(kind)});
    }
  b->ArgNames({"fibres", "solver"})->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_ContactDetection)->Apply(sizes);
BENCHMARK(BM_BundleDetection)->Arg(75)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactAssembly)->Apply(sizes);
BENCHMARK(BM_ContactFactorizeSolve)->Apply(sizes_and_solvers);
BENCHMARK(BM_ContactNewtonIteration)->Apply(sizes)->UseRealTime();
BENCHMARK(BM_BundleFactorAnalysis)
    ->Arg(27)
    ->Arg(75)
    ->Arg(300)
    ->Arg(1000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactInstall)
    ->ArgsProduct({{7, 27, 75}, {0, 1}})
    ->ArgNames({"fibres", "new_pattern"})
    ->Unit(benchmark::kMillisecond);
