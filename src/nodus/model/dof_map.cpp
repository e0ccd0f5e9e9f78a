#include "nodus/model/dof_map.hpp"

#include <stdexcept>

namespace nodus::model {

int DofMap::add_block(std::span<const DofKind> kinds) {
  if (kinds.empty()) throw std::invalid_argument("DofMap::add_block: a block needs at least one unknown");
  kinds_.insert(kinds_.end(), kinds.begin(), kinds.end());
  offsets_.push_back(static_cast<int>(kinds_.size()));
  return num_blocks() - 1;
}

}  // namespace nodus::model
