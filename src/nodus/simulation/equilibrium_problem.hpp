#pragma once
/// The equilibrium of the model under its boundary conditions at one load time [Durville 2012, Eq. 8]:
/// residual R = f_int - f_ext over the free unknowns, and its tangent. Prescribed unknowns are eliminated.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {

struct Tolerances {
  double residual = 1e-8;   ///< |R| <= residual * force scale
  double increment = 1e-6;  ///< max |du_i| / scale_i <= increment (positions scaled by the model size)
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
  void commit() override;
  void restore() override;

  double time() const { return time_; }
  const Eigen::VectorXd& state() const { return x_; }
  const Eigen::VectorXd& committed_state() const { return x_committed_; }
  /// f_int - f_ext over all unknowns at the last evaluation (reactions at the prescribed ones).
  const Eigen::VectorXd& full_residual() const { return residual_full_; }

 private:
  const model::Model& model_;
  loading::Conditions& conditions_;
  Tolerances tolerances_;
  double length_scale_;
  double force_floor_;
  Eigen::VectorXd x_, x_committed_;
  double time_ = 0.0, time_committed_ = 0.0;
  std::vector<int> free_dofs_;
  std::vector<bool> prescribed_;
  std::unique_ptr<solver::SparseAssembler> assembler_;
  Eigen::VectorXd f_int_, f_ext_, residual_full_;
  double residual_tolerance_ = 0.0;
};

}  // namespace nodus::simulation
