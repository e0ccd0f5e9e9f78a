#pragma once
/// Assembly of a sparse symmetric-pattern matrix over the free unknowns of a system whose unknowns come in
/// blocks (a beam node's nine, a rigid body's six, ...). The pattern is built once from the block
/// connectivity and then reused: each assembly only overwrites values.

#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "nodus/solver/ordered_assembly.hpp"

namespace nodus::solver {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// The pattern of a matrix by blocks.
struct BlockAdjacency {
  /// Per block, the blocks it is coupled with (itself included), sorted.
  std::vector<std::vector<int>> neighbours;
  bool operator==(const BlockAdjacency&) const = default;
};

/// The adjacency of `num_blocks` blocks that `groups` couple (every block of a group with every other).
BlockAdjacency block_adjacency(int num_blocks, const std::vector<std::vector<int>>& groups);

/// The blocks of `block_offsets` (as SparseAssembler's) split into `parts` consecutive ranges of nearly equal
/// numbers of matrix entries in their columns (their rows: the pattern is symmetric), plus one a block, for
/// the pattern of `free_index` and `adjacency`: the ranks' shares of a distributed evaluation.
std::vector<BlockRange> split_blocks(const std::vector<int>& block_offsets,
                                     const std::vector<int>& free_index, const BlockAdjacency& adjacency,
                                     int parts);

class SparseAssembler {
 public:
  /// `block_offsets`: the first unknown of every block, then the number of unknowns (increasing).
  /// `free_index[dof]` is the row of unknown `dof` in the reduced system, or -1 if the unknown is prescribed.
  /// `groups` lists, for every element, the blocks it couples. All unknowns of coupled blocks are coupled.
  SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index,
                  const std::vector<std::vector<int>>& groups);
  /// The same from the blocks' adjacency (block_adjacency of the groups). `rows`: only the rows of these
  /// blocks are in the matrix (by default all): a process of a distributed run holds and assembles the rows
  /// it owns (docs/parallel.md); entries of other rows are not added.
  SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index, BlockAdjacency adjacency,
                  BlockRange rows = {});
  /// Blocks of `block_size` unknowns each.
  SparseAssembler(int block_size, const std::vector<int>& free_index,
                  const std::vector<std::vector<int>>& groups);

  int size() const { return static_cast<int>(matrix_.rows()); }
  void set_zero();
  /// Adds the dense matrix `k` of the unknowns of `blocks` (each block's unknowns, in order), in the columns
  /// of the blocks of `columns` only (by default all): threads that add into different ranges of columns
  /// write different entries.
  void add(std::span<const int> blocks, const Eigen::Ref<const Eigen::MatrixXd>& k, BlockRange columns = {});
  /// The blocks whose rows the matrix holds.
  BlockRange rows() const { return rows_; }
  /// The blocks split into `parts` consecutive ranges of nearly equal numbers of the matrix's entries in
  /// their columns, for adding on `parts` threads (OrderedAssembly). Kept for the last `parts` asked.
  const std::vector<BlockRange>& split_columns(int parts) const;
  const SparseMatrix& matrix() const { return matrix_; }
  const std::vector<int>& free_index() const { return free_index_; }
  /// Whether this assembler's pattern is the one of `free_index` and `adjacency`: then a new assembler for
  /// them (and the same rows) would build the same matrix pattern, and an analysis of this one serves it.
  bool has_pattern(const std::vector<int>& free_index, const BlockAdjacency& adjacency) const {
    return free_index == free_index_ && adjacency == adjacency_;
  }
  const BlockAdjacency& adjacency() const { return adjacency_; }

 private:
  int value_offset(int row, int col) const;

  std::vector<int> offsets_;
  std::vector<int> free_index_;
  BlockAdjacency adjacency_;
  SparseMatrix matrix_;
  BlockRange rows_;
  mutable std::vector<BlockRange> columns_split_;  // split_columns' last answer
};

}  // namespace nodus::solver
