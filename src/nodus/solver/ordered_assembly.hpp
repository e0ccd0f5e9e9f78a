#pragma once
/// Element-by-element assembly on all OpenMP threads whose sums do not depend on the number of threads.
/// The threads compute the contributions of the elements (force vector, dense tangent block, ...) into a
/// ring of buffers, taking the elements in increasing order as they come free; the first thread adds them
/// into the global residual and matrix strictly in element order, and computes elements itself while the
/// next one to add is not ready. Every global entry is thus summed in the order of a serial loop over the
/// elements, and the results are bitwise those of one thread. There is no barrier between elements: a thread
/// that the system suspends (another process on the cores) holds up only the element it is computing.

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace nodus::solver {

/// The number of buffers of the ring for `count` elements: 1 where the loop runs on one thread (a single
/// thread, or less work than pays for a parallel region). `relative_cost`: the cost of an element relative to
/// a beam element with its tangent (about 10 us).
std::size_t assembly_buffers(std::size_t count, double relative_cost = 1.0);

/// Calls compute(k, slot) for every k in [0, count) on all threads, and scatter(k, slot) on one thread, in
/// increasing k, each after compute(k, slot); `slot` = k mod `buffers` names the buffer of element k.
void assemble_in_order(std::size_t count, std::size_t buffers,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t)>& scatter);

/// The ring of `Contribution` buffers, kept across calls (a contact element's 54 x 54 block is 23 kB; the
/// ring of them, a few MB, however many elements there are).
template <class Contribution>
class OrderedAssembly {
 public:
  /// Calls compute(k, contribution) for every element k in [0, count), on all threads, and
  /// scatter(k, contribution) on one thread in increasing k, with the contribution computed for k.
  /// compute() may write to its contribution and to data of element k only, and must not throw; scatter()
  /// may write to what compute() does not read.
  /// `relative_cost` as for assembly_buffers().
  template <class Compute, class Scatter>
  void run(std::size_t count, Compute&& compute, Scatter&& scatter, double relative_cost = 1.0) {
    const std::size_t buffers = assembly_buffers(count, relative_cost);
    if (buffer_.size() < buffers) buffer_.resize(buffers);
    assemble_in_order(
        count, buffers, [&](std::size_t k, std::size_t slot) { compute(k, buffer_[slot]); },
        [&](std::size_t k, std::size_t slot) { scatter(k, std::as_const(buffer_[slot])); });
  }

 private:
  std::vector<Contribution> buffer_;
};

}  // namespace nodus::solver
