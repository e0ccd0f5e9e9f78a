#include "nodus/simulation/equilibrium_problem.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nodus::simulation {

EquilibriumProblem::EquilibriumProblem(const model::Model& model, loading::Conditions& conditions,
                                       Tolerances tolerances)
    : model_(model),
      conditions_(conditions),
      tolerances_(tolerances),
      x_(model.reference()),
      x_committed_(x_) {
  // Scales: positions by the largest beam length. Forces have a floor at the level of rounding errors in the
  // internal forces: a strain is computed from positions of size |x| differentiated over an element length h,
  // so it carries an error of about eps |x| / h, and each of the n unknowns an error of about E A eps |x| /
  // h. Below that floor no residual can be asked for; above it the relative tolerance applies.
  length_scale_ = 0.0;
  double stiffest = 0.0, shortest = INFINITY;
  for (const beam::Beam& b : model_.beams()) {
    length_scale_ = std::max(length_scale_, b.length());
    shortest = std::min(shortest, b.element_length());
    const beam::ElementProperties p = b.element_properties(1);
    stiffest = std::max(stiffest, p.stiffness(beam::kE33, beam::kE33));
  }
  const double extent = std::max(length_scale_, x_.lpNorm<Eigen::Infinity>());
  force_floor_ = 10.0 * std::numeric_limits<double>::epsilon() * stiffest * (extent / shortest) *
                 std::sqrt(static_cast<double>(model_.num_dofs()));
  element_nodes_ = model_.element_nodes();
  // Each quadratic element of length h gives h/6, 2h/3, h/6 to its nodes (Simpson's rule): the weights of a
  // beam add up to its length.
  // The drag on the directors is that of the section's points averaged over the disc: <xi_a xi_b> = R^2/4
  // delta_ab, so each director takes R^2/4 times the weight of the centre.
  const auto nodes = static_cast<std::size_t>(model_.num_dofs() / model::kDofsPerNode);
  node_length_.assign(nodes, 0.0);
  node_director_length_.assign(nodes, 0.0);
  for (const beam::Beam& b : model_.beams())
    for (int e = 0; e < b.num_elements(); ++e) {
      const double h = b.element_length(), spread = 0.25 * b.radius() * b.radius();
      const double weights[3] = {h / 6.0, 2.0 * h / 3.0, h / 6.0};
      for (int k = 0; k < 3; ++k) {
        const auto n = static_cast<std::size_t>(b.node(2 * e + k));
        node_length_[n] += weights[k];
        node_director_length_[n] += spread * weights[k];
      }
    }
  update_free_set();
}

void EquilibriumProblem::set_contact(contact::ContactGeometry geometry, std::vector<double> penalty,
                                     std::vector<Eigen::Vector3d> reversible) {
  contact_ = std::move(geometry);
  penalty_ = std::move(penalty);
  reversible_committed_ = std::move(reversible);
  contact_states_.assign(contact_.elements.size(), ContactState{});
  rebuild_pattern();
}

ProblemState EquilibriumProblem::saved_state() const {
  return {x_committed_, time_committed_, contact_, penalty_, reversible_committed_, contact_states_};
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
  contact_ = std::move(state.contact);
  penalty_ = std::move(state.penalty);
  reversible_committed_ = std::move(state.reversible);
  contact_states_ = std::move(state.contact_states);
  update_free_set();
}

void EquilibriumProblem::set_contact_laws(double regularization, std::optional<contact::FrictionLaw> friction,
                                          contact::ResponseOptions options) {
  regularization_ = regularization;
  friction_ = friction;
  response_options_ = options;
}

