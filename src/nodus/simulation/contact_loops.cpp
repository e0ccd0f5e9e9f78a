#include "nodus/simulation/contact_loops.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/beam/beam_element.hpp"
#include "nodus/contact/history_transfer.hpp"

namespace nodus::simulation {
namespace {

/// Loop 2 stops after the Newton solve that follows a detection whose new contact elements leave an
/// out-of-balance force below this fraction of the total normal force. Re-detections on parallel contact
/// lines move the particles by fractions of their spacing and redistribute the line load at the 1e-5 to 1e-3
/// level (double helix: 2e-6 to 4e-5 N against 0.04 N); with the residual tolerance alone (4e-9 N) loop 2
/// used all its detections in every step.
constexpr double kSetTolerance = 1e-3;

/// A converged step whose largest penetration exceeds this many p_max is rejected (cut back).
constexpr double kMaxPenetrationRatio = 10.0;
/// A converged step is also rejected where a detection of its state finds a penetration beyond this many
/// p_max and beyond twice the largest of its own contact elements: a surface that the last Newton solve
/// carried into another where no contact element held it.
constexpr double kMaxUnseenPenetrationRatio = 4.0;
/// The smallest penalty the adjustment of loop 3 gives a zone, as a fraction of the initial one.
constexpr double kPenaltyFloor = 1e-4;

/// Loop 3 inside Newton updates the normals between iterations once |R| has fallen below this fraction of
/// the total normal force (docs/contact.md, "Loop 3 inside Newton").
constexpr double kNormalUpdateRatio = 1e-3;

/// The sum of R_N over the contact elements, at the last evaluation.
double total_normal_force(const std::vector<ContactState>& states) {
  double sum = 0.0;
  for (const ContactState& c : states) sum += c.normal_reaction;
  return sum;
}

/// Adds the Newton solve `r` to the step's `total`; false, with its failure, if it did not converge.
bool add_solve(solver::NewtonReport& total, const solver::NewtonReport& r) {
  total.iterations += r.iterations;
  total.longest_solve = std::max(total.longest_solve, r.iterations);
  total.residual = r.residual;
  total.residual_tolerance = r.residual_tolerance;
  total.increment = r.increment;
  if (r.converged) return true;
  total.failure = r.failure;
  total.cancelled = r.cancelled;
  return false;
}

}  // namespace

double worst_zone_imbalance(const std::vector<contact::ContactElement>& elements,
                            const std::vector<ContactState>& states,
                            const std::function<int(int)>& first_node, const Eigen::VectorXd& residual,
                            const std::function<bool(int)>& prescribed) {
  int num_zones = 0;
  for (const contact::ContactElement& e : elements) num_zones = std::max(num_zones, e.zone + 1);
  std::vector<double> force(static_cast<std::size_t>(num_zones), 0.0);
  std::vector<std::vector<int>> nodes(static_cast<std::size_t>(num_zones));
  for (std::size_t e = 0; e < elements.size() && e < states.size(); ++e) {
    const auto z = static_cast<std::size_t>(elements[e].zone);
    force[z] += states[e].normal_reaction;
    for (const int element : {elements[e].particle_i.element, elements[e].particle_j.element})
      for (int k = 0; k < beam::kElementNodes; ++k) nodes[z].push_back(first_node(element) + k);
  }
  double worst = 0.0;
  for (std::size_t z = 0; z < nodes.size(); ++z) {
    if (!(force[z] > 0.0)) continue;
    std::sort(nodes[z].begin(), nodes[z].end());
    nodes[z].erase(std::unique(nodes[z].begin(), nodes[z].end()), nodes[z].end());
    double sum = 0.0;
    for (const int node : nodes[z])
      for (int d = beam::kNodeDofs * node; d < beam::kNodeDofs * (node + 1); ++d)
        if (!prescribed(d)) sum += residual[d] * residual[d];
    worst = std::max(worst, std::sqrt(sum) / force[z]);
  }
  return worst;
}

ContactLoops::ContactLoops(const model::Model& model, EquilibriumProblem& problem,
                           solver::NewtonSolver& newton, contact::DetectionParameters detection,
                           std::vector<int> beams, ContactLawSettings laws)
    : model_(model),
      problem_(problem),
      newton_(newton),
      detection_(detection),
      beams_(std::move(beams)),
      laws_(laws) {
  problem_.set_contact_laws(
      laws_.regularization, laws_.friction,
      {laws_.facing_particles, laws_.friction_normal_coupling, false, laws_.centre_facing});
  problem_.set_contact_pair_friction(laws_.pair_friction, static_cast<int>(model_.beams().size()));
}

contact::Clearance ContactLoops::clearance() const {
  if (beams_.empty()) return {};
  const contact::DetectionParameters prm = contact::resolve_parameters(detection_, model_, beams_);
  int elements = 0;
  for (int b : beams_) elements += model_.beam(b).num_elements();
  const bool parallel = elements >= 1000;  // as detection: below, waking the threads costs more
  return contact::min_clearance(model_, problem_.state(), beams_, prm.separation_distance,
                                prm.proximity_distance, 9, parallel);
}

std::optional<contact::Crossing> ContactLoops::crossing() const {
  if (!laws_.crossing_guard || beams_.empty()) return std::nullopt;
  const contact::DetectionParameters prm = contact::resolve_parameters(detection_, model_, beams_);
  int elements = 0;
  for (int b : beams_) elements += model_.beam(b).num_elements();
  return contact::find_crossing(model_, problem_.committed_state(), problem_.state(), beams_,
                                prm.separation_distance, elements >= 1000);
}

contact::ContactGeometry ContactLoops::detect() {
  if (beams_.empty()) return {};
  const auto start = std::chrono::steady_clock::now();
  contact::ContactGeometry g =
      contact::detect(model_, problem_.state(), detection_, beams_, &problem_.contact_geometry());
  detection_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return g;
}

void ContactLoops::install(contact::ContactGeometry next) {
  replaced_normal_force_ = total_normal_force(problem_.contact_states());
  const contact::ContactGeometry& old = problem_.contact_geometry();
  const double reach = contact::resolve_parameters(detection_, model_, beams_).separation_distance;
  std::vector<double> penalty =
      contact::transfer_penalties(old, problem_.zone_penalty(), next, laws_.penalty, reach);
  std::vector<Eigen::Vector3d> reversible =
      contact::transfer_reversible(old, problem_.reversible_committed(), next, reach);
  // Newton analyses the tangent again if the pattern changed (EquilibriumProblem::pattern_version).
  problem_.set_contact(std::move(next), std::move(penalty), std::move(reversible));
}

double ContactLoops::update_normals() {
  double turn = 0.0;
  largest_turn_element_ = -1;
  std::vector<contact::ContactElement>& elements = problem_.contact_geometry().elements;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    contact::ContactElement& e = elements[k];
    const Eigen::Vector3d before = e.normal;
    if (!contact::update_normal(model_, problem_.state(), e, laws_.facing_particles, laws_.centre_facing))
      continue;
    const double angle = std::atan2(before.cross(e.normal).norm(), before.dot(e.normal));
    if (angle > turn) {
      turn = angle;
      largest_turn_element_ = static_cast<int>(k);
    }
  }
  return turn;
}

