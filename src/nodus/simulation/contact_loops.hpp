#pragma once
/// The contact loops of the global algorithm [Durville 2012, Sect. 6] around Newton, for one load step:
///
///     loop 2  determination of the contact elements (detection, fixed point on the set of elements)
///       loop 3  determination of the normal directions (fixed point), with the penalty adjusted per zone
///         Newton-Raphson with the contact elements, their particles and normals fixed
///
/// Between detections the reversible tangential displacements and the penalty coefficients are carried from
/// the old contact elements and zones to the new ones (Sect. 5.2.3).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "nodus/contact/clearance.hpp"
#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/crossing.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/newton.hpp"

namespace nodus::simulation {

struct ContactLawSettings {
  double penalty = 0.0;          ///< initial k_c of a new zone [N/mm]
  double max_penetration = 0.0;  ///< p_max [mm]
  double regularization = 0.0;   ///< p_reg [mm]
  std::optional<contact::FrictionLaw> friction;
  /// With `friction`: its coefficient per pair of beams, [i * num_beams + j] for beams i and j of the model
  /// (contact.friction_pairs); empty: friction->coefficient for every pair.
  std::vector<double> pair_friction;
  /// Linearise friction with R_N varying (a non-symmetric tangent, needs an LU solver;
  /// contact.friction_tangent: varying); false: R_N held fixed in the friction tangent (symmetric).
  bool friction_normal_coupling = false;
  /// Particles at the facing points of the sections (contact.particles: facing); false: fixed particles.
  bool facing_particles = false;
  /// With facing_particles: facing along the centres' direction (contact.particles: centres).
  bool centre_facing = false;
  int max_detections = 4;
  /// Loop 3 inside Newton (contact.normal_updates: inside_newton): the normals are updated between Newton
  /// iterations once the residual has fallen below kNormalUpdateRatio of the total normal force, and at each
  /// converged state, the penalties only there; false: the paper's nested loop, a Newton solve to convergence
  /// after every update.
  bool normals_inside_newton = false;
  /// The normals become functions of the state, linearised in the tangent, within each Newton solve of the
  /// nested loop once |R| is below kNormalUpdateRatio of the total normal force (contact.normal_updates:
  /// linearized; not symmetric, needs an LU solver). A solve in which they did ends loop 3 unless a penalty
  /// is adjusted.
  bool linearized_normals = false;
  int max_normal_iterations = 6;
  double normal_tolerance = 1e-3;  ///< [rad]
  /// Nested loop 3: the Newton solves between updates stop at |R| <= this fraction of the total normal force
  /// (contact.normal_pass_residual); 0: each to the residual tolerance.
  double normal_pass_residual = 0.0;
  /// Refuse a converged step in which two axes crossed (contact.crossing_guard; ContactLoops::crossing()).
  bool crossing_guard = true;
};

/// What the loops did in the last step, and the contact forces at its end.
struct ContactStepStats {
  int detections = 0;  ///< loop 2 iterations
  /// Loop 3 iterations, summed over the detections: the Newton solves (nested), or the updates of the normals
  /// at converged states (inside Newton).
  int normal_iterations = 0;
  /// Loop 2 stopped at max_detections without its criterion (the set of contact elements settled) met.
  bool detections_capped = false;
  /// The last loop 3 of the step stopped at max_normal_iterations with normals that a further update would
  /// still turn by more than normal_tolerance, or penalties that it would still adjust.
  bool normals_capped = false;
  double penetration_ratio = 0.0;  ///< largest penetration / p_max over all zones
  double normal_force = 0.0;       ///< sum of R_N over the contact elements [N]
  double tangential_force = 0.0;   ///< sum of |R_T| [N]
  int slipping = 0;                ///< contact elements sliding

