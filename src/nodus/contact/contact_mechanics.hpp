#pragma once
/// The mechanics of one contact element [Durville 2012, Sect. 5, Eq. 49-79]: with the normal law
/// (penalty_law.hpp, Eq. 53) and the friction law (friction_law.hpp, Eq. 55-64), the element's contributions
/// to the residual and the tangent over the 54 unknowns of the two beam elements that carry its particles
/// (Eq. 65-79).
///
/// Conventions (docs/contact.md): the normal n points from the particle on I to the particle on J; the gap
/// is <x_J - x_I, n>, negative when the surfaces overlap; the normal reaction R_N >= 0 pushes J along +n and
/// I along -n. The relative displacement is that of J's particle minus I's.

#include <Eigen/Core>

#include "nodus/beam/beam_element.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/contact/friction_law.hpp"
#include "nodus/contact/penalty_law.hpp"

namespace nodus::contact {

using Mat3 = Eigen::Matrix3d;
using ParticleMap = Eigen::Matrix<double, 3, beam::kElementDofs>;
using PairVector = Eigen::Matrix<double, 2 * beam::kElementDofs, 1>;
using PairMatrix = Eigen::Matrix<double, 2 * beam::kElementDofs, 2 * beam::kElementDofs>;

/// The 3 x 27 matrix B of a particle: its position is B q for the 27 unknowns q of its element (Eq. 65-67).
ParticleMap particle_map(const Particle& p);

/// The state of a contact element after evaluation.
struct ContactResponse {
  double gap = 0.0;                         ///< [mm]
  double normal_reaction = 0.0;             ///< R_N [N]
  FrictionResponse friction;                ///< tangential part (zero without friction)
  PairVector force = PairVector::Zero();    ///< contribution to f_int - f_ext, unknowns (q_I, q_J)
  PairMatrix tangent = PairMatrix::Zero();  ///< its derivative (normal and particles fixed unless the options
                                            ///< say otherwise)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< the normal used (the element's, or the state's)
};

/// How contact_response places the particles and linearises friction.
struct ResponseOptions {
  /// Each particle is the point of its section's border that lies furthest along the normal towards the other
  /// beam, in the current state (the section's abscissa is kept): the normal force then passes through the
  /// section's axis whatever the rotation of the section. Off: the particles keep the material coordinates
  /// of the element (the paper's fixed particles).
  bool facing_particles = false;
  /// Add to the tangent the derivative of the friction force through R_N (not symmetric: needs an LU solver).
  /// Off: R_N held fixed in the friction tangent (the paper's simplification, Sect. 5.3).
  bool friction_normal_coupling = false;
  /// The normal is recomputed from the current state at every evaluation, at the particles' abscissas (Eq.
  /// 41-44, as update_normal does), and its derivative enters the tangent (not symmetric: needs an LU
  /// solver). The friction force's turn with the normal (its projection on the tangent plane) is left out of
  /// the tangent. Off: the normal of the contact element, fixed during Newton (the paper's loop 3).
  bool linearized_normal = false;
  /// With facing_particles: each particle is the point of its section's border that faces the other section
  /// along the direction between the section centres (d of Eq. 37, projected on the section), as detection
  /// places the paper's particles (Eq. 37-40), but re-placed at every evaluation; the tangent is the exact
  /// derivative through the particles' motion (forward automatic differentiation). Off: the facing points
  /// along the normal, which at a crossing at a steep angle sit a full radius towards each other at every
  /// element of the zone however far apart the axes are laterally (the gap is then n.(r_J - r_I) - R_I - R_J
  /// all along the zone, and near a beam's tip, where the normal of the crossing is nearly perpendicular to
  /// the centres' direction, it reports deep penetrations of sections that are apart).
  bool centre_facing = false;
};

/// Evaluates the contact element `e` (normal fixed, unless options.linearized_normal) for the element
/// unknowns q_i, q_j (current) and q_i_committed, q_j_committed (at the committed state, for the friction
/// increment). `friction` may be null (frictionless). `reversible_committed` is the element's committed
/// g_rev.
ContactResponse contact_response(const ContactElement& e, const beam::ElementVector& q_i,
                                 const beam::ElementVector& q_j, const beam::ElementVector& q_i_committed,
                                 const beam::ElementVector& q_j_committed, const NormalLaw& normal,
                                 const FrictionLaw* friction, const Eigen::Vector3d& reversible_committed,
                                 const ResponseOptions& options = {});
/// The same, written into `response` (whose 54 x 54 tangent a caller may keep, rather than copy, across
/// evaluations).
void contact_response(const ContactElement& e, const beam::ElementVector& q_i, const beam::ElementVector& q_j,
                      const beam::ElementVector& q_i_committed, const beam::ElementVector& q_j_committed,
                      const NormalLaw& normal, const FrictionLaw* friction,
                      const Eigen::Vector3d& reversible_committed, const ResponseOptions& options,
                      ContactResponse& response);

/// The transverse material coordinates (xi1, xi2), of norm `radius`, of the point of the border of the
/// section with directors g1, g2 that lies furthest along `direction`: xi ~ (g1.direction, g2.direction).
/// False (xi unchanged) if the direction is along the axis.
bool facing_point(const Eigen::Vector3d& g1, const Eigen::Vector3d& g2, const Eigen::Vector3d& direction,
                  double radius, Eigen::Vector2d& xi);

}  // namespace nodus::contact