std::string ContactLoops::largest_turn_where() const {
  const contact::ContactGeometry& g = problem_.contact_geometry();
  if (largest_turn_element_ < 0 || static_cast<std::size_t>(largest_turn_element_) >= g.elements.size())
    return "no element";
  const contact::ContactElement& e = g.elements[static_cast<std::size_t>(largest_turn_element_)];
  const contact::ProximityZone& zone = g.zones[static_cast<std::size_t>(e.zone)];
  return fmt::format(
      "element {} (zone {}, beams {} at s = {:.4f} mm and {} at s = {:.4f} mm, gap {:.2e} mm, "
      "parallel weight {:.2f})",
      largest_turn_element_, e.zone, model_.beam(zone.beam_i).name(), e.particle_i.abscissa,
      model_.beam(zone.beam_j).name(), e.particle_j.abscissa, e.gap, e.parallel_weight);
}

bool ContactLoops::adjust_penalties() {
  const contact::ContactGeometry& g = problem_.contact_geometry();
  std::vector<double>& penalty = problem_.zone_penalty();
  const contact::NormalLaw unit{1.0, laws_.regularization};
  // Aim at 3/4 of p_max; a zone whose penetration lies in [p_max / 2, p_max] is left as it is.
  const double aim = 0.75 * laws_.max_penetration;
  const double target = contact::normal_reaction(unit, -aim);
  bool off = false;
  for (std::size_t z = 0; z < g.zones.size(); ++z) {
    const contact::ProximityZone& zone = g.zones[z];
    double penetration = 0.0;
    for (int k = zone.first_element; k < zone.first_element + zone.num_elements; ++k)
      penetration = std::max(penetration, -g.elements[static_cast<std::size_t>(k)].gap);
    // A zone that only touches (penetration below p_max / 1000: a surface resting on another, no load yet)
    // is left alone: matching the aim would divide its penalty by 10 at every pass, leaving it soft for the
    // load to come.
    if (!(penetration > 1e-3 * laws_.max_penetration)) continue;
    if (penetration >= 0.5 * laws_.max_penetration && penetration <= laws_.max_penetration) continue;
    // Eq. 54, in the direction that makes the penetration approach the aim: the new coefficient gives at the
    // aim the reaction the old one gives at the penetration reached (the law is linear in k_c).
    const double factor = std::clamp(contact::normal_reaction(unit, -penetration) / target, 1e-3, 1e3);
    // Not below kPenaltyFloor of the initial penalty: a zone pressed by the kinematics rather than by a load
    // (fibres of a yarn that the twist brings together) keeps its penetration as the penalty falls, and Eq.
    // 54 would divide it by up to 1e3 at every pass, to 1e-25 of the initial value within a few steps, after
    // which the surfaces pass through each other (docs/contact.md). A zone held at the floor is settled.
    const double adjusted = std::max(penalty[z] * factor, kPenaltyFloor * laws_.penalty);
    if (adjusted == penalty[z]) continue;
    off = true;
    penalty[z] = adjusted;
  }
  return off;
}

