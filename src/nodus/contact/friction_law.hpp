#pragma once
/// The friction law: regularised Coulomb friction with a reversible tangential displacement as history
/// variable, and its return mapping [Durville 2012, Eq. 55-64].

#include <Eigen/Core>

namespace nodus::contact {

/// Regularised Coulomb friction (Eq. 55-64).
struct FrictionLaw {
  double coefficient = 0.0;     ///< mu [-], >= 0
  double max_reversible = 0.0;  ///< g_rev_max [mm], > 0: the tangential displacement before sliding
};

/// The result of the return mapping of one contact element.
struct FrictionResponse {
  Eigen::Vector3d reversible = Eigen::Vector3d::Zero();  ///< g_rev at the end of the step [mm]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();       ///< tangential force on J [N]; -force acts on I
  Eigen::Matrix3d stiffness =
      Eigen::Matrix3d::Zero();  ///< -d force / d(relative displacement) [N/mm], R_N held fixed
  bool slip = false;
};

/// Return mapping (Eq. 59-64): trial g_tr = g_rev_n + (I - n n) du, with du the increment of the relative
/// displacement of the two particles since the committed state and g_rev_n the committed reversible
/// displacement (projected on the plane normal to n); stick if |g_tr| <= g_rev_max, else slip with
/// g_rev = g_rev_max g_tr / |g_tr|. The force on J is -mu R_N g_rev / g_rev_max. With mu = 0 or R_N = 0
/// (surfaces apart): no force, and g_rev = 0 (no memory of an earlier contact).
FrictionResponse friction_response(const FrictionLaw& law, double normal_reaction, const Eigen::Vector3d& n,
                                   const Eigen::Vector3d& reversible_committed, const Eigen::Vector3d& du);

}  // namespace nodus::contact
