#pragma once
/// Element-by-element assembly on all OpenMP threads whose sums do not depend on the number of threads.
/// Elements are taken in chunks. The contributions of a chunk's elements (force vector, dense tangent block,
/// ...) are computed in parallel into buffers, while one thread adds those of the previous chunk into the
/// global residual and matrix, in element order, and then joins the others. Every global entry is thus
/// summed in the order of a serial loop over the elements, and the results are bitwise those of one thread.

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace nodus::solver {

/// The number of elements per chunk for `count` elements: 1 where the loop runs on one thread (a single
/// thread, or fewer elements than pay for a parallel region).
std::size_t assembly_chunk(std::size_t count);

/// Calls compute(k, slot) for k in [0, count), chunk by chunk on all threads, and scatter(k, slot) on one
/// thread at a time in increasing k, after compute(k, slot) and while the next chunk is computed; `slot`, in
/// [0, 2 chunk), names the buffer of element k (two chunks' worth: the one computed, the one added up).
void assemble_in_order(std::size_t count, std::size_t chunk,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t)>& scatter);

/// The buffers of two chunks of `Contribution`s, kept across calls (a contact element's 54 x 54 block is
/// 23 kB; two chunks of them, a few MB, however many elements there are).
template <class Contribution>
class OrderedAssembly {
 public:
  /// Calls compute(k, contribution) for every element k in [0, count), on all threads, and
  /// scatter(k, contribution) one at a time in increasing k, with the contribution computed for k.
  /// compute() may write to its contribution and to data of element k only, and must not throw; scatter()
  /// may write to what compute() does not read.
  template <class Compute, class Scatter>
  void run(std::size_t count, Compute&& compute, Scatter&& scatter) {
    const std::size_t chunk = assembly_chunk(count);
    if (buffer_.size() < 2 * chunk) buffer_.resize(2 * chunk);
    assemble_in_order(
        count, chunk, [&](std::size_t k, std::size_t slot) { compute(k, buffer_[slot]); },
        [&](std::size_t k, std::size_t slot) { scatter(k, std::as_const(buffer_[slot])); });
  }

 private:
  std::vector<Contribution> buffer_;
};

}  // namespace nodus::solver
