#pragma once
/// Internal forces of the 3-node quadratic 9-dof beam element [Durville 2012, Eq. 3, 16-23, 65-67].
///
/// The element unknowns are the current nodal values x_e = (r, g1, g2) of its three nodes (27 numbers, node
/// by node); internal forces depend on them only, not on the displacement history. The strain energy per unit
/// reference length is 1/2 eps^T D eps (section.hpp), integrated along the axis by Gauss points.

#include <Eigen/Core>

#include "nodus/beam/section.hpp"
#include "nodus/beam/strain_measures.hpp"

namespace nodus::beam {

inline constexpr int kNodeDofs = 9;
inline constexpr int kElementNodes = 3;
inline constexpr int kElementDofs = kNodeDofs * kElementNodes;

using ElementVector = Eigen::Matrix<double, kElementDofs, 1>;
using ElementMatrix = Eigen::Matrix<double, kElementDofs, kElementDofs>;

/// Constant data of one element: its reference length and section stiffness.
struct ElementProperties {
  double length;                ///< reference length h [mm]
  SectionMatrix stiffness;      ///< D of section.hpp
  int gauss_points = 2;         ///< along the axis
  double fold_stiffness = 0.0;  ///< beta of the fold stabilisation (fold_energy), >= 0 [-]
  double fold_barrier = 1.0;    ///< gamma of the orientation barrier (orientation_barrier_energy), >= 0 [-]
};

/// The orientation of the section against the axis at a point of the axis: J = det[g1, g2, r'] =
/// r' . (g1 x g2) [-]. It is 1 in the reference state and 1 + O(strain) in any state the beam model
/// describes; J <= 0 means the axis runs against its section, as at one Gauss point of a folded element.
double orientation(const KinematicVector& y);

/// J0 of orientation_barrier_energy: the orientation below which the barrier acts [-].
inline constexpr double kOrientationThreshold = 0.5;

/// The energy of the orientation barrier [N mm]: gamma (h/2) (D33/2) sum_p <J0 - J(xi_p)>_+^2 over the
/// element's Gauss points and its centre, with J = orientation(), J0 = kOrientationThreshold = 1/2 and D33 =
/// D(E33, E33) the axial stiffness. It is exactly zero wherever J >= 1/2 at those points, that is in every
/// state of small strain (J = 1 + O(strain)), so a run none of whose iterates comes below 1/2 is unchanged
/// bit for bit, and a converged state above it solves the same equations as without; but the fold
/// of a 2-point element (fold_energy) has J = -1 at one Gauss point and J = 0 at the centre, and costs
/// gamma (5/8) h D33, the energy of the whole element at a uniform axial strain E33 of 1.1 (docs/model.md).
double orientation_barrier_energy(const ElementVector& x_e, const ElementProperties& props);

/// The energy that stabilises the fold of a reduced-integrated element [N mm]. With 2 Gauss points an element
/// can fold back on itself at no cost: its middle node out, its end nodes together, the tangent r' of unit
/// length and normal to the directors at both Gauss points (no strain there) but reversed between them. The
/// fold shows in the axial strain e = (|r'|^2 - 1)/2 at the element's centre, which the 2-point rule does not
/// see: e(0) minus the mean of e at the Gauss points is d = -|b|^2 / 6, with b = dr'/dxi = (2/h)(r1 - 2 r2 +
/// r3) (r' is linear in xi). The energy is beta (h/2) (D33/2) d^2, D33 = D(E33, E33) the section's axial
/// stiffness: zero for any uniform stretch, quartic in the second difference of the nodes. It adds to a
/// smooth bend of curvature kappa a fraction beta (kappa h)^2 (h/R)^2 D33 / (288 f E A) of its energy (f the
/// bending factor), and a complete fold costs it beta (h/2) (D33/2) / 4 (docs/model.md).
double fold_energy(const ElementVector& x_e, const ElementProperties& props);

/// The kinematic vector y = (r', g1, g2, g1', g2') at xi in [-1, 1] of an element of reference length h.
KinematicVector element_kinematics(const ElementVector& x_e, double length, double xi);

/// Strain energy of the element [N mm].
double element_energy(const ElementVector& x_e, const ElementProperties& props);

/// Internal force vector f_e = dW/dx_e [N, N mm]; if `tangent` is not null, also K_e = d f_e / d x_e.
void element_internal_force(const ElementVector& x_e, const ElementProperties& props, ElementVector& force,
                            ElementMatrix* tangent);

}  // namespace nodus::beam