void EquilibriumProblem::add_contact(solver::SparseAssembler* assembler) {
  std::array<int, 6> blocks{};
  for (std::size_t k = 0; k < contact_.elements.size(); ++k) {
    const contact::ContactElement& e = contact_.elements[k];
    const int ei = e.particle_i.element, ej = e.particle_j.element;
    const contact::NormalLaw law{penalty_[static_cast<std::size_t>(e.zone)], regularization_};
    const contact::ContactResponse r = contact::contact_response(
        e, model_.gather(x_, ei), model_.gather(x_, ej), model_.gather(x_committed_, ei),
        model_.gather(x_committed_, ej), law, friction_ ? &*friction_ : nullptr, reversible_committed_[k],
        response_options_);
    contact_states_[k] = {r.gap, r.normal_reaction, r.friction.force, r.friction.reversible, r.friction.slip};
    const std::vector<int>& ni = element_nodes_[static_cast<std::size_t>(ei)];
    const std::vector<int>& nj = element_nodes_[static_cast<std::size_t>(ej)];
    for (int a = 0; a < 3; ++a) {
      blocks[static_cast<std::size_t>(a)] = ni[static_cast<std::size_t>(a)];
      blocks[static_cast<std::size_t>(a + 3)] = nj[static_cast<std::size_t>(a)];
    }
    for (int b = 0; b < 6; ++b)
      residual_full_.segment<model::kDofsPerNode>(model::kDofsPerNode *
                                                  blocks[static_cast<std::size_t>(b)]) +=
          r.force.segment<model::kDofsPerNode>(model::kDofsPerNode * b);
    if (assembler) assembler->add(blocks, r.tangent);
  }
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

void EquilibriumProblem::rebuild_pattern() {
  std::vector<std::vector<int>> groups = element_nodes_;
  for (const contact::ContactElement& e : contact_.elements) {
    std::vector<int> g = element_nodes_[static_cast<std::size_t>(e.particle_i.element)];
    const std::vector<int>& nj = element_nodes_[static_cast<std::size_t>(e.particle_j.element)];
    g.insert(g.end(), nj.begin(), nj.end());
    groups.push_back(std::move(g));
  }
  assembler_ = std::make_unique<solver::SparseAssembler>(model::kDofsPerNode, free_index_, groups);
}

Eigen::VectorXd EquilibriumProblem::unknowns() const {
  Eigen::VectorXd u(size());
  for (int i = 0; i < size(); ++i) u[i] = x_[free_dofs_[static_cast<std::size_t>(i)]];
  return u;
}

void EquilibriumProblem::set_unknowns(const Eigen::VectorXd& u) {
  for (int i = 0; i < size(); ++i) x_[free_dofs_[static_cast<std::size_t>(i)]] = u[i];
}

void EquilibriumProblem::evaluate(Eigen::VectorXd& residual, bool with_tangent) {
  model_.internal_force(x_, f_int_, with_tangent ? assembler_.get() : nullptr);
  f_ext_.setZero(model_.num_dofs());
  conditions_.external_force(time_, x_, f_ext_);
  if (with_tangent) conditions_.add_load_tangent(time_, x_, *assembler_);
  residual_full_ = f_int_ - f_ext_;
  if (!contact_.elements.empty()) {
    add_contact(with_tangent ? assembler_.get() : nullptr);
  }
  add_stabilization(with_tangent ? assembler_.get() : nullptr);
  residual.resize(size());
  for (int i = 0; i < size(); ++i) residual[i] = residual_full_[free_dofs_[static_cast<std::size_t>(i)]];
  // Force scale: the applied loads and the support reactions.
  double reactions = 0.0;
  for (int i = 0; i < model_.num_dofs(); ++i)
    if (prescribed_[static_cast<std::size_t>(i)]) reactions += residual_full_[i] * residual_full_[i];
  // Plus the round-off of the stabilising drag: c (x - x_committed) carries an error of c eps |x| per
  // unknown, which grows as 1/dt when steps are cut back. Without it, a step cut back below 1e-9 of the load
  // time could never converge (|R| stuck at this floor, doubling with every cutback, under 1e-15 increments).
  residual_tolerance_ =
      std::max(tolerances_.residual * std::max(f_ext_.norm(), std::sqrt(reactions)), force_floor_) +
      stabilization_roundoff_;
}

double Stabilization::at(double t) const {
  if (start <= 0.0 || t1 <= t0) return 0.0;
  const double u = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
  if (end > 0.0) return start * std::pow(end / start, u);
  return u >= 1.0 - 1e-12 ? 0.0 : start * std::pow(1e-6, u);
}

void EquilibriumProblem::add_stabilization(solver::SparseAssembler* assembler) {
  stabilization_force_ = 0.0;
  stabilization_roundoff_ = 0.0;
  const double dt = time_ - time_committed_;
  const double eta = stabilization_.at(time_);
  if (eta <= 0.0 || dt <= 0.0) return;
  double squared = 0.0, roundoff = 0.0;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  Eigen::Matrix<double, model::kDofsPerNode, model::kDofsPerNode> k;
  for (std::size_t n = 0; n < node_length_.size(); ++n) {
    const double c = eta * node_length_[n] / dt, c_directors = eta * node_director_length_[n] / dt;
    const int i = model::kDofsPerNode * static_cast<int>(n);
    // Prescribed nodes feel the drag too: their supports carry it (a tool dragged through the same medium).
    Eigen::Matrix<double, model::kDofsPerNode, 1> weight;
    weight << Eigen::Vector3d::Constant(c), Eigen::Matrix<double, 6, 1>::Constant(c_directors);
    const auto drag =
        (weight.array() *
         (x_.segment<model::kDofsPerNode>(i) - x_committed_.segment<model::kDofsPerNode>(i)).array())
            .matrix()
            .eval();
    residual_full_.segment<model::kDofsPerNode>(i) += drag;
    squared += drag.squaredNorm();
    roundoff +=
        (kEps * weight.array() * x_.segment<model::kDofsPerNode>(i).array().abs()).matrix().squaredNorm();
    if (assembler) {
      k = weight.asDiagonal();
      const int block[1] = {static_cast<int>(n)};
      assembler->add(block, k);
    }
  }
  stabilization_force_ = std::sqrt(squared);
  stabilization_roundoff_ = std::sqrt(roundoff);
}

double EquilibriumProblem::scaled_increment(const Eigen::VectorXd& du) const {
  double largest = 0.0;
  for (int i = 0; i < size(); ++i) {
    const bool position = free_dofs_[static_cast<std::size_t>(i)] % model::kDofsPerNode < 3;
    largest = std::max(largest, std::abs(du[i]) / (position ? length_scale_ : 1.0));
  }
  return largest;
}

void EquilibriumProblem::set_time(double t) {
  time_ = t;
  conditions_.apply_prescribed(t, x_);
}

void EquilibriumProblem::commit() {
  if (!contact_.elements.empty()) {
    Eigen::VectorXd residual;
    evaluate(residual, false);  // the contact states of the converged state
    for (std::size_t k = 0; k < contact_states_.size(); ++k)
      reversible_committed_[k] = contact_states_[k].reversible;
  }
  x_committed_ = x_;
  time_committed_ = time_;
  conditions_.commit(x_);
}

void EquilibriumProblem::restore() {
  x_ = x_committed_;
  time_ = time_committed_;
}

}  // namespace nodus::simulation
