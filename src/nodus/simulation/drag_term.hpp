#pragma once
/// The viscous stabilisation of a stage as a term of the equilibrium: a drag -c_n (x_n - x_n,committed) / dt
/// on the centre of every node n, c_n the node's share of the beam length times the coefficient eta(t) [N
/// s/mm^2], and on its directors the drag of the section's points averaged over the disc.

#include <vector>

#include "nodus/model/model.hpp"
#include "nodus/model/term.hpp"

namespace nodus::simulation {

/// The drag coefficient of a stage: eta(t) goes geometrically from `start` at t0 to `end` at t1 (end 0: to
/// 1e-6 start, and exactly 0 at t1).
struct Stabilization {
  double t0 = 0.0, t1 = 0.0;      ///< the stage [s]
  double start = 0.0, end = 0.0;  ///< eta at t0 and t1 [N s/mm^2]
  /// eta at load time t [N s/mm^2].
  double at(double t) const;
};

class DragTerm final : public model::Term {
 public:
  explicit DragTerm(const model::Model& model);

  std::string_view name() const override { return "viscous drag"; }
  void couplings(std::vector<std::vector<int>>& groups) const override;
  void add(const model::TermState& state, Eigen::VectorXd& residual,
           solver::SparseAssembler* tangent) override;
  /// roundoff: c (x - x_committed) carries an error of c eps |x| per unknown, which grows as 1/dt when steps
  /// are cut back; without it a step cut back below 1e-9 of the load time could never converge.
  model::ResidualScale residual_scale() const override { return {0.0, 0.0, roundoff_}; }

  /// The stabilisation of the stage being solved (default: none).
  void set(const Stabilization& s) { stabilization_ = s; }
  /// |drag force| over all nodes at the last evaluation [N] (0 without stabilisation).
  double force() const { return force_; }

 private:
  const model::Model& model_;
  Stabilization stabilization_;
  double force_ = 0.0;
  double roundoff_ = 0.0;            ///< sqrt(sum (c eps |x|)^2) [N]
  std::vector<double> node_length_;  ///< per node: its share of the beam length (Simpson weights) [mm]
  std::vector<double>
      node_director_length_;  ///< per node: R^2/4 times node_length_ (drag on directors) [mm^3]
};

}  // namespace nodus::simulation
