#pragma once
/// The beams' internal forces as a term of the equilibrium [Durville 2012, Eq. 3 and 8]: f_int of every
/// element (model.hpp) and its tangent.

#include "nodus/model/model.hpp"
#include "nodus/model/term.hpp"

namespace nodus::model {

class InternalForcesTerm final : public Term {
 public:
  explicit InternalForcesTerm(const Model& model);

  std::string_view name() const override { return "beam internal forces"; }
  void couplings(std::vector<std::vector<int>>& groups) const override;
  void add(const TermState& state, Eigen::VectorXd& residual, solver::SparseAssembler* tangent) override;
  /// The floor is the rounding error of the internal forces: a strain is computed from positions of size
  /// |x| differentiated over an element length h, so it carries an error of about eps |x| / h, and each of
  /// the n unknowns an error of about E A eps |x| / h: floor = 10 eps E A (|x| / h) sqrt(n) [N], with the
  /// stiffest axial stiffness, the shortest element and |x| the larger of the longest beam and the largest
  /// reference coordinate.
  ResidualScale residual_scale() const override { return {0.0, floor_, 0.0}; }

 private:
  const Model& model_;
  double floor_ = 0.0;
  InternalForceAssembly assembly_;
};

}  // namespace nodus::model
