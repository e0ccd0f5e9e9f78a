#include "nodus/solver/ordered_assembly.hpp"

#include <algorithm>
#include <atomic>
#include <memory>
#include <thread>

#include <omp.h>

namespace nodus::solver {
namespace {

/// Buffers of the ring on several threads: small enough to stay in cache (32 contact responses: 740 kB), as
/// a ring of 256 ran 5 % slower on the 27-fibre bundle (docs/performance.md).
constexpr std::size_t kRing = 32;
/// Below the work of this many beam elements with their tangent (2.7 ms) the loop runs on one thread: the
/// threads would gain little, and on a busy machine a parallel region can wait milliseconds for a thread
/// that the system has not yet run.
constexpr double kParallelElements = 256.0;

}  // namespace

std::size_t assembly_buffers(std::size_t count, double relative_cost) {
  if (static_cast<double>(count) * relative_cost < kParallelElements || omp_get_max_threads() < 2) return 1;
  return std::min(kRing, count);
}

void assemble_in_order(std::size_t count, std::size_t buffers,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t)>& scatter) {
  if (buffers == 1) {
    for (std::size_t k = 0; k < count; ++k) {
      compute(k, 0);
      scatter(k, 0);
    }
    return;
  }
  std::atomic<std::size_t> next{0};       // the next element to compute
  std::atomic<std::size_t> scattered{0};  // the elements added up so far
  // ready[slot] = k + 1 once element k is computed into its slot.
  const std::unique_ptr<std::atomic<std::size_t>[]> ready(new std::atomic<std::size_t>[buffers]);
  for (std::size_t s = 0; s < buffers; ++s) ready[s].store(0, std::memory_order_relaxed);
  // Computes the next element if its slot is free (its element of the previous lap added up); false if
  // there is none to compute or no free slot.
  const auto compute_next = [&] {
    std::size_t k = next.load(std::memory_order_relaxed);
    if (k >= count || k >= scattered.load(std::memory_order_acquire) + buffers) return false;
    if (next.compare_exchange_weak(k, k + 1, std::memory_order_relaxed)) {
      compute(k, k % buffers);
      ready[k % buffers].store(k + 1, std::memory_order_release);
    }
    return true;
  };
#pragma omp parallel
  {
    if (omp_get_thread_num() == 0) {
      for (std::size_t k = 0; k < count; ++k) {
        while (ready[k % buffers].load(std::memory_order_acquire) != k + 1)
          if (!compute_next()) std::this_thread::yield();
        scatter(k, k % buffers);
        scattered.store(k + 1, std::memory_order_release);
      }
    } else {
      while (next.load(std::memory_order_relaxed) < count)
        if (!compute_next()) std::this_thread::yield();
    }
  }
}

}  // namespace nodus::solver
