#include "nodus/solver/sparse_assembler.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

namespace nodus::solver {
namespace {

std::vector<int> uniform_offsets(int block_size, std::size_t num_dofs) {
  if (block_size < 1 || num_dofs % static_cast<std::size_t>(block_size) != 0)
    throw std::invalid_argument("SparseAssembler: the unknowns must come in whole blocks");
  std::vector<int> offsets;
  for (std::size_t first = 0; first <= num_dofs; first += static_cast<std::size_t>(block_size))
    offsets.push_back(static_cast<int>(first));
  return offsets;
}

int num_blocks_of(const std::vector<int>& block_offsets) {
  return block_offsets.empty() ? 0 : static_cast<int>(block_offsets.size()) - 1;
}

/// `blocks` blocks split into `parts` consecutive ranges of nearly equal weights, `prefix[b]` the summed
/// weight of blocks [0, b).
std::vector<BlockRange> balanced_split(const std::vector<long long>& prefix, int parts) {
  const int blocks = static_cast<int>(prefix.size()) - 1;
  std::vector<BlockRange> ranges = even_split(blocks, parts);
  const auto n = static_cast<long long>(ranges.size());
  for (long long p = 1; p < n; ++p) {
    const long long target = prefix.back() * p / n;
    const auto at = std::lower_bound(prefix.begin(), prefix.end(), target);
    const int first = static_cast<int>(at - prefix.begin());
    ranges[static_cast<std::size_t>(p)].first =
        std::max(first, ranges[static_cast<std::size_t>(p) - 1].first);
    ranges[static_cast<std::size_t>(p) - 1].last = ranges[static_cast<std::size_t>(p)].first;
  }
  return ranges;
}

/// The free unknowns of block `b`.
int free_in_block(const std::vector<int>& offsets, const std::vector<int>& free_index, int b) {
  int count = 0;
  for (int dof = offsets[static_cast<std::size_t>(b)]; dof < offsets[static_cast<std::size_t>(b) + 1]; ++dof)
    count += free_index[static_cast<std::size_t>(dof)] >= 0 ? 1 : 0;
  return count;
}

}  // namespace

std::vector<BlockRange> split_blocks(const std::vector<int>& block_offsets,
                                     const std::vector<int>& free_index, const BlockAdjacency& adjacency,
                                     int parts) {
  const int blocks = num_blocks_of(block_offsets);
  std::vector<int> free(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b)
    free[static_cast<std::size_t>(b)] = free_in_block(block_offsets, free_index, b);
  std::vector<long long> prefix(static_cast<std::size_t>(blocks) + 1, 0);
  for (int b = 0; b < blocks; ++b) {
    long long rows = 0;
    for (int other : adjacency.neighbours.at(static_cast<std::size_t>(b)))
      rows += free[static_cast<std::size_t>(other)];
    prefix[static_cast<std::size_t>(b) + 1] =
        prefix[static_cast<std::size_t>(b)] + 1 + rows * free[static_cast<std::size_t>(b)];
  }
  return balanced_split(prefix, parts);
}

BlockAdjacency block_adjacency(int num_blocks, const std::vector<std::vector<int>>& groups) {
  BlockAdjacency adjacency{std::vector<std::vector<int>>(static_cast<std::size_t>(num_blocks))};
  std::vector<std::vector<int>>& neighbours = adjacency.neighbours;
  for (const auto& group : groups)
    for (int a : group)
      for (int b : group) neighbours.at(static_cast<std::size_t>(a)).push_back(b);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adjacency;
}

SparseAssembler::SparseAssembler(int block_size, const std::vector<int>& free_index,
                                 const std::vector<std::vector<int>>& groups)
    : SparseAssembler(uniform_offsets(block_size, free_index.size()), free_index, groups) {}

SparseAssembler::SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index,
                                 const std::vector<std::vector<int>>& groups)
    : SparseAssembler(block_offsets, std::move(free_index),
                      block_adjacency(num_blocks_of(block_offsets), groups)) {}

