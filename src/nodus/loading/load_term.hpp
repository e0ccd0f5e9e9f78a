#pragma once
/// The loads as a term of the equilibrium [Durville 2012, Eq. 4 and 8]: minus the generalised external forces
/// of the active loads (dead forces, moments about a fixed axis, and the ramped-down loads of released
/// supports), and minus their derivative (the load stiffness of moments).

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/term.hpp"

namespace nodus::loading {

class LoadTerm final : public model::Term {
 public:
  /// `conditions` outlives the term.
  explicit LoadTerm(Conditions& conditions) : conditions_(conditions) {}

  std::string_view name() const override { return "loads"; }
  /// The node of every condition: any of them may carry a load (a released support does); a bind couples
  /// all its bodies.
  void couplings(std::vector<std::vector<int>>& groups) const override;
  void add(const model::TermState& state, Eigen::VectorXd& residual,
           solver::SparseAssembler* tangent) override;
  /// Moment angles count their turns.
  void commit(const model::TermState& state) override { conditions_.commit(state.x); }
  /// applied: |f_ext| at the last evaluation, the binds' forces included (constraint forces, as the support
  /// reactions that also set the force scale).
  model::ResidualScale residual_scale() const override { return {applied_, 0.0, 0.0}; }

 private:
  Conditions& conditions_;
  Eigen::VectorXd f_ext_;
  double applied_ = 0.0;
};

}  // namespace nodus::loading