void ContactLoops::collect_stats() {
  const std::vector<ContactState>& states = problem_.contact_states();
  stats_.normal_force = stats_.tangential_force = stats_.penetration_ratio = 0.0;
  stats_.slipping = 0;
  for (const ContactState& s : states) {
    stats_.normal_force += s.normal_reaction;
    stats_.tangential_force += s.tangential.norm();
    stats_.penetration_ratio = std::max(stats_.penetration_ratio, -s.gap / laws_.max_penetration);
    if (s.slip) ++stats_.slipping;
  }
}

bool ContactLoops::solve_normals_nested(solver::NewtonReport& total, bool last) {
  for (int m = 1;; ++m) {
    ++stats_.normal_iterations;
    // A solve whose state only serves to update the normals and penalties may stop short of the residual
    // tolerance (contact.normal_pass_residual); the solve that ends the loop goes on to it, below.
    double pass_residual = 0.0;
    // The normal force at the last evaluation: of the state the solve starts from. Right after a detection
    // the new contact elements carry no reactions until Newton evaluates them (install() zeroes them); the
    // elements they replaced give that state's force then.
    if (laws_.normal_pass_residual > 0.0) {
      const double force = total_normal_force(problem_.contact_states());
      pass_residual = laws_.normal_pass_residual * (force > 0.0 ? force : replaced_normal_force_);
    }
    // Linearized normals: Newton starts with the normals as loop 3 left them (far from equilibrium, where the
    // iterates overshoot, normals that follow them turn the contact forces with them and the follower
    // force's tangent, not definite, sends Newton further away), and lets them follow the state, with their
    // derivative in the tangent, once |R| is below kNormalUpdateRatio of the total normal force.
    bool following = false;
    const solver::FixedPointUpdate follow = [&](const solver::NewtonProgress& p) {
      if (following || p.converged) return false;
      if (!(p.residual <= kNormalUpdateRatio * total_normal_force(problem_.contact_states()))) return false;
      problem_.set_contact_normals_follow(true);
      following = true;
      return true;
    };
    const auto solve = [&](double loose) {
      following = false;
      const solver::NewtonReport r =
          newton_.solve(problem_, laws_.linearized_normals ? follow : solver::FixedPointUpdate{}, loose);
      problem_.set_contact_normals_follow(false);
      return r;
    };
    const solver::NewtonReport pass = solve(pass_residual);
    if (!add_solve(total, pass)) return false;
    // The state the loop ends in: to the residual tolerance, or, where a detection follows in this step and
    // passes are short, as short as a pass (the next detection's elements are solved for again).
    const bool at_tolerance = (pass.residual <= problem_.residual_tolerance() &&
                               pass.increment <= problem_.increment_tolerance()) ||
                              (!last && pass_residual > 0.0 && pass.residual <= pass_residual);
    const contact::ContactGeometry kept = problem_.contact_geometry();
    const std::vector<double> kept_penalty = problem_.zone_penalty();
    const double turn = update_normals();
    const bool off = adjust_penalties();
    // Where the normals followed the state, Newton solved with the normals of its iterates, and the update
    // only brings the stored normals (those written out) to the state: their turn since the last update is
    // no reason to solve again.
    const bool converged = (following || turn <= laws_.normal_tolerance) && !off;
    if (converged || m >= laws_.max_normal_iterations) {
      // Converged: the state is the equilibrium of these normals and penalties (to the tolerance, or short
      // of it before a further detection). At the cap: keep those Newton converged with too, and say
      // whether the update would still have changed them.
      if (!following) problem_.contact_geometry() = kept;
      problem_.zone_penalty() = kept_penalty;
      stats_.normals_capped = !converged;
      // The state must be the equilibrium of the normals and penalties kept: to the residual tolerance, or,
      // before a further detection, to the pass's bound.
      if (!at_tolerance && !add_solve(total, solve(last ? 0.0 : pass_residual))) return false;
      if (!converged)
        spdlog::debug(
            "contact loop 3: stopped at max_normal_iterations = {}; normals would still turn by "
            "up to {:.2e} rad{}",
            laws_.max_normal_iterations, turn, off ? ", and penalties would still be adjusted" : "");
      return true;
    }
    if (spdlog::should_log(spdlog::level::debug))
      spdlog::debug("contact loop 3: normals turned by up to {:.2e} rad, most at {}{}", turn,
                    largest_turn_where(), off ? "; penalties adjusted" : "");
  }
}

