#include "nodus/solver/ordered_assembly.hpp"

#include <algorithm>
#include <atomic>
#include <memory>
#include <thread>

#include <omp.h>

namespace nodus::solver {
namespace {

/// Buffers of the ring per thread. Every thread adds its own blocks of every element, so a slot comes free
/// only when the slowest adder is past it: on 16 threads a ring of 32 x 16 assembled the 75-fibre bundle in
/// 350 ms, one of 32 in 452 ms, one of 8 x 16 in 453 ms (docs/performance.md). With one thread adding
/// everything, a ring of 256 had run 5 % slower than 32 on 2 threads (27 fibres).
constexpr std::size_t kRingPerThread = 32;
/// Below the work of this many beam elements with their tangent (2.7 ms) the loop runs on one thread: the
/// threads would gain little, and on a busy machine a parallel region can wait milliseconds for a thread
/// that the system has not yet run.
constexpr double kParallelElements = 256.0;

}  // namespace

std::vector<BlockRange> even_split(int blocks, int parts) {
  std::vector<BlockRange> ranges(static_cast<std::size_t>(std::max(parts, 1)));
  const auto n = static_cast<long long>(ranges.size());
  for (long long p = 0; p < n; ++p) {
    ranges[static_cast<std::size_t>(p)].first = static_cast<int>(blocks * p / n);
    if (p + 1 < n) ranges[static_cast<std::size_t>(p)].last = static_cast<int>(blocks * (p + 1) / n);
  }
  return ranges;
}

std::size_t assembly_buffers(std::size_t count, double relative_cost) {
  if (static_cast<double>(count) * relative_cost < kParallelElements || omp_get_max_threads() < 2) return 1;
  return std::min(kRingPerThread * static_cast<std::size_t>(omp_get_max_threads()), count);
}

void assemble_in_order(std::size_t count, std::size_t buffers,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t, BlockRange)>& scatter,
                       const std::function<std::vector<BlockRange>(int)>& split) {
  if (buffers == 1) {
    for (std::size_t k = 0; k < count; ++k) {
      compute(k, 0);
      scatter(k, 0, BlockRange{});
    }
    return;
  }
  std::atomic<std::size_t> next{0};  // the next element to compute
  // ready[slot] = k + 1 once element k is computed into its slot.
  const std::unique_ptr<std::atomic<std::size_t>[]> ready(new std::atomic<std::size_t>[buffers]);
  for (std::size_t s = 0; s < buffers; ++s) ready[s].store(0, std::memory_order_relaxed);
  std::vector<BlockRange> ranges;
  // added[t]: the elements thread t has added its blocks of, so far.
  std::unique_ptr<std::atomic<std::size_t>[]> added;
  int threads = 1;
  // Computes the next element if its slot is free (every thread has added its element of the previous lap);
  // false if there is none to compute or no free slot.
  const auto compute_next = [&] {
    std::size_t k = next.load(std::memory_order_relaxed);
    if (k >= count) return false;
    std::size_t all_added = count;
    for (int t = 0; t < threads; ++t)
      all_added = std::min(all_added, added[static_cast<std::size_t>(t)].load(std::memory_order_acquire));
    if (k >= all_added + buffers) return false;
    if (next.compare_exchange_weak(k, k + 1, std::memory_order_relaxed)) {
      compute(k, k % buffers);
      ready[k % buffers].store(k + 1, std::memory_order_release);
    }
    return true;
  };
#pragma omp parallel
  {
#pragma omp single
    {
      threads = omp_get_num_threads();
      ranges = split(threads);
      ranges.resize(static_cast<std::size_t>(threads), BlockRange{0, 0});  // a split into fewer: idle adders
      added.reset(new std::atomic<std::size_t>[static_cast<std::size_t>(threads)]);
      for (int t = 0; t < threads; ++t)
        added[static_cast<std::size_t>(t)].store(0, std::memory_order_relaxed);
    }  // the implicit barrier publishes them
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const BlockRange range = ranges[t];
    for (std::size_t k = 0; k < count;) {
      if (ready[k % buffers].load(std::memory_order_acquire) == k + 1) {
        scatter(k, k % buffers, range);
        added[t].store(++k, std::memory_order_release);
      } else if (!compute_next()) {
        std::this_thread::yield();
      }
    }
  }
}

}  // namespace nodus::solver
