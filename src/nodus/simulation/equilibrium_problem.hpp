#pragma once
/// The equilibrium of the model under its boundary conditions at one load time [Durville 2012, Eq. 8]:
/// residual R = f_int - f_ext over the free unknowns, and its tangent. Prescribed unknowns are eliminated.

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {

struct Tolerances {
  double residual = 1e-8;   ///< |R| <= residual * force scale
  double increment = 1e-6;  ///< max |du_i| / scale_i <= increment (positions scaled by the model size)
};

/// The state of one contact element at the last evaluation.
struct ContactState {
  double gap = 0.0;                                      ///< [mm]
  double normal_reaction = 0.0;                          ///< R_N [N]
  Eigen::Vector3d tangential = Eigen::Vector3d::Zero();  ///< friction force on J [N]
  Eigen::Vector3d reversible = Eigen::Vector3d::Zero();  ///< g_rev [mm]
  bool slip = false;
};

/// What the problem carries from one load step to the next (at a committed state): the unknowns and load
/// time, and the contact elements it was solved with, their zones' penalties, committed reversible
/// displacements and last evaluated states. Restored into a problem built on the same model and conditions,
/// it continues the run exactly.
struct ProblemState {
  Eigen::VectorXd x;  ///< committed unknowns, nine per node
  double time = 0.0;  ///< committed load time [s]
  contact::ContactGeometry contact;
  std::vector<double> penalty;               ///< per zone [N/mm]
  std::vector<Eigen::Vector3d> reversible;   ///< committed g_rev per contact element [mm]
  std::vector<ContactState> contact_states;  ///< per contact element, at the last evaluation
};

/// Viscous stabilisation of a stage: a drag -c_n (x_n - x_n,committed) / dt on the centre of every node n,
/// c_n the node's share of the beam length times the coefficient eta(t) [N s/mm^2], which goes geometrically
/// from `start` at t0 to `end` at t1 (end 0: to 1e-6 start, and exactly 0 at t1).
struct Stabilization {
  double t0 = 0.0, t1 = 0.0;      ///< the stage [s]
  double start = 0.0, end = 0.0;  ///< eta at t0 and t1 [N s/mm^2]
  /// eta at load time t [N s/mm^2].
  double at(double t) const;
};

class EquilibriumProblem final : public solver::SteppedProblem {
 public:
  EquilibriumProblem(const model::Model& model, loading::Conditions& conditions, Tolerances tolerances);

  /// Re-reads which unknowns are prescribed (after conditions were activated or released); rebuilds the
  /// sparse pattern.
  void update_free_set();

  // solver::NonlinearProblem
  int size() const override { return static_cast<int>(free_dofs_.size()); }
  Eigen::VectorXd unknowns() const override;
  void set_unknowns(const Eigen::VectorXd& u) override;
  void evaluate(Eigen::VectorXd& residual, bool with_tangent) override;
  const solver::SparseMatrix& tangent() const override { return assembler_->matrix(); }
  double residual_tolerance() const override { return residual_tolerance_; }
  double scaled_increment(const Eigen::VectorXd& du) const override;
  double increment_tolerance() const override { return tolerances_.increment; }

  // solver::SteppedProblem
  void set_time(double t) override;
  /// The viscous stabilisation of the stage being solved (default: none).
  void set_stabilization(const Stabilization& s) { stabilization_ = s; }
  /// |drag force| over all nodes at the last evaluation [N] (0 without stabilisation).
  double stabilization_force() const { return stabilization_force_; }
  void commit() override;
  void restore() override;

  double time() const { return time_; }
  const Eigen::VectorXd& state() const { return x_; }
  const Eigen::VectorXd& committed_state() const { return x_committed_; }
  /// The committed state (call between steps, after commit()).
  ProblemState saved_state() const;
  /// Makes `state` the current and committed state; re-reads the free set from the conditions (restore them
  /// first) and rebuilds the sparse pattern (the solver must re-analyse it).
  void restore_state(ProblemState state);
  /// f_int - f_ext over all unknowns at the last evaluation (reactions at the prescribed ones).
  const Eigen::VectorXd& full_residual() const { return residual_full_; }

  // Contact (Sect. 5): the contact elements, their normals and particles fixed during Newton.
  /// Replaces the contact elements; `penalty` per zone [N/mm], `reversible` per element (committed g_rev).
  /// Rebuilds the sparse pattern (the solver must re-analyse it).
  void set_contact(contact::ContactGeometry geometry, std::vector<double> penalty,
                   std::vector<Eigen::Vector3d> reversible);
  /// The laws: p_reg of the normal law, and friction (null: none).
  /// `options`: where the particles sit, and the friction tangent with R_N varying (not symmetric; for an LU
  /// solver).
  void set_contact_laws(double regularization, std::optional<contact::FrictionLaw> friction,
                        contact::ResponseOptions options = {});
  contact::ContactGeometry& contact_geometry() { return contact_; }
  const contact::ContactGeometry& contact_geometry() const { return contact_; }
  std::vector<double>& zone_penalty() { return penalty_; }
  /// Committed g_rev per contact element.
  const std::vector<Eigen::Vector3d>& reversible_committed() const { return reversible_committed_; }
  /// Per contact element, at the last evaluation.
  const std::vector<ContactState>& contact_states() const { return contact_states_; }

 private:
  const model::Model& model_;
  loading::Conditions& conditions_;
  Tolerances tolerances_;
  double length_scale_;
  double force_floor_;
  Eigen::VectorXd x_, x_committed_;
  double time_ = 0.0, time_committed_ = 0.0;
  std::vector<int> free_dofs_;
  std::vector<int> free_index_;  ///< per unknown: its row among the free ones, or -1
  std::vector<bool> prescribed_;
  std::unique_ptr<solver::SparseAssembler> assembler_;
  Eigen::VectorXd f_int_, f_ext_, residual_full_;
  double residual_tolerance_ = 0.0;
  std::vector<std::vector<int>> element_nodes_;
  contact::ContactGeometry contact_;
  std::vector<double> penalty_;
  std::vector<Eigen::Vector3d> reversible_committed_;
  std::vector<ContactState> contact_states_;
  double regularization_ = 0.0;
  std::optional<contact::FrictionLaw> friction_;
  contact::ResponseOptions response_options_;

  Stabilization stabilization_;
  double stabilization_force_ = 0.0;
  double stabilization_roundoff_ =
      0.0;                           ///< round-off of the drag in the residual, sqrt(sum (c eps |x|)^2) [N]
  std::vector<double> node_length_;  ///< per node: its share of the beam length (Simpson weights) [mm]
  std::vector<double>
      node_director_length_;  ///< per node: R^2/4 times node_length_ (drag on the directors) [mm^3]

  void rebuild_pattern();
  /// Adds the stabilisation drag to residual_full_ and, if `assembler`, its tangent.
  void add_stabilization(solver::SparseAssembler* assembler);
  /// Adds the contact forces to residual_full_ and, if `assembler`, their tangent.
  void add_contact(solver::SparseAssembler* assembler);
};

}  // namespace nodus::simulation
