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

class SparseAssembler {
 public:
  /// `block_offsets`: the first unknown of every block, then the number of unknowns (increasing).
  /// `free_index[dof]` is the row of unknown `dof` in the reduced system, or -1 if the unknown is prescribed.
  /// `groups` lists, for every element, the blocks it couples. All unknowns of coupled blocks are coupled.
  SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index,
                  const std::vector<std::vector<int>>& groups);
  /// The same from the blocks' adjacency (block_adjacency of the groups).
  SparseAssembler(std::vector<int> block_offsets, std::vector<int> free_index, BlockAdjacency adjacency);
  /// Blocks of `block_size` unknowns each.
  SparseAssembler(int block_size, const std::vector<int>& free_index,
                  const std::vector<std::vector<int>>& groups);

  int size() const { return static_cast<int>(matrix_.rows()); }
  void set_zero();
  /// Adds the dense matrix `k` of the unknowns of `blocks` (each block's unknowns, in order), in the columns
  /// of the blocks of `columns` only (by default all): threads that add into different ranges of columns
  /// write different entries.
  void add(std::span<const int> blocks, const Eigen::Ref<const Eigen::MatrixXd>& k, BlockRange columns = {});
  /// Only the rows of the blocks of `rows` are assembled from now on (by default all): a process of a
  /// distributed run assembles the rows it owns (docs/parallel.md); the other rows keep their zeros.
  void set_rows(BlockRange rows) { rows_ = rows; }
  BlockRange rows() const { return rows_; }
  /// The blocks split into `parts` consecutive ranges of nearly equal numbers of matrix entries in their
  /// columns, for adding on `parts` threads (OrderedAssembly).
  std::vector<BlockRange> split_columns(int parts) const;
  const SparseMatrix& matrix() const { return matrix_; }
  const std::vector<int>& free_index() const { return free_index_; }
  /// Whether this assembler's pattern is the one of `free_index` and `adjacency`: then a new assembler for
  /// them would build the same matrix pattern, and an analysis of this one serves it.
  bool has_pattern(const std::vector<int>& free_index, const BlockAdjacency& adjacency) const {
    return free_index == free_index_ && adjacency == adjacency_;
  }

 private:
  int value_offset(int row, int col) const;

  std::vector<int> offsets_;
  std::vector<int> free_index_;
  BlockAdjacency adjacency_;
  SparseMatrix matrix_;
  BlockRange rows_;
};

}  // namespace nodus::solver
