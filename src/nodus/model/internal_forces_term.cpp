#include "nodus/model/internal_forces_term.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nodus::model {

InternalForcesTerm::InternalForcesTerm(const Model& model) : model_(model) {
  double longest = 0.0, stiffest = 0.0, shortest = INFINITY;
  for (const beam::Beam& b : model_.beams()) {
    longest = std::max(longest, b.length());
    shortest = std::min(shortest, b.element_length());
    const beam::ElementProperties p = b.element_properties(1);
    stiffest = std::max(stiffest, p.stiffness(beam::kE33, beam::kE33));
  }
  if (model_.beams().empty()) return;
  const double extent = std::max(longest, model_.reference().lpNorm<Eigen::Infinity>());
  floor_ = 10.0 * std::numeric_limits<double>::epsilon() * stiffest * (extent / shortest) *
           std::sqrt(static_cast<double>(model_.num_dofs()));
}

void InternalForcesTerm::couplings(std::vector<std::vector<int>>& groups) const {
  const std::vector<std::vector<int>> elements = model_.element_nodes();
  groups.insert(groups.end(), elements.begin(), elements.end());
}

void InternalForcesTerm::add(const TermState& state, Eigen::VectorXd& residual,
                             solver::SparseAssembler* tangent) {
  model_.add_internal_force(state.x, residual, tangent, assembly_, state.blocks);
}

}  // namespace nodus::model
