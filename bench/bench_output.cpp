// The VTK picture of a twisted bundle of 27 fibres of 100 elements (the 3x9 yarn's size: 2,700 elements,
// 5,427 nodes), written in memory in either encoding (output.vtk_format): the time of a step's picture, and
// its size as the counter `bytes`. Results and command: docs/performance.md ("Output").

#include <benchmark/benchmark.h>

#include <sstream>

#include "nodus/output/vtk_format.hpp"
#include "twisted_bundle.hpp"

namespace {

void BM_WriteVtp(benchmark::State& state) {
  const auto encoding = static_cast<nodus::output::VtkEncoding>(state.range(0));
  static const nodus::bench::Bundle bundle = nodus::bench::twisted_bundle(27);
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::ostringstream out;
    nodus::output::write_vtp(out, bundle.model, bundle.x, 12, 0.5, encoding);
    bytes = out.str().size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
  state.SetLabel(encoding == nodus::output::VtkEncoding::binary ? "binary" : "ascii");
}
BENCHMARK(BM_WriteVtp)
    ->Arg(static_cast<int>(nodus::output::VtkEncoding::binary))
    ->Arg(static_cast<int>(nodus::output::VtkEncoding::ascii))
    ->Unit(benchmark::kMillisecond);

}  // namespace
