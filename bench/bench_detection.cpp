// Time of one contact detection (broad phase, test points, zones, contact elements) in twisted bundles of
// 3 to 1000 fibres of 100 elements each (bench/twisted_bundle.hpp), and of the crossing guard's check of a
// step (contact::find_crossing) in the same bundles. Figures: docs/performance.md.

#include <optional>

#include <benchmark/benchmark.h>

#include "nodus/contact/crossing.hpp"
#include "nodus/contact/detection.hpp"
#include "twisted_bundle.hpp"

namespace {

void BM_DetectTwistedBundle(benchmark::State& state) {
  const nodus::bench::Bundle bundle = nodus::bench::twisted_bundle(static_cast<int>(state.range(0)));
  nodus::contact::ContactGeometry geometry;
  for (auto _ : state) {
    geometry = nodus::contact::detect(bundle.model, bundle.x, {});
    benchmark::DoNotOptimize(geometry.elements.data());
  }
  state.counters["elements"] = bundle.model.num_elements();
  state.counters["zones"] = static_cast<double>(geometry.zones.size());
  state.counters["contact_elements"] = static_cast<double>(geometry.elements.size());
  state.counters["us_per_element"] =
      benchmark::Counter(static_cast<double>(bundle.model.num_elements()) * 1e-6,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
/// The bundles of both benchmarks: 3 to 1000 fibres, wall time in ms.
void bundle_sizes(benchmark::internal::Benchmark* b) {
  for (int fibres : {3, 27, 75, 300, 1000}) b->Arg(fibres);
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK(BM_DetectTwistedBundle)->Apply(bundle_sizes);

/// The crossing guard between the twisted state and the state after a step that moves every node by up to
/// 0.005 mm (a pseudo-random displacement, the same at each run): no crossing, every pair of swept boxes that
/// meet tested.
void BM_CrossingTwistedBundle(benchmark::State& state) {
  const nodus::bench::Bundle bundle = nodus::bench::twisted_bundle(static_cast<int>(state.range(0)));
  const Eigen::VectorXd x1 = bundle.x + 0.005 * Eigen::VectorXd::Random(bundle.x.size());
  std::optional<nodus::contact::Crossing> crossing;
  for (auto _ : state) {
    crossing = nodus::contact::find_crossing(bundle.model, bundle.x, x1, {}, 1.2);
    benchmark::DoNotOptimize(crossing);
  }
  if (crossing) state.SkipWithError("the bundle's fibres crossed");
  state.counters["elements"] = bundle.model.num_elements();
  state.counters["us_per_element"] =
      benchmark::Counter(static_cast<double>(bundle.model.num_elements()) * 1e-6,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CrossingTwistedBundle)->Apply(bundle_sizes);

}  // namespace
