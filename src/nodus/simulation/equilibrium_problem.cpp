#include "nodus/simulation/equilibrium_problem.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "nodus/loading/load_term.hpp"
#include "nodus/model/internal_forces_term.hpp"
#include "nodus/model/rotation_vector.hpp"

namespace nodus::simulation {

EquilibriumProblem::EquilibriumProblem(const model::Model& model, loading::Conditions& conditions,
                                       Tolerances tolerances, DirectorUpdate director_update)
    : model_(model),
      conditions_(conditions),
      tolerances_(tolerances),
      director_update_(director_update),
      x_(model.reference()),
      x_committed_(x_) {
  terms_.push_back(std::make_unique<model::InternalForcesTerm>(model_));
  terms_.push_back(std::make_unique<loading::LoadTerm>(conditions_));
  auto contact = std::make_unique<contact::ContactTerm>(model_);
  contact_ = contact.get();
  terms_.push_back(std::move(contact));
  auto drag = std::make_unique<DragTerm>(model_);
  drag_ = drag.get();
  terms_.push_back(std::move(drag));
  // Increments are scaled per kind of unknown: positions by the largest beam length.
  double length_scale = 0.0;
  for (const beam::Beam& b : model_.beams()) length_scale = std::max(length_scale, b.length());
  if (length_scale <= 0.0) length_scale = 1.0;
  increment_scale_.reserve(static_cast<std::size_t>(model_.num_dofs()));
  for (model::DofKind kind : model_.dofs().kinds())
    increment_scale_.push_back(kind == model::DofKind::position ? length_scale : 1.0);
  update_free_set();
}

model::Term& EquilibriumProblem::add_term(std::unique_ptr<model::Term> term) {
  if (!term) throw std::invalid_argument("EquilibriumProblem::add_term: no term");
  terms_.push_back(std::move(term));
  rebuild_pattern();
  return *terms_.back();
}

bool EquilibriumProblem::set_contact(contact::ContactGeometry geometry, std::vector<double> penalty,
                                     std::vector<Eigen::Vector3d> reversible) {
  contact_->set_elements(std::move(geometry), std::move(penalty), std::move(reversible));
  contact_changed_ = true;
  return rebuild_pattern();
}

ProblemState EquilibriumProblem::saved_state() const {
  return {x_committed_,
          time_committed_,
          contact_->geometry(),
          contact_->zone_penalty(),
          contact_->reversible_committed(),
          contact_->states()};
}

void EquilibriumProblem::restore_state(ProblemState state) {
  if (state.x.size() != model_.num_dofs())
    throw std::invalid_argument("restore_state: the state has " + std::to_string(state.x.size()) +
                                " unknowns, the model " + std::to_string(model_.num_dofs()));
  const std::size_t elements = state.contact.elements.size();
  if (state.penalty.size() != state.contact.zones.size() || state.reversible.size() != elements ||
      state.contact_states.size() != elements)
    throw std::invalid_argument("restore_state: contact data of inconsistent sizes");
  x_ = x_committed_ = std::move(state.x);
  time_ = time_committed_ = state.time;
  contact_->set_elements(std::move(state.contact), std::move(state.penalty), std::move(state.reversible));
  contact_->set_states(std::move(state.contact_states));
  contact_committed_ = {contact_->geometry(), contact_->zone_penalty(), contact_->reversible_committed()};
  contact_changed_ = false;
  update_free_set();
}

void EquilibriumProblem::update_free_set() {
  prescribed_ = conditions_.prescribed(model_.num_dofs());
  std::vector<int> free_index(static_cast<std::size_t>(model_.num_dofs()), -1);
  free_dofs_.clear();
  for (int i = 0; i < model_.num_dofs(); ++i)
    if (!prescribed_[static_cast<std::size_t>(i)]) {
      free_index[static_cast<std::size_t>(i)] = static_cast<int>(free_dofs_.size());
      free_dofs_.push_back(i);
    }
  free_index_ = std::move(free_index);
  rebuild_pattern();
}

bool EquilibriumProblem::rebuild_pattern() {
  std::vector<std::vector<int>> groups;
  for (const auto& term : terms_) term->couplings(groups);
  const std::vector<int>& offsets = model_.dofs().offsets();
  // The blocks' adjacency costs a small part of the matrix's pattern (a block pair stands for up to 81
  // entries): compared first, it spares the pattern and the solver's analysis when a detection found
  // contact elements between the same beam elements as before.
  solver::BlockAdjacency adjacency = solver::block_adjacency(static_cast<int>(offsets.size()) - 1, groups);
  if (assembler_ && assembler_->has_pattern(free_index_, adjacency)) return false;
  make_assembler(std::move(adjacency));
  return true;
}

void EquilibriumProblem::make_assembler(solver::BlockAdjacency adjacency) {
  solver::BlockRange rows;  // all
  if (distributed_) {
    split_among_ranks(adjacency);
    rows = rank_blocks_[static_cast<std::size_t>(parallel::rank())];
  }
  assembler_ = std::make_unique<solver::SparseAssembler>(model_.dofs().offsets(), free_index_,
                                                         std::move(adjacency), rows);
  ++pattern_version_;
}

void EquilibriumProblem::distribute(bool on) {
  const bool was = distributed_;
  distributed_ = on && parallel::size() > 1;
  if (!distributed_) rank_blocks_.clear();
  // The matrix of this rank's rows, or of all of them again.
  if (assembler_ && (distributed_ || was)) make_assembler(assembler_->adjacency());
}

void EquilibriumProblem::split_among_ranks(const solver::BlockAdjacency& adjacency) {
  const int ranks = parallel::size();
  const std::vector<int>& offsets = model_.dofs().offsets();
  // Balanced by the tangent's entries in the blocks' columns (its rows: the pattern is symmetric), which
  // follow the elements and contact elements at the blocks.
  rank_blocks_ = solver::split_blocks(offsets, free_index_, adjacency, ranks);
  const int blocks = static_cast<int>(offsets.size()) - 1;
  rank_dofs_.assign(static_cast<std::size_t>(ranks) + 1, model_.num_dofs());
  rank_rows_.assign(static_cast<std::size_t>(ranks) + 1, size());
  for (int r = 0; r < ranks; ++r) {
    const int first =
        offsets[static_cast<std::size_t>(std::min(rank_blocks_[static_cast<std::size_t>(r)].first, blocks))];
    rank_dofs_[static_cast<std::size_t>(r)] = first;
    // The free rows before unknown `first`.
    rank_rows_[static_cast<std::size_t>(r)] =
        static_cast<int>(std::lower_bound(free_dofs_.begin(), free_dofs_.end(), first) - free_dofs_.begin());
  }
  spdlog::debug(
      "evaluation distributed over {} ranks: rank 0 computes blocks [0, {}), free rows [0, {}) of {}", ranks,
      rank_blocks_.front().last, rank_rows_[1], size());
}

std::pair<int, int> EquilibriumProblem::local_rows() const {
  if (!distributed_) return {-1, -1};
  const auto r = static_cast<std::size_t>(parallel::rank());
  return {rank_rows_[r], rank_rows_[r + 1]};
}

void EquilibriumProblem::share_among_ranks() {
  parallel::share_segments(residual_full_.data(), rank_dofs_);
  // Each contact element's state as the rank that owns particle i's first node computed it (that rank
  // evaluated the element): the others send zeros.
  const solver::BlockRange mine = rank_blocks_[static_cast<std::size_t>(parallel::rank())];
  const std::vector<contact::ContactElement>& elements = contact_->geometry().elements;
  if (elements.empty()) return;
  constexpr std::size_t kValues = 9;  // gap, R_N, tangential (3), reversible (3), slip
  std::vector<double> packed(kValues * elements.size(), 0.0);
  const std::vector<ContactState>& states = contact_->states();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (!mine.contains(model_.element_first_node(elements[k].particle_i.element))) continue;
    const ContactState& c = states[k];
    double* p = packed.data() + kValues * k;
    p[0] = c.gap;
    p[1] = c.normal_reaction;
    for (int d = 0; d < 3; ++d) {
      p[2 + d] = c.tangential[d];
      p[5 + d] = c.reversible[d];
    }
    p[8] = c.slip ? 1.0 : 0.0;
  }
  parallel::sum_over_ranks(packed.data(), packed.size());
  std::vector<ContactState> shared(elements.size());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const double* p = packed.data() + kValues * k;
    shared[k] = {p[0], p[1], Eigen::Vector3d(p[2], p[3], p[4]), Eigen::Vector3d(p[5], p[6], p[7]),
                 p[8] != 0.0};
  }
  contact_->set_states(std::move(shared));
}