  /// Both loops ended by their criteria, not at their caps.
  bool loops_converged() const { return !detections_capped && !normals_capped; }
};

/// Loop 2 judges a new set of contact elements per proximity zone as well as globally: one global number can
/// hide a zone far from balance among thousands. Returns the largest, over the zones whose elements press, of
/// the out-of-balance force on the free unknowns of the zone's beam elements over the zone's normal force (0
/// if no zone presses). Zones that share beam elements share those unknowns; an unknown counts once per zone.
/// `first_node(e)` is the first node of beam element e (its three nodes are consecutive, nine unknowns each,
/// beam nodes first), `residual` covers all unknowns and `prescribed(dof)` says which it leaves out.
double worst_zone_imbalance(const std::vector<contact::ContactElement>& elements,
                            const std::vector<ContactState>& states,
                            const std::function<int(int)>& first_node, const Eigen::VectorXd& residual,
                            const std::function<bool(int)>& prescribed);

class ContactLoops {
 public:
  /// `beams`: the beams in contact, listed (none: no contact).
  ContactLoops(const model::Model& model, EquilibriumProblem& problem, solver::NewtonSolver& newton,
               contact::DetectionParameters detection, std::vector<int> beams, ContactLawSettings laws);

  /// The beams that take part in contact from the next step on (none: no contact).
  void set_beams(std::vector<int> beams) { beams_ = std::move(beams); }
  /// Where the contact forces act from the next evaluation on, and where detection and the normal updates
  /// place the particles (ContactLawSettings::facing_particles, centre_facing; stages[].particles).
  void set_particles(bool facing, bool centre_facing) {
    laws_.facing_particles = facing;
    laws_.centre_facing = centre_facing;
    problem_.set_contact_particles(facing, centre_facing);
  }
  /// Solves the current load step of `problem_` from its current unknowns.
  solver::NewtonReport solve();
  const ContactStepStats& stats() const { return stats_; }
  /// The smallest clearance between the surfaces of the contact beams in the current state
  /// (contact::min_clearance, pairs within delta_prox, one beam's parts more than delta_separ apart).
  contact::Clearance clearance() const;
  /// Whether the axes of the contact beams crossed between the committed state and the current one
  /// (contact::find_crossing, one beam's parts more than delta_separ apart); nothing if the guard is off.
  std::optional<contact::Crossing> crossing() const;
  double detection_seconds() const { return detection_seconds_; }

 private:
  /// Loop 3, nested: Newton solves to convergence with the normals and penalties fixed, updated between
  /// them. Adds to `total`; returns false if a Newton solve failed. `last`: no detection follows in this
  /// step, and the state must be the equilibrium to the residual tolerance; otherwise, with short passes
  /// (contact.normal_pass_residual), the solve that ends the loop may stop short as the others do.
  bool solve_normals_nested(solver::NewtonReport& total, bool last);
  /// Loop 3 inside one Newton solve (ContactLawSettings::normals_inside_newton).
  bool solve_normals_inside_newton(solver::NewtonReport& total);
  /// A detection in the current state (timed).
  contact::ContactGeometry detect();
  /// Makes `next` the contact elements, with penalties and history carried over from the current ones.
  void install(contact::ContactGeometry next);
  /// Updates the normals in the current state; returns the largest turn [rad]. Costs O(contact elements):
  /// each update reads only the two beam elements that carry its particles.
  double update_normals();
  /// For the debug log: where the last update_normals() turned a normal most, as "element K (zone Z, beams
  /// I at s = ... mm and J at s = ... mm, gap ..., parallel weight ...)".
  std::string largest_turn_where() const;
  /// Adjusts the penalty of each zone whose largest penetration is outside [p_max / 2, p_max] so that it
  /// approaches 3/4 p_max (Eq. 54); returns true if it adjusted one.
  bool adjust_penalties();
  void collect_stats();

  const model::Model& model_;
  EquilibriumProblem& problem_;
  int largest_turn_element_ = -1;  ///< of the last update_normals(); -1: none turned
  solver::NewtonSolver& newton_;
  contact::DetectionParameters detection_;
  std::vector<int> beams_;
  ContactLawSettings laws_;
  ContactStepStats stats_;
  double detection_seconds_ = 0.0;
  /// The sum of R_N of the contact elements that install() replaced, at their last evaluation [N]: the
  /// normal force of the state a solve starts from while the new elements have not been evaluated yet.
  double replaced_normal_force_ = 0.0;
};

}  // namespace nodus::simulation
