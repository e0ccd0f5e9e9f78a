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
  /// Restores the states of a saved run (one per element).
  void set_states(std::vector<ContactState> states) { states_ = std::move(states); }

 private:
  /// Logs (debug) how many elements press and slip, and how many changed since the last evaluation.
  void log_regime_changes();

  const model::Model& model_;
  ContactGeometry geometry_;
  std::vector<double> penalty_;
  std::vector<Eigen::Vector3d> reversible_committed_;
  std::vector<ContactState> states_;
  /// For the log of --verbose: the states of the last evaluation logged.
  std::vector<ContactState> last_states_;
  double regularization_ = 0.0;
  std::optional<FrictionLaw> friction_;
  std::vector<double> pair_friction_;  ///< set_pair_friction
  int num_beams_ = 0;
  ResponseOptions options_;
  solver::OrderedAssembly<ContactResponse> assembly_;  ///< the elements' responses, evaluated on all threads
};

}  // namespace nodus::contact
