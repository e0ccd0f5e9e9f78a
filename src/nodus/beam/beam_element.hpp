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
  double length;            ///< reference length h [mm]
  SectionMatrix stiffness;  ///< D of section.hpp
  int gauss_points = 2;     ///< along the axis
};

/// The kinematic vector y = (r', g1, g2, g1', g2') at xi in [-1, 1] of an element of reference length h.
KinematicVector element_kinematics(const ElementVector& x_e, double length, double xi);

/// Strain energy of the element [N mm].
double element_energy(const ElementVector& x_e, const ElementProperties& props);

/// Internal force vector f_e = dW/dx_e [N, N mm]; if `tangent` is not null, also K_e = d f_e / d x_e.
void element_internal_force(const ElementVector& x_e, const ElementProperties& props, ElementVector& force,
                            ElementMatrix* tangent);

}  // namespace nodus::beam
