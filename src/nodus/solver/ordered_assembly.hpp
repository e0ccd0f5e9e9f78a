#pragma once
/// Element-by-element assembly on all OpenMP threads whose sums do not depend on the number of threads.
/// The threads compute the contributions of the elements (force vector, dense tangent block, ...) into a
/// ring of buffers, taking the elements in increasing order as they come free. The adding is split too:
/// each thread owns a range of blocks (the rows of the residual and the columns of the tangent of some
/// nodes) and adds, for every element in increasing order, the entries of its own blocks only, computing
/// elements while the next one to add is not ready. Every global entry is thus summed by one thread in the
/// order of a serial loop over the elements, and the results are bitwise those of one thread. There is no
/// barrier between elements: a thread that the system suspends (another process on the cores) holds up only
/// the element it is computing and, once the ring is full, the slots it has still to add from.

#include <cstddef>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace nodus::solver {

/// The blocks [first, last) whose entries one thread adds.
struct BlockRange {
  int first = 0;
  int last = std::numeric_limits<int>::max();
  bool contains(int block) const { return block >= first && block < last; }
};

/// `blocks` blocks split into `parts` consecutive ranges of nearly equal numbers of blocks (the last range
/// open-ended, so that blocks added later still belong to one).
std::vector<BlockRange> even_split(int blocks, int parts);

/// The number of buffers of the ring for `count` elements: 1 where the loop runs on one thread (a single
/// thread, or less work than pays for a parallel region). `relative_cost`: the cost of an element relative to
/// a beam element with its tangent (about 10 us).
std::size_t assembly_buffers(std::size_t count, double relative_cost = 1.0);

/// Calls compute(k, slot) for every k in [0, count) on all threads, and scatter(k, slot, range) in increasing
/// k, each after compute(k, slot), once for every range of split(threads) (one range covering every block on
/// one thread), each range on one thread; `slot` = k mod `buffers` names the buffer of element k.
void assemble_in_order(std::size_t count, std::size_t buffers,
                       const std::function<void(std::size_t, std::size_t)>& compute,
                       const std::function<void(std::size_t, std::size_t, BlockRange)>& scatter,
                       const std::function<std::vector<BlockRange>(int)>& split);

/// The ring of `Contribution` buffers, kept across calls (a contact element's 54 x 54 block is 23 kB; the
/// ring of them, a few MB, however many elements there are).
template <class Contribution>
class OrderedAssembly {
 public:
  /// Calls compute(k, contribution) for every element k in [0, count), on all threads, and
  /// scatter(k, contribution, range) in increasing k, with the contribution computed for k, for each range
  /// of split(threads) on one thread: scatter adds the entries of the blocks in `range` only.
  /// compute() may write to its contribution and to data of element k only, and must not throw; scatter()
  /// may write to what compute() does not read, within its range.
  /// `relative_cost` as for assembly_buffers().
  template <class Compute, class Scatter, class Split>
  void run(std::size_t count, Compute&& compute, Scatter&& scatter, Split&& split,
           double relative_cost = 1.0) {
    const std::size_t buffers = assembly_buffers(count, relative_cost);
    if (buffer_.size() < buffers) buffer_.resize(buffers);
    assemble_in_order(
        count, buffers, [&](std::size_t k, std::size_t slot) { compute(k, buffer_[slot]); },
        [&](std::size_t k, std::size_t slot, BlockRange range) {
          scatter(k, std::as_const(buffer_[slot]), range);
        },
        split);
  }

 private:
  std::vector<Contribution> buffer_;
};

}  // namespace nodus::solver
