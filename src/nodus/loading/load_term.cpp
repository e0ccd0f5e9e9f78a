#include "nodus/loading/load_term.hpp"

namespace nodus::loading {

void LoadTerm::couplings(std::vector<std::vector<int>>& groups) const {
  for (int c = 0; c < conditions_.size(); ++c) {
    if (conditions_.kind(c) == ConditionKind::bind)
      groups.push_back(conditions_.blocks(c));  // a bind couples its bodies
    else
      groups.push_back({conditions_.block(c)});
  }
}

void LoadTerm::add(const model::TermState& state, Eigen::VectorXd& residual,
                   solver::SparseAssembler* tangent) {
  f_ext_.setZero(state.x.size());
  conditions_.external_force(state.time, state.x, f_ext_);
  if (tangent) conditions_.add_load_tangent(state.time, state.x, *tangent);
  residual -= f_ext_;
  applied_ = f_ext_.norm();
}

}  // namespace nodus::loading
