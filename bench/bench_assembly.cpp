// Assembly of internal forces and the tangent of a single straight beam (L = 20 mm, R = 0.1 mm, E = 4000 MPa,
// nu = 0.3) in a deformed state: the reference bent into a plane arc, stretched, plus a small random
// perturbation (fixed seed). items/s = elements per second. See docs/performance.md.

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_beam.hpp"

using nodus::bench::kLength;
using nodus::bench::kRadius;

#include "nodus/model/model.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace {

using nodus::beam::kNodeDofs;
using nodus::model::Model;

Model make_model(int elements) {
  Model model;  // 2 Gauss points, the scenario default
  model.add_beam(nodus::bench::benchmark_beam(elements));
  return model;
}

/// The beam (along x, g1 = y, g2 = z) bent in the x-y plane into an arc subtending `angle`, with its centre
/// line stretched by `stretch`; directors stay normal to the arc. Then every position is perturbed by up to
/// 1e-3 of the node spacing and every director component by up to 1e-3 (uniform, fixed seed).
Eigen::VectorXd deformed_state(const Model& model, double angle, double stretch, unsigned seed) {
  const nodus::beam::Beam& beam = model.beam(0);
  const double rho = kLength / angle;
  const double spacing = 0.5 * beam.element_length();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x = model.reference();
  for (int i = 0; i < beam.num_nodes(); ++i) {
    const double s = beam.abscissa(i);
    const double theta = s / rho;
    auto q = x.segment<kNodeDofs>(kNodeDofs * beam.node(i));
    q.segment<3>(0) = (1.0 + stretch) * rho * Eigen::Vector3d(std::sin(theta), 1.0 - std::cos(theta), 0.0);
    q.segment<3>(3) = Eigen::Vector3d(-std::sin(theta), std::cos(theta), 0.0);
    q.segment<3>(6) = Eigen::Vector3d::UnitZ();
    for (int k = 0; k < 3; ++k) q[k] += 1e-3 * spacing * u(rng);
    for (int k = 3; k < kNodeDofs; ++k) q[k] += 1e-3 * u(rng);
  }
  return x;
}

/// Reduced numbering with the nine unknowns of node 0 prescribed (clamp).
std::vector<int> clamp_first_node(const Model& model) {
  std::vector<int> free_index(static_cast<std::size_t>(model.num_dofs()), -1);
  int next = 0;
  for (int i = kNodeDofs; i < model.num_dofs(); ++i) free_index[static_cast<std::size_t>(i)] = next++;
  return free_index;
}

void set_counters(benchmark::State& state, const Model& model) {
  state.SetItemsProcessed(state.iterations() * model.num_elements());
  state.counters["elements"] = model.num_elements();
  state.counters["dofs"] = model.num_dofs();
}

/// (a) Internal force vector only.
void BM_InternalForce(benchmark::State& state) {
  const Model model = make_model(static_cast<int>(state.range(0)));
  const Eigen::VectorXd x = deformed_state(model, std::numbers::pi / 3, 1e-3, 42);
  Eigen::VectorXd f;
  for (auto _ : state) {
    model.internal_force(x, f, nullptr);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, model);
}

/// (b) Internal force and tangent, into an assembler whose pattern was built once beforehand.
void BM_InternalForceAndTangent(benchmark::State& state) {
  const Model model = make_model(static_cast<int>(state.range(0)));
  const Eigen::VectorXd x = deformed_state(model, std::numbers::pi / 3, 1e-3, 42);
  nodus::solver::SparseAssembler assembler(kNodeDofs, clamp_first_node(model), model.element_nodes());
  Eigen::VectorXd f;
  for (auto _ : state) {
    model.internal_force(x, f, &assembler);
    benchmark::DoNotOptimize(f.data());
    benchmark::DoNotOptimize(assembler.matrix().valuePtr());
    benchmark::ClobberMemory();
  }
  set_counters(state, model);
  state.counters["free_dofs"] = assembler.size();
  state.counters["nnz"] = static_cast<double>(assembler.matrix().nonZeros());
}

/// (c) Building the sparse pattern (what EquilibriumProblem::update_free_set does: element_nodes() and the
/// SparseAssembler constructor).
void BM_PatternConstruction(benchmark::State& state) {
  const Model model = make_model(static_cast<int>(state.range(0)));
  const std::vector<int> free_index = clamp_first_node(model);
  double nnz = 0;
  for (auto _ : state) {
    nodus::solver::SparseAssembler assembler(kNodeDofs, free_index, model.element_nodes());
    benchmark::DoNotOptimize(assembler.matrix().innerIndexPtr());
    nnz = static_cast<double>(assembler.matrix().nonZeros());
  }
  set_counters(state, model);
  state.counters["nnz"] = nnz;
}

}  // namespace

BENCHMARK(BM_InternalForce)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InternalForceAndTangent)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PatternConstruction)->Arg(300)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);
