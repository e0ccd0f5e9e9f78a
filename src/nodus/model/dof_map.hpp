#pragma once
/// The unknowns of a problem, handed out in blocks (deal.II's DoFHandler in spirit): nine per beam node
/// (r, g1, g2), six for a rigid body (translation, rotation), or any other count for whoever needs them.
/// Blocks are numbered in the order they are added and their unknowns are consecutive, block after block.
/// Each unknown says what it measures, so that the increment test scales each kind by its own size.

#include <cstdint>
#include <span>
#include <vector>

namespace nodus::model {

/// What an unknown measures.
enum class DofKind : std::uint8_t {
  position,  ///< a coordinate of a point [mm]
  director,  ///< a component of a section director [-]
  rotation,  ///< a rotation angle [rad]
  other,     ///< anything else (a multiplier, ...): scaled by 1
};

class DofMap {
 public:
  /// Adds a block of kinds.size() unknowns; returns its index.
  int add_block(std::span<const DofKind> kinds);

  int num_blocks() const { return static_cast<int>(offsets_.size()) - 1; }
  int num_dofs() const { return offsets_.back(); }
  /// The first unknown of `block`.
  int first(int block) const { return offsets_[static_cast<std::size_t>(block)]; }
  /// The number of unknowns of `block`.
  int size(int block) const {
    return offsets_[static_cast<std::size_t>(block) + 1] - offsets_[static_cast<std::size_t>(block)];
  }
  /// The first unknown of every block, and then the total: num_blocks() + 1 values.
  const std::vector<int>& offsets() const { return offsets_; }
  DofKind kind(int dof) const { return kinds_[static_cast<std::size_t>(dof)]; }
  const std::vector<DofKind>& kinds() const { return kinds_; }

 private:
  std::vector<int> offsets_{0};
  std::vector<DofKind> kinds_;
};

}  // namespace nodus::model
