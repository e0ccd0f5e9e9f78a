#pragma once
/// Contact-friction as a term of the equilibrium [Durville 2012, Sect. 5 and Eq. 8]: the forces of the
/// contact elements (normal penalty law, regularised Coulomb friction; contact_mechanics.hpp) with their
/// normals and particles fixed, as the contact loops set them, and their tangent. It carries the history of
/// friction: the committed reversible displacement of each element.

#include <optional>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"
#include "nodus/model/term.hpp"
#include "nodus/solver/ordered_assembly.hpp"

namespace nodus::contact {

/// The state of one contact element at the last evaluation.
struct ContactState {
  double gap = 0.0;                                      ///< [mm]
  double normal_reaction = 0.0;                          ///< R_N [N]
  Eigen::Vector3d tangential = Eigen::Vector3d::Zero();  ///< friction force on J [N]
  Eigen::Vector3d reversible = Eigen::Vector3d::Zero();  ///< g_rev [mm]
  bool slip = false;
};

/// Changes of regime of contact elements between evaluations (counts).
struct RegimeChanges {
  int entered = 0;   ///< elements that began to press (R_N > 0 after R_N = 0)
  int left = 0;      ///< elements that stopped pressing (R_N = 0 after R_N > 0)
  int to_slip = 0;   ///< elements pressing at both evaluations that went from stick to slip
  int to_stick = 0;  ///< elements pressing at both evaluations that went from slip to stick

  RegimeChanges& operator+=(const RegimeChanges& other) {
    entered += other.entered;
    left += other.left;
    to_slip += other.to_slip;
    to_stick += other.to_stick;
    return *this;
  }
  bool operator==(const RegimeChanges&) const = default;
};

/// The changes of regime from `before` to `now`, the states of the same contact elements (element k in both)
/// at two successive evaluations. Pressing: R_N > 0. Stick and slip changes are counted for elements that
/// press at both evaluations only (one that leaves contact stops slipping). Throws std::invalid_argument if
/// the two differ in size.
RegimeChanges compare_regimes(const std::vector<ContactState>& before, const std::vector<ContactState>& now);

class ContactTerm final : public model::Term {
 public:
  explicit ContactTerm(const model::Model& model) : model_(model) {}

  std::string_view name() const override { return "contact-friction"; }
  /// The nodes of both elements of every contact element.
  void couplings(std::vector<std::vector<int>>& groups) const override;
  /// The elements are evaluated on all threads and added up in element order: the sums do not depend on the
  /// number of threads.
  void add(const model::TermState& state, Eigen::VectorXd& residual,
           solver::SparseAssembler* tangent) override;
  bool evaluates_before_commit() const override { return !geometry_.elements.empty(); }
  /// The reversible displacements of the converged state become the committed ones.
  void commit(const model::TermState& state) override;

  /// Replaces the contact elements; `penalty` per zone [N/mm], `reversible` per element (committed g_rev).
  /// The couplings change: the problem must rebuild its pattern.
  void set_elements(ContactGeometry geometry, std::vector<double> penalty,
                    std::vector<Eigen::Vector3d> reversible);
  /// The laws: p_reg of the normal law [mm], and friction (none: frictionless).
  void set_laws(double regularization, std::optional<FrictionLaw> friction, ResponseOptions options = {});

  /// Friction coefficients per pair of beams, `coefficients[i * num_beams + j]` for beams i and j, in place
  /// of the law's own (set_laws; with a law only); empty: the law's for every pair.
  void set_pair_friction(std::vector<double> coefficients, int num_beams) {
    // The table is built from the scenario's beams and read with the model's beam indices.
    if (!coefficients.empty() &&
        coefficients.size() != static_cast<std::size_t>(num_beams) * static_cast<std::size_t>(num_beams))
      throw std::invalid_argument("ContactTerm::set_pair_friction: expected num_beams^2 coefficients");
    pair_friction_ = std::move(coefficients);
    num_beams_ = num_beams;
  }

  /// Whether the normals follow the state, linearised (ResponseOptions::linearized_normal), from the next
  /// evaluation on.
  void set_linearized_normal(bool on) { options_.linearized_normal = on; }
  /// Where the forces act (ResponseOptions::facing_particles and centre_facing), from the next evaluation on.
  void set_particles(bool facing, bool centre_facing) {
    options_.facing_particles = facing;
    options_.centre_facing = centre_facing;
  }

  ContactGeometry& geometry() { return geometry_; }
  const ContactGeometry& geometry() const { return geometry_; }
  std::vector<double>& zone_penalty() { return penalty_; }
  const std::vector<double>& zone_penalty() const { return penalty_; }
  /// Committed g_rev per contact element [mm].
  const std::vector<Eigen::Vector3d>& reversible_committed() const { return reversible_committed_; }
  /// Per contact element, at the last evaluation.
  const std::vector<ContactState>& states() const { return states_; }
  /// Restores the states of a saved run (one per element), or, in a distributed evaluation
  /// (EquilibriumProblem::distribute), hands every rank the states of all elements after add() computed its
  /// own: these then count as that evaluation's (regime_changes).
  void set_states(std::vector<ContactState> states);

  /// The changes of regime of the contact elements summed over the evaluations since the last
  /// reset_regime_changes() (or since the term was made), each evaluation compared with the previous one of
  /// the same elements: the first evaluation after set_elements() (a new detection, or the elements of the
  /// committed state put back) or after the reset is compared with none. Counted at every evaluation, at a
  /// cost of O(elements).
  const RegimeChanges& regime_changes() const { return changes_; }
  /// Zeroes regime_changes() and forgets the last evaluation: the next one is compared with none (a step
  /// attempt counts its own changes, a resumed run as the run never stopped).
  void reset_regime_changes();

 private:
  /// After an evaluation of all the elements: adds its changes of regime since the previous evaluation of the
  /// same elements to changes_, and logs them (debug) with how many elements press and slip.
  void note_evaluation();

  const model::Model& model_;
  ContactGeometry geometry_;
  std::vector<double> penalty_;
  std::vector<Eigen::Vector3d> reversible_committed_;
  std::vector<ContactState> states_;
  /// The states of the previous evaluation, with which the next one is compared (when `compare_`).
  std::vector<ContactState> last_states_;
  bool compare_ = false;  ///< last_states_ are those of the same elements at the previous evaluation
  /// add() evaluated only some of the elements (distributed): the evaluation is counted when set_states()
  /// brings those of the other ranks.
  bool pending_ = false;
  RegimeChanges changes_;  ///< since the last reset_regime_changes()
  double regularization_ = 0.0;
  std::optional<FrictionLaw> friction_;
  std::vector<double> pair_friction_;  ///< set_pair_friction
  int num_beams_ = 0;
  ResponseOptions options_;
  solver::OrderedAssembly<ContactResponse> assembly_;  ///< the elements' responses, evaluated on all threads
};

}  // namespace nodus::contact