SparseAssembler::SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index,
                                 BlockAdjacency adjacency, BlockRange rows)
    : offsets_(std::move(block_offsets)),
      free_index_(std::move(free_index)),
      adjacency_(std::move(adjacency)),
      rows_(rows) {
  if (offsets_.empty() || offsets_.front() != 0 || offsets_.back() != static_cast<int>(free_index_.size()) ||
      !std::is_sorted(offsets_.begin(), offsets_.end()))
    throw std::invalid_argument("SparseAssembler: block offsets do not cover the unknowns in order");
  const int num_blocks = static_cast<int>(offsets_.size()) - 1;
  if (adjacency_.neighbours.size() != static_cast<std::size_t>(num_blocks))
    throw std::invalid_argument("SparseAssembler: the adjacency does not have one list per block");
  const std::vector<std::vector<int>>& neighbours = adjacency_.neighbours;
  const int n =
      static_cast<int>(std::count_if(free_index_.begin(), free_index_.end(), [](int i) { return i >= 0; }));

  // Column by column (global order maps monotonically onto reduced order, so rows come out sorted).
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> inner;
  int col = 0;
  for (int block = 0; block < num_blocks; ++block) {
    for (int c = offsets_[static_cast<std::size_t>(block)]; c < offsets_[static_cast<std::size_t>(block) + 1];
         ++c) {
      if (free_index_[static_cast<std::size_t>(c)] < 0) continue;
      for (int other : neighbours[static_cast<std::size_t>(block)]) {
        if (!rows_.contains(other)) continue;
        for (int r = offsets_[static_cast<std::size_t>(other)];
             r < offsets_[static_cast<std::size_t>(other) + 1]; ++r) {
          const int row = free_index_[static_cast<std::size_t>(r)];
          if (row >= 0) inner.push_back(row);
        }
      }
      outer[static_cast<std::size_t>(++col)] = static_cast<int>(inner.size());
    }
  }
  assert(col == n);
  std::vector<double> values(inner.size(), 0.0);
  matrix_ = Eigen::Map<const SparseMatrix>(n, n, static_cast<int>(inner.size()), outer.data(), inner.data(),
                                           values.data());
  matrix_.makeCompressed();
}

void SparseAssembler::set_zero() {
  std::fill_n(matrix_.valuePtr(), matrix_.nonZeros(), 0.0);
}

int SparseAssembler::value_offset(int row, int col) const {
  const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
  const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  assert(it != end && *it == row && "SparseAssembler: entry outside the pattern");
  return static_cast<int>(it - matrix_.innerIndexPtr());
}

const std::vector<BlockRange>& SparseAssembler::split_columns(int parts) const {
  if (static_cast<int>(columns_split_.size()) == parts) return columns_split_;
  const int blocks = static_cast<int>(offsets_.size()) - 1;
  // The entries in the columns of blocks [0, b), plus one a block (a block with no free unknown still costs
  // its test).
  std::vector<long long> entries(static_cast<std::size_t>(blocks) + 1, 0);
  const int* outer = matrix_.outerIndexPtr();
  for (int b = 0; b < blocks; ++b) {
    long long in_block = 1;
    for (int dof = offsets_[static_cast<std::size_t>(b)]; dof < offsets_[static_cast<std::size_t>(b) + 1];
         ++dof) {
      const int col = free_index_[static_cast<std::size_t>(dof)];
      if (col >= 0) in_block += outer[col + 1] - outer[col];
    }
    entries[static_cast<std::size_t>(b) + 1] = entries[static_cast<std::size_t>(b)] + in_block;
  }
  columns_split_ = balanced_split(entries, parts);
  return columns_split_;
}

void SparseAssembler::add(std::span<const int> blocks, const Eigen::Ref<const Eigen::MatrixXd>& k,
                          BlockRange columns) {
  const auto block_first = [&](int b) { return offsets_[static_cast<std::size_t>(b)]; };
  const auto block_size = [&](int b) {
    return offsets_[static_cast<std::size_t>(b) + 1] - offsets_[static_cast<std::size_t>(b)];
  };
  // The first free unknown of a block of `size` unknowns whose reduced indices start at `free`; `size` if
  // none.
  const auto first_free = [](const int* free, int size) {
    int first = 0;
    while (first < size && free[first] < 0) ++first;
    return first;
  };
  int m = 0;
  for (int b : blocks) m += block_size(b);
  if (k.rows() != m || k.cols() != m) throw std::invalid_argument("SparseAssembler::add: size mismatch");
  double* values = matrix_.valuePtr();
  const int* outer = matrix_.outerIndexPtr();
  int j = 0;  // first column of k of the column block
  for (int column_block : blocks) {
    const int width = block_size(column_block);
    const int* column_free = free_index_.data() + block_first(column_block);
    const int first_column = first_free(column_free, width);
    if (!columns.contains(column_block) || first_column == width) {
      j += width;
      continue;
    }
    int i = 0;  // first row of k of the row block
    for (int row_block : blocks) {
      const int height = block_size(row_block);
      const int* row_free = free_index_.data() + block_first(row_block);
      const int first_row = first_free(row_free, height);
      if (rows_.contains(row_block) && first_row < height) {
        // Every free column of a block holds the same rows (the constructor), and the free unknowns of a
        // block have consecutive reduced indices: the row block's entries start at the same distance from the
        // top of each of its columns, found by one search for the pair of blocks.
        const int depth =
            value_offset(row_free[first_row], column_free[first_column]) - outer[column_free[first_column]];
        for (int c = first_column; c < width; ++c) {
          const int col = column_free[c];
          if (col < 0) continue;
          int offset = outer[col] + depth;
          for (int r = first_row; r < height; ++r) {
            if (row_free[r] < 0) continue;
            assert(matrix_.innerIndexPtr()[offset] == row_free[r]);
            values[offset++] += k(i + r, j + c);
          }
        }
      }
      i += height;
    }
    j += width;
  }
}

}  // namespace nodus::solver