Eigen::VectorXd EquilibriumProblem::unknowns() const {
  Eigen::VectorXd u(size());
  for (int i = 0; i < size(); ++i) u[i] = x_[free_dofs_[static_cast<std::size_t>(i)]];
  return u;
}

Eigen::VectorXd EquilibriumProblem::step(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const {
  Eigen::VectorXd next = u + du;
  if (director_update_ == DirectorUpdate::additive) return next;
  for (int node = 0; node < model_.num_nodes(); ++node) {
    // The free indices of g1 and g2 (unknowns 3 to 8 of the node's block); a node with any of them
    // prescribed keeps the additive update.
    const int first = model_.node_dof(node) + 3;
    std::array<int, 6> at{};
    bool free = true;
    for (std::size_t k = 0; k < at.size(); ++k) {
      at[k] = free_index_[static_cast<std::size_t>(first) + k];
      free = free && at[k] >= 0;
    }
    if (!free) continue;
    const auto vec = [&at](const Eigen::VectorXd& v, std::size_t from) {
      return Eigen::Vector3d(v[at[from]], v[at[from + 1]], v[at[from + 2]]);
    };
    const std::array<Eigen::Vector3d, 2> g =
        model::rotate_directors(vec(u, 0), vec(u, 3), vec(du, 0), vec(du, 3));
    for (std::size_t k = 0; k < 3; ++k) {
      next[at[k]] = g[0][static_cast<int>(k)];
      next[at[3 + k]] = g[1][static_cast<int>(k)];
    }
  }
  return next;
}

void EquilibriumProblem::set_unknowns(const Eigen::VectorXd& u) {
  for (int i = 0; i < size(); ++i) x_[free_dofs_[static_cast<std::size_t>(i)]] = u[i];
}

void EquilibriumProblem::evaluate(Eigen::VectorXd& residual, bool with_tangent) {
  solver::SparseAssembler* tangent = with_tangent ? assembler_.get() : nullptr;
  if (tangent) tangent->set_zero();
  residual_full_.setZero(model_.num_dofs());
  const model::TermState state = term_state();
  for (const auto& term : terms_) term->add(state, residual_full_, tangent);
  if (distributed_) share_among_ranks();
  residual.resize(size());
  for (int i = 0; i < size(); ++i) residual[i] = residual_full_[free_dofs_[static_cast<std::size_t>(i)]];
  // Force scale: the applied loads and the support reactions, above the terms' round-off floors, plus the
  // round-off of this evaluation (the drag's grows as 1/dt when steps are cut back).
  double reactions = 0.0;
  for (int i = 0; i < model_.num_dofs(); ++i)
    if (prescribed_[static_cast<std::size_t>(i)]) reactions += residual_full_[i] * residual_full_[i];
  double applied = 0.0, floor = 0.0, roundoff = 0.0;
  for (const auto& term : terms_) {
    const model::ResidualScale s = term->residual_scale();
    applied = std::max(applied, s.applied);
    floor = std::max(floor, s.floor);
    roundoff += s.roundoff;
  }
  residual_tolerance_ =
      std::max(tolerances_.residual * std::max(applied, std::sqrt(reactions)), floor) + roundoff;
}

double EquilibriumProblem::scaled_increment(const Eigen::VectorXd& du) const {
  double largest = 0.0;
  for (int i = 0; i < size(); ++i)
    largest = std::max(
        largest, std::abs(du[i]) /
                     increment_scale_[static_cast<std::size_t>(free_dofs_[static_cast<std::size_t>(i)])]);
  return largest;
}

void EquilibriumProblem::set_time(double t) {
  time_ = t;
  conditions_.apply_prescribed(t, x_);
}

void EquilibriumProblem::commit() {
  if (std::any_of(terms_.begin(), terms_.end(), [](const auto& t) { return t->evaluates_before_commit(); })) {
    Eigen::VectorXd residual;
    evaluate(residual, false);  // the history variables of the converged state
  }
  const model::TermState state = term_state();
  for (const auto& term : terms_) term->commit(state);
  x_committed_ = x_;
  time_committed_ = time_;
  contact_committed_ = {contact_->geometry(), contact_->zone_penalty(), contact_->reversible_committed()};
  contact_changed_ = false;
}

void EquilibriumProblem::restore() {
  x_ = x_committed_;
  time_ = time_committed_;
  // A failed attempt leaves the contact elements of its last detection and the penalties its loop 3
  // adjusted, by up to 1e3 a pass: carried into the next attempt, they compounded over the cutbacks of one
  // step (the double helix at 30 degrees: from 1.4e9 to 7.6e12 N/mm over 8 cutbacks, and a first residual of
  // 2e10 N). The next attempt starts from those of the committed state.
  if (contact_changed_ || contact_->zone_penalty() != contact_committed_.penalty) {
    contact_->set_elements(contact_committed_.geometry, contact_committed_.penalty,
                           contact_committed_.reversible);
    rebuild_pattern();
    contact_changed_ = false;
  }
}

}  // namespace nodus::simulation
