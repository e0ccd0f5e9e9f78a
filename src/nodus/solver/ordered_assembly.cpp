#include "nodus/solver/ordered_assembly.hpp"

#include <algorithm>

#include <omp.h>

namespace nodus::solver {
namespace {

/// Elements per chunk on several threads.
constexpr std::size_t kChunk = 256;
/// Below this many elements the loop runs on one thread: a parallel region would cost more than it saves.
constexpr std::size_t kParallelElements = 256;

}  // namespace

std::size_t assembly_chunk(std::size_t count) {
  if (count < kParallelElements || omp_get_max_threads() < 2) return 1;
  return std::min(kChunk, count);
}

void assemble_in_order(std::size_t count, std::size_t chunk,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t)>& scatter) {
  const bool parallel = chunk > 1;
  const std::size_t chunks = (count + chunk - 1) / chunk;
  const auto first = [&](std::size_t c) { return c * chunk; };
  const auto size = [&](std::size_t c) { return std::min(chunk, count - c * chunk); };
  const auto slot = [&](std::size_t c, std::size_t i) { return (c % 2) * chunk + i; };
  // Pass c computes chunk c and adds up chunk c - 1 (whose buffers the computation does not touch).
  for (std::size_t c = 0; c <= chunks; ++c) {
#pragma omp parallel if (parallel)
    {
#pragma omp single nowait
      if (c > 0)
        for (std::size_t i = 0; i < size(c - 1); ++i) scatter(first(c - 1) + i, slot(c - 1, i));
      if (c < chunks) {
        const auto n = static_cast<std::ptrdiff_t>(size(c));
#pragma omp for schedule(dynamic) nowait
        for (std::ptrdiff_t i = 0; i < n; ++i)
          compute(first(c) + static_cast<std::size_t>(i), slot(c, static_cast<std::size_t>(i)));
      }
    }
  }
}

}  // namespace nodus::solver
