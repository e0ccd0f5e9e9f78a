#pragma once
/// The equilibrium of the model under its boundary conditions at one load time [Durville 2012, Eq. 8]: the
/// out-of-balance forces R = f_int - f_ext over the free unknowns, a sum of terms (model/term.hpp), and its
/// tangent. Prescribed unknowns are eliminated. The problem is built with the terms of a beam assembly (beam
/// internal forces, loads, contact-friction, viscous drag); others are registered with add_term().

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/contact_term.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/model/rotation_vector.hpp"
#include "nodus/model/term.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/simulation/drag_term.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {

struct Tolerances {
  double residual = 1e-8;   ///< |R| <= residual * force scale
  double increment = 1e-6;  ///< max |du_i| / scale_i <= increment (positions scaled by the model size)
};

using DirectorUpdate = model::DirectorUpdate;

using ContactState = contact::ContactState;

/// What the problem carries from one load step to the next (at a committed state): the unknowns and load
/// time, and the contact elements it was solved with, their zones' penalties, committed reversible
/// displacements and last evaluated states. Restored into a problem built on the same model and conditions,
/// it continues the run exactly.
struct ProblemState {
  Eigen::VectorXd x;  ///< committed unknowns, all of the model's DofMap, in its order
  double time = 0.0;  ///< committed load time [s]
  contact::ContactGeometry contact;
  std::vector<double> penalty;               ///< per zone [N/mm]
  std::vector<Eigen::Vector3d> reversible;   ///< committed g_rev per contact element [mm]
  std::vector<ContactState> contact_states;  ///< per contact element, at the last evaluation
};

class EquilibriumProblem final : public solver::SteppedProblem {
 public:
  /// The problem of a beam assembly: the terms of beam internal forces, loads, contact-friction (no elements
  /// yet) and viscous drag (none yet), in that order. `model` and `conditions` outlive the problem.
  EquilibriumProblem(const model::Model& model, loading::Conditions& conditions, Tolerances tolerances,
                     DirectorUpdate director_update = DirectorUpdate::rotation);

  /// Registers one more term (after the built-in ones) and rebuilds the sparse pattern; returns it.
  model::Term& add_term(std::unique_ptr<model::Term> term);
  /// Rebuilds the sparse pattern from the terms' couplings and the free set (after a term's couplings or the
  /// free set changed). Returns whether the pattern changed: if not, the tangent keeps its matrix and an
  /// analysis of it still serves (a detection that finds contact elements between the same beam elements).
  bool rebuild_pattern();

  /// Re-reads which unknowns are prescribed (after conditions were activated or released); rebuilds the
  /// sparse pattern.
  void update_free_set();