bool ContactLoops::solve_normals_inside_newton(solver::NewtonReport& total) {
  // Updates that changed the problem, on the way and at converged states together: at most
  // max_normal_iterations - 1, as in the nested loop (a normal that flips between two directions would
  // otherwise keep Newton from converging).
  int updates = 0;
  bool capped = false;
  const solver::FixedPointUpdate update = [&](const solver::NewtonProgress& p) {
    const bool last = updates + 1 >= laws_.max_normal_iterations;
    if (!p.converged) {
      // On the way: the normals follow the iterates once they are near equilibrium (updating them far from
      // it turns them by the iterates' overshoots). Only a turn beyond the tolerance is taken: smaller ones,
      // which the nested loop accepts, would hold Newton to the linear convergence of the fixed point.
      if (last) return false;
      if (!(p.residual <= kNormalUpdateRatio * total_normal_force(problem_.contact_states()))) return false;
      const contact::ContactGeometry kept = problem_.contact_geometry();
      if (update_normals() > laws_.normal_tolerance) {
        ++updates;
        return true;
      }
      problem_.contact_geometry() = kept;
      return false;
    }
    // At a converged state, as the nested loop after each solve.
    const contact::ContactGeometry kept = problem_.contact_geometry();
    const std::vector<double> kept_penalty = problem_.zone_penalty();
    const double turn = update_normals();
    const bool off = adjust_penalties();
    const bool settled = turn <= laws_.normal_tolerance && !off;
    if (settled || last) {
      capped = !settled;
      if (capped)
        spdlog::debug(
            "contact loop 3: stopped at max_normal_iterations = {}; normals would still turn by "
            "up to {:.2e} rad{}",
            laws_.max_normal_iterations, turn, off ? ", and penalties would still be adjusted" : "");
      problem_.contact_geometry() = kept;
      problem_.zone_penalty() = kept_penalty;
      return false;
    }
    ++updates;
    if (spdlog::should_log(spdlog::level::debug))
      spdlog::debug("contact loop 3: at a converged state normals turned by up to {:.2e} rad, most at {}{}",
                    turn, largest_turn_where(), off ? "; penalties adjusted" : "");
    return true;
  };
  const solver::NewtonReport r = newton_.solve(problem_, update);
  stats_.normal_iterations += updates + 1;
  stats_.normals_capped = capped;
  return add_solve(total, r);
}

