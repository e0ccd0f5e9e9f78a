// SparseAssembler against a dense reference: each block matrix added to a dense matrix entry by entry, at the
// reduced indices of its free unknowns. Blocks of different sizes, unknowns fixed here and there and one
// block fixed whole, blocks coupled by overlapping groups; the same entries whether added at once or by
// ranges of columns, and in the rows of a range of blocks only.

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::solver {
namespace {

struct Problem {
  std::vector<int> offsets;     // block b holds unknowns [offsets[b], offsets[b + 1])
  std::vector<int> free_index;  // reduced index of each unknown, -1 where fixed
  std::vector<std::vector<int>> groups;
  std::vector<Eigen::MatrixXd> blocks;  // one per group, over the unknowns of its blocks in order
  int free = 0;
};

Problem make_problem() {
  Problem p;
  const std::vector<int> sizes{9, 6, 9, 3, 9, 9, 12, 9, 6, 9, 9, 3};
  p.offsets.push_back(0);
  for (int s : sizes) p.offsets.push_back(p.offsets.back() + s);
  const int blocks = static_cast<int>(sizes.size());
  for (int b = 0; b < blocks; ++b)
    for (int d = 0; d < sizes[static_cast<std::size_t>(b)]; ++d) {
      const bool fixed = b == 4 || (b == 1 && d < 2) || (b == 6 && d % 4 == 1) || (b == 9 && d == 8);
      p.free_index.push_back(fixed ? -1 : p.free++);
    }
  for (int b = 0; b + 2 < blocks; b += 2) p.groups.push_back({b, b + 1, b + 2});  // elements
  p.groups.push_back({0, 1, 7, 8});                                               // contact-like
  p.groups.push_back({3, 10, 11});
  p.groups.push_back({9, 2});  // not in increasing order
  p.groups.push_back({4, 6});  // with the fixed block
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::vector<int>& g : p.groups) {
    Eigen::Index m = 0;
    for (int b : g) m += sizes[static_cast<std::size_t>(b)];
    p.blocks.push_back(Eigen::MatrixXd::NullaryExpr(m, m, [&] { return u(rng); }));
  }
  return p;
}

/// The dense reference: the groups' matrices added twice, in order, entry by entry.
Eigen::MatrixXd dense_sum(const Problem& p) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(p.free, p.free);
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t g = 0; g < p.groups.size(); ++g) {
      std::vector<int> dofs;
      for (int b : p.groups[g])
        for (int i = p.offsets[static_cast<std::size_t>(b)]; i < p.offsets[static_cast<std::size_t>(b) + 1];
             ++i)
          dofs.push_back(p.free_index[static_cast<std::size_t>(i)]);
      for (std::size_t c = 0; c < dofs.size(); ++c)
        for (std::size_t r = 0; r < dofs.size(); ++r)
          if (dofs[r] >= 0 && dofs[c] >= 0)
            d(dofs[r], dofs[c]) += p.blocks[g](static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
    }
  return d;
}

void add_all(const Problem& p, SparseAssembler& a, BlockRange columns = {}) {
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t g = 0; g < p.groups.size(); ++g) a.add(p.groups[g], p.blocks[g], columns);
}

TEST(SparseAssembler, EqualsTheDenseSumOfItsBlocks) {
  const Problem p = make_problem();
  SparseAssembler a(p.offsets, p.free_index, p.groups);
  a.set_zero();
  add_all(p, a);
  EXPECT_EQ(Eigen::MatrixXd(a.matrix()), dense_sum(p));
  // The pattern holds the coupled blocks' entries and no others: a zero of the reference outside it.
  EXPECT_LT(a.matrix().nonZeros(), Eigen::Index{p.free} * p.free);
}

TEST(SparseAssembler, ByRangesOfColumnsGivesTheSameEntries) {
  const Problem p = make_problem();
  SparseAssembler a(p.offsets, p.free_index, p.groups);
  a.set_zero();
  for (const BlockRange& columns : {BlockRange{0, 3}, BlockRange{3, 8}, BlockRange{8}})
    add_all(p, a, columns);
  EXPECT_EQ(Eigen::MatrixXd(a.matrix()), dense_sum(p));
}

TEST(SparseAssembler, ARangeOfRowBlocksHoldsThoseRowsOfTheWhole) {
  const Problem p = make_problem();
  const BlockRange rows{2, 7};
  SparseAssembler a(p.offsets, p.free_index,
                    block_adjacency(static_cast<int>(p.offsets.size()) - 1, p.groups), rows);
  a.set_zero();
  add_all(p, a);
  Eigen::MatrixXd expected = dense_sum(p);
  for (int b = 0; b + 1 < static_cast<int>(p.offsets.size()); ++b)
    if (!rows.contains(b))
      for (int i = p.offsets[static_cast<std::size_t>(b)]; i < p.offsets[static_cast<std::size_t>(b) + 1];
           ++i)
        if (p.free_index[static_cast<std::size_t>(i)] >= 0)
          expected.row(p.free_index[static_cast<std::size_t>(i)]).setZero();
  EXPECT_EQ(Eigen::MatrixXd(a.matrix()), expected);
}

}  // namespace
}  // namespace nodus::solver
