// Time of one contact detection (broad phase, test points, zones, contact elements) in twisted bundles of
// 3 to 1000 fibres of 100 elements each (bench/twisted_bundle.hpp). Figures: docs/performance.md.

#include <benchmark/benchmark.h>

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
BENCHMARK(BM_DetectTwistedBundle)
    ->Arg(3)
    ->Arg(27)
    ->Arg(75)
    ->Arg(300)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