solver::NewtonReport ContactLoops::solve() {
  stats_ = ContactStepStats{};
  solver::NewtonReport total;
  install(detect());
  // A run resumed at this step starts with an analysis: where the solver's analysis is given the values
  // (UMFPACK), every step attempt starts with one, so that the resumed run repeats the one never stopped.
  // Otherwise, and for loop 2's further detections, the analysis is kept with the pattern
  // (EquilibriumProblem::pattern_version).
  newton_.restart();
  stats_.detections = 1;
  bool settled = false;  // the last detection changed the contact forces by less than kSetTolerance
  // With short passes of the nested loop 3, the solves before a further detection stop short too: only the
  // state after the step's last detection must be the equilibrium to the residual tolerance, and loop 2
  // judges what the new elements change in the residual rather than the residual itself.
  const bool short_before_detection = !laws_.normals_inside_newton && laws_.normal_pass_residual > 0.0;
  for (;;) {
    const bool last = settled || stats_.detections >= laws_.max_detections;
    const bool solved = laws_.normals_inside_newton
                            ? solve_normals_inside_newton(total)
                            : solve_normals_nested(total, last || !short_before_detection);
    if (!solved) return total;
    if (settled) break;
    if (stats_.detections >= laws_.max_detections) {
      // At the cap before the set of contact elements settled: unless no beam takes part in contact, where
      // every detection finds nothing.
      stats_.detections_capped = !beams_.empty();
      break;
    }
    // Loop 2: a new detection in the converged state. The set of contact elements has converged when the
    // new set changes the contact forces by little: the state is in equilibrium with it to the residual
    // tolerance (Newton would stop at once: done), or to kSetTolerance of the total normal force (one more
    // Newton solve with the new set, and no further detection).
    Eigen::VectorXd before;  // the residual with the elements replaced, where the state is short of balance
    if (short_before_detection) before = problem_.full_residual();
    install(detect());
    ++stats_.detections;
    Eigen::VectorXd residual;
    problem_.evaluate(residual, false);
    if (residual.norm() <= problem_.residual_tolerance()) break;
    Eigen::VectorXd change = problem_.full_residual();
    double change_norm = residual.norm();
    if (before.size() == change.size()) {
      change -= before;
      double sum = 0.0;
      for (Eigen::Index d = 0; d < change.size(); ++d)
        if (!problem_.prescribed(static_cast<int>(d))) sum += change[d] * change[d];
      change_norm = std::sqrt(sum);
    }
    const double zone_imbalance = worst_zone_imbalance(
        problem_.contact_geometry().elements, problem_.contact_states(),
        [this](int element) { return model_.element_first_node(element); }, change,
        [this](int dof) { return problem_.prescribed(dof); });
    settled = change_norm <= kSetTolerance * total_normal_force(problem_.contact_states()) &&
              zone_imbalance <= kSetTolerance;
    spdlog::debug(
        "contact loop 2: |R| = {:.3e} with the new contact elements, changed by {:.3e} (tolerance {:.1e}; "
        "{:.1e} of the normal force, overall and in every zone, the worst zone at {:.1e}: {})",
        residual.norm(), change_norm, problem_.residual_tolerance(), kSetTolerance, zone_imbalance,
        settled ? "settled" : "not settled");
  }
  collect_stats();  // Newton's last evaluation was at the converged state, with these contact elements
  // A state that converged with a penetration far beyond p_max is not a contact state: loop 3 stopped before
  // the penalties caught up, or the surfaces are passing through each other (in the tightened knot a step was
  // accepted at 146 p_max, 0.29 mm with R = 0.1 mm, and the rod came out of its knot). The step is cut back.
  if (stats_.penetration_ratio > kMaxPenetrationRatio) {
    total.failure = fmt::format("penetration {:.3g} times max_penetration (more than {:g})",
                                stats_.penetration_ratio, kMaxPenetrationRatio);
    return total;
  }
  // The contact elements come from the detection before the last Newton solve. A solve that moves the beams
  // far (a knot sliding open by a large step as its drag fades) may carry a surface into another where no
  // element holds it: in the 150-element knot's release, with the line search, the axes came 0.178 mm close,
  // 11 p_max of overlap, while no contact element penetrated by more than 1.5 p_max. A detection of the
  // converged state sees it (one detection: about 1 % of a Newton iteration on the knot); the step is cut
  // back.
  // Each detected element's overlap is measured along its normal (-gap) and along the line of its sections'
  // centres (contact::centre_overlap), which does not depend on the normal: where two beams turn by a large
  // angle against each other within a step, the cross-product normal of the new detection may be oriented so
  // that a deep overlap shows a positive gap (in the 3x1 knot's threading two fibres went from 0.1105 to
  // 0.067 and 0.015 mm between axes, 2R = 0.113 mm, their elements showing gaps of +0.022 to +0.027 mm).
  if (!beams_.empty()) {
    double unseen = 0.0;
    for (const contact::ContactElement& e : detect().elements) {
      unseen = std::max(unseen, -e.gap / laws_.max_penetration);
      unseen = std::max(unseen, contact::centre_overlap(model_, problem_.state(), e) / laws_.max_penetration);
    }
    if (unseen > kMaxUnseenPenetrationRatio && unseen > 2.0 * stats_.penetration_ratio) {
      total.failure = fmt::format(
          "a detection of the converged state finds a penetration of {:.3g} times max_penetration where its "
          "contact elements reach {:.3g} (more than {:g} and twice as much): a surface passing through",
          unseen, stats_.penetration_ratio, kMaxUnseenPenetrationRatio);
      return total;
    }
  }
  total.converged = true;
  return total;
}

}  // namespace nodus::simulation
