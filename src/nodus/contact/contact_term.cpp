#include "nodus/contact/contact_term.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::contact {

RegimeChanges compare_regimes(const std::vector<ContactState>& before, const std::vector<ContactState>& now) {
  if (before.size() != now.size())
    throw std::invalid_argument("compare_regimes: " + std::to_string(before.size()) + " states before, " +
                                std::to_string(now.size()) + " now");
  RegimeChanges changes;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const bool presses = now[k].normal_reaction > 0.0;
    const bool pressed = before[k].normal_reaction > 0.0;
    if (presses != pressed) ++(presses ? changes.entered : changes.left);
    if (now[k].slip != before[k].slip && presses && pressed)
      ++(now[k].slip ? changes.to_slip : changes.to_stick);
  }
  return changes;
}

void ContactTerm::couplings(std::vector<std::vector<int>>& groups) const {
  for (const ContactElement& e : geometry_.elements) {
    const int i = model_.element_first_node(e.particle_i.element);
    const int j = model_.element_first_node(e.particle_j.element);
    groups.push_back({i, i + 1, i + 2, j, j + 1, j + 2});
  }
}

void ContactTerm::set_elements(ContactGeometry geometry, std::vector<double> penalty,
                               std::vector<Eigen::Vector3d> reversible) {
  geometry_ = std::move(geometry);
  penalty_ = std::move(penalty);
  reversible_committed_ = std::move(reversible);
  states_.assign(geometry_.elements.size(), ContactState{});
  // Other elements: the next evaluation is compared with none.
  last_states_.clear();
  compare_ = pending_ = false;
}

void ContactTerm::set_states(std::vector<ContactState> states) {
  states_ = std::move(states);
  if (pending_) note_evaluation();
}

void ContactTerm::reset_regime_changes() {
  changes_ = {};
  last_states_.clear();
  compare_ = pending_ = false;
}

void ContactTerm::set_laws(double regularization, std::optional<FrictionLaw> friction,
                           ResponseOptions options) {
  regularization_ = regularization;
  friction_ = friction;
  options_ = options;
}

void ContactTerm::add(const model::TermState& state, Eigen::VectorXd& residual,
                      solver::SparseAssembler* tangent) {
  // The contact elements with a node among state.blocks (all of them, unless the run is distributed), in
  // order; the others keep their last state.
  const std::size_t count = geometry_.elements.size();
  std::vector<std::size_t> some;
  const bool all = state.blocks.first <= 0 && state.blocks.last >= model_.num_nodes();
  if (!all)
    for (std::size_t k = 0; k < count; ++k) {
      const ContactElement& e = geometry_.elements[k];
      const int ni = model_.element_first_node(e.particle_i.element);
      const int nj = model_.element_first_node(e.particle_j.element);
      for (int n : {ni, ni + 1, ni + 2, nj, nj + 1, nj + 2})
        if (state.blocks.contains(n)) {
          some.push_back(k);
          break;
        }
    }
  const auto element = [&](std::size_t i) { return all ? i : some[i]; };
  const auto compute = [&](std::size_t i, ContactResponse& r) {
    const std::size_t k = element(i);
    const ContactElement& e = geometry_.elements[k];
    const int ei = e.particle_i.element, ej = e.particle_j.element;
    const NormalLaw law{penalty_[static_cast<std::size_t>(e.zone)], regularization_};
    const FrictionLaw* friction = friction_ ? &*friction_ : nullptr;
    FrictionLaw pair;  // the coefficient of the pair of beams (set_pair_friction)
    if (friction && !pair_friction_.empty()) {
      pair = *friction;
      pair.coefficient =
          pair_friction_[static_cast<std::size_t>(e.particle_i.beam * num_beams_ + e.particle_j.beam)];
      friction = pair.coefficient > 0.0 ? &pair : nullptr;
    }
    contact_response(e, model_.gather(state.x, ei), model_.gather(state.x, ej),
                     model_.gather(state.x_committed, ei), model_.gather(state.x_committed, ej), law,
                     friction, reversible_committed_[k], options_, r);
    states_[k] = {r.gap, r.normal_reaction, r.friction.force, r.friction.reversible, r.friction.slip};
  };
  // Each thread adds the entries of its own nodes (blocks), so the sums do not depend on the thread count.
  const auto scatter = [&](std::size_t i, const ContactResponse& r, solver::BlockRange nodes_added) {
    constexpr int kNode = beam::kNodeDofs;
    const ContactElement& e = geometry_.elements[element(i)];
    const int ni = model_.element_first_node(e.particle_i.element);
    const int nj = model_.element_first_node(e.particle_j.element);
    const std::array<int, 6> blocks{ni, ni + 1, ni + 2, nj, nj + 1, nj + 2};
    for (int b = 0; b < 6; ++b)
      if (nodes_added.contains(blocks[static_cast<std::size_t>(b)]))
        residual.segment<kNode>(model_.node_dof(blocks[static_cast<std::size_t>(b)])) +=
            r.force.segment<kNode>(kNode * b);
    if (tangent) tangent->add(blocks, r.tangent, nodes_added);
  };
  const auto split = [&](int parts) {
    return tangent ? tangent->split_columns(parts) : solver::even_split(model_.dofs().num_blocks(), parts);
  };
  assembly_.run(all ? count : some.size(), compute, scatter, split);
  // A distributed evaluation computed this rank's elements only: it is counted when set_states() brings the
  // others' (EquilibriumProblem::share_among_ranks), so that every rank counts the same changes.
  pending_ = !all;
  if (all) note_evaluation();
}

void ContactTerm::note_evaluation() {
  pending_ = false;
  // Which elements changed regime since the last evaluation of the same elements: a Newton solve whose
  // residual wanders while elements keep entering and leaving contact, or sticking and slipping, shows it
  // here (steps.csv sums them over the step).
  const bool compare = compare_ && last_states_.size() == states_.size();
  const RegimeChanges changes = compare ? compare_regimes(last_states_, states_) : RegimeChanges{};
  changes_ += changes;
  if (spdlog::should_log(spdlog::level::debug)) {
    int pressing = 0, slipping = 0, reversed = 0;
    for (std::size_t k = 0; k < states_.size(); ++k) {
      const ContactState& now = states_[k];
      pressing += now.normal_reaction > 0.0;
      slipping += now.slip;
      // Slipping at both evaluations, against the direction of the last: across the stick band in one
      // iteration.
      if (compare && now.slip && last_states_[k].slip && now.tangential.dot(last_states_[k].tangential) < 0.0)
        ++reversed;
    }
    spdlog::debug(
        "contact: {} of {} elements pressing ({} entered, {} left), {} slipping (pressing before and "
        "after: {} began, {} stuck; {} slip the other way)",
        pressing, states_.size(), changes.entered, changes.left, slipping, changes.to_slip, changes.to_stick,
        reversed);
  }
  last_states_ = states_;
  compare_ = true;
}

void ContactTerm::commit(const model::TermState& /*state*/) {
  for (std::size_t k = 0; k < states_.size(); ++k) reversible_committed_[k] = states_[k].reversible;
}

}  // namespace nodus::contact
