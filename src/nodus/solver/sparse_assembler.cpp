#include "nodus/solver/sparse_assembler.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

namespace nodus::solver {

SparseAssembler::SparseAssembler(int block_size, std::vector<int> free_index,
                                 const std::vector<std::vector<int>>& groups)
    : block_size_(block_size), free_index_(std::move(free_index)) {
  if (block_size_ < 1 || free_index_.size() % static_cast<std::size_t>(block_size_) != 0)
    throw std::invalid_argument("SparseAssembler: the unknowns must come in whole blocks");
  const int num_blocks = static_cast<int>(free_index_.size()) / block_size_;
  const int n =
      static_cast<int>(std::count_if(free_index_.begin(), free_index_.end(), [](int i) { return i >= 0; }));

  std::vector<std::vector<int>> neighbours(num_blocks);
  for (const auto& group : groups)
    for (int a : group)
      for (int b : group) neighbours.at(a).push_back(b);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  // Column by column (global order maps monotonically onto reduced order, so rows come out sorted).
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> inner;
  int col = 0;
  for (int block = 0; block < num_blocks; ++block) {
    for (int c = 0; c < block_size_; ++c) {
      if (free_index_[block * block_size_ + c] < 0) continue;
      for (int other : neighbours[block])
        for (int r = 0; r < block_size_; ++r) {
          const int row = free_index_[other * block_size_ + r];
          if (row >= 0) inner.push_back(row);
        }
      outer[++col] = static_cast<int>(inner.size());
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

void SparseAssembler::add(std::span<const int> blocks, const Eigen::Ref<const Eigen::MatrixXd>& k) {
  const int m = static_cast<int>(blocks.size()) * block_size_;
  if (k.rows() != m || k.cols() != m) throw std::invalid_argument("SparseAssembler::add: size mismatch");
  double* values = matrix_.valuePtr();
  const int num_blocks = static_cast<int>(blocks.size());
  for (int j = 0; j < m; ++j) {
    const int col = free_index_[blocks[j / block_size_] * block_size_ + j % block_size_];
    if (col < 0) continue;
    for (int b = 0; b < num_blocks; ++b) {
      // The free unknowns of a block have consecutive reduced indices, so they sit next to each other in the
      // column: one search per block.
      const int* free = free_index_.data() + blocks[static_cast<std::size_t>(b)] * block_size_;
      int first = 0;
      while (first < block_size_ && free[first] < 0) ++first;
      if (first == block_size_) continue;
      int offset = value_offset(free[first], col);
      for (int r = first; r < block_size_; ++r) {
        if (free[r] < 0) continue;
        assert(matrix_.innerIndexPtr()[offset] == free[r]);
        values[offset++] += k(b * block_size_ + r, j);
      }
    }
  }
}

}  // namespace nodus::solver