  // solver::NonlinearProblem
  int size() const override { return static_cast<int>(free_dofs_.size()); }
  Eigen::VectorXd unknowns() const override;
  void set_unknowns(const Eigen::VectorXd& u) override;
  /// u + du, except at the beam nodes whose six director unknowns are all free, where the directors turn by
  /// the rigid part of their increments (DirectorUpdate::rotation, the default).
  Eigen::VectorXd step(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const override;
  void evaluate(Eigen::VectorXd& residual, bool with_tangent) override;
  const solver::SparseMatrix& tangent() const override { return assembler_->matrix(); }
  /// Counts the patterns built (rebuild_pattern returning true).
  std::uint64_t pattern_version() const override { return pattern_version_; }
  double residual_tolerance() const override { return residual_tolerance_; }
  /// max |du_i| / scale_i over the free unknowns: positions scaled by the longest beam, directors, rotations
  /// and other unknowns by 1 (model::DofKind).
  double scaled_increment(const Eigen::VectorXd& du) const override;
  double increment_tolerance() const override { return tolerances_.increment; }

  // solver::SteppedProblem
  void set_time(double t) override;
  void commit() override;
  /// Back to the committed state: the unknowns and load time, and the contact elements with their penalties
  /// and committed g_rev (a failed step attempt may have changed them).
  void restore() override;

  /// The viscous stabilisation of the stage being solved (default: none).
  void set_stabilization(const Stabilization& s) { drag_->set(s); }
  /// |drag force| over all nodes at the last evaluation [N] (0 without stabilisation).
  double stabilization_force() const { return drag_->force(); }

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
  /// Whether unknown `dof` is prescribed (by a condition) at the moment.
  bool prescribed(int dof) const { return prescribed_[static_cast<std::size_t>(dof)]; }

  // Contact (Sect. 5): the contact elements, their normals and particles fixed during Newton.
  contact::ContactTerm& contact() { return *contact_; }
  const contact::ContactTerm& contact() const { return *contact_; }
  /// Replaces the contact elements (ContactTerm::set_elements) and rebuilds the sparse pattern. Returns
  /// whether the pattern changed (then the solver must re-analyse it; see rebuild_pattern).
  bool set_contact(contact::ContactGeometry geometry, std::vector<double> penalty,
                   std::vector<Eigen::Vector3d> reversible);
  /// The laws: p_reg of the normal law, and friction (null: none); see ContactTerm::set_laws.
  void set_contact_laws(double regularization, std::optional<contact::FrictionLaw> friction,
                        contact::ResponseOptions options = {}) {
    contact_->set_laws(regularization, friction, options);
  }
  /// Friction coefficients per pair of beams (ContactTerm::set_pair_friction).
  void set_contact_pair_friction(std::vector<double> coefficients, int num_beams) {
    contact_->set_pair_friction(std::move(coefficients), num_beams);
  }
  /// The contact normals follow the state, linearised in the tangent, or stay as the contact loops set them.
  void set_contact_normals_follow(bool on) { contact_->set_linearized_normal(on); }
  /// Where the contact forces act from the next evaluation on (ContactTerm::set_particles).
  void set_contact_particles(bool facing, bool centre_facing) {
    contact_->set_particles(facing, centre_facing);
  }
  contact::ContactGeometry& contact_geometry() { return contact_->geometry(); }
  const contact::ContactGeometry& contact_geometry() const { return contact_->geometry(); }
  std::vector<double>& zone_penalty() { return contact_->zone_penalty(); }
  /// Committed g_rev per contact element.
  const std::vector<Eigen::Vector3d>& reversible_committed() const {
    return contact_->reversible_committed();
  }
  /// Per contact element, at the last evaluation.
  const std::vector<ContactState>& contact_states() const { return contact_->states(); }

  /// Distributes the evaluation over the MPI ranks of the run, or not (docs/parallel.md): each rank then
  /// evaluates the elements that touch its own range of blocks (consecutive nodes, balanced by the entries of
  /// the tangent), and computes those blocks' rows of the residual and the tangent only, summed in element
  /// order as one process would. The ranks then exchange their residual rows and the states of the contact
  /// elements they own, so every rank holds the whole residual, bit for bit as one process computes it, while
  /// the tangent stays distributed: each rank holds its own rows only, and only a solver that reads them
  /// (petsc, local_rows()) can factorise it. Without MPI, or on one rank, nothing changes.
  void distribute(bool on);
  bool distributed() const { return distributed_; }
  /// The free rows [first, last) of this rank's blocks when distributed, else {-1, -1}.
  std::pair<int, int> local_rows() const;
  /// This rank's blocks when distributed (the elements with a node among them are its to evaluate), else all.
  solver::BlockRange local_blocks() const {
    return distributed_ ? rank_blocks_[static_cast<std::size_t>(parallel::rank())] : solver::BlockRange{};
  }

 private:
  const model::Model& model_;
  loading::Conditions& conditions_;
  Tolerances tolerances_;
  DirectorUpdate director_update_;
  std::vector<std::unique_ptr<model::Term>> terms_;
  contact::ContactTerm* contact_ = nullptr;  ///< owned by terms_
  DragTerm* drag_ = nullptr;                 ///< owned by terms_
  std::vector<double> increment_scale_;      ///< per unknown
  Eigen::VectorXd x_, x_committed_;
  double time_ = 0.0, time_committed_ = 0.0;
  std::vector<int> free_dofs_;
  std::vector<int> free_index_;  ///< per unknown: its row among the free ones, or -1
  std::vector<bool> prescribed_;
  std::unique_ptr<solver::SparseAssembler> assembler_;
  std::uint64_t pattern_version_ = 0;
  Eigen::VectorXd residual_full_;
  double residual_tolerance_ = 0.0;
  /// The contact elements, zone penalties and committed g_rev of the committed state, which restore() puts
  /// back.
  struct CommittedContact {
    contact::ContactGeometry geometry;
    std::vector<double> penalty;
    std::vector<Eigen::Vector3d> reversible;
  };
  CommittedContact contact_committed_;
  bool contact_changed_ = false;  ///< set_contact() was called since the last commit

  /// Distributed over MPI ranks (distribute()): the blocks whose rows each rank computes, and where their
  /// unknowns and free rows begin (one more entry: the totals).
  bool distributed_ = false;
  std::vector<solver::BlockRange> rank_blocks_;
  std::vector<int> rank_dofs_, rank_rows_;
  /// Sets the ranges above for the pattern of `adjacency` (a new one balances the ranks anew).
  void split_among_ranks(const solver::BlockAdjacency& adjacency);
  /// The assembler of the pattern of `adjacency` (this rank's rows when distributed), a new pattern version.
  void make_assembler(solver::BlockAdjacency adjacency);
  /// After the terms of a distributed evaluation: every rank receives the other ranks' rows of the residual
  /// and the states of the contact elements they own.
  void share_among_ranks();

  model::TermState term_state() const { return {x_, x_committed_, time_, time_committed_, local_blocks()}; }
};

}  // namespace nodus::simulation
