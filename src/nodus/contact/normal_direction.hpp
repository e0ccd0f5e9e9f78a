#pragma once
/// The normal direction of a contact element [Durville 2012, Eq. 41-44] as a function of the axis positions
/// and tangents of its two sections, and the derivative of that function. The cross product of the tangents
/// (Eq. 42) above a crossing angle of 15 degrees, the double cross product (Eq. 44) below 5 degrees, a smooth
/// blend between (docs/contact.md, "Normal direction").

#include <Eigen/Core>

namespace nodus::contact {

/// The normal of a pair of sections, oriented from I towards J.
struct NormalDirection {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();        ///< unit direction between the section centres (Eq. 37)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit (Eq. 41-44)
  double parallel_weight = 0.0;  ///< 1: double cross product only (Eq. 44); 0: cross product only (Eq. 42)
};

/// The normal of the sections with axis positions r_i, r_j and axis derivatives dr_i, dr_j (along any
/// parametrisation: only their directions count). Centres closer than `centre_tolerance` [mm] count as
/// coincident, where the direction between them is taken as the common normal of the axes. False if the
/// normal is undefined (coincident centres of parallel axes).
bool normal_direction(const Eigen::Vector3d& r_i, const Eigen::Vector3d& dr_i, const Eigen::Vector3d& r_j,
                      const Eigen::Vector3d& dr_j, double centre_tolerance, NormalDirection& out);

/// The derivative of the normal with respect to (r_i, dr_i, r_j, dr_j), columns in that order.
using NormalJacobian = Eigen::Matrix<double, 3, 12>;

/// The same, with the derivative of the normal (by forward automatic differentiation of the same function).
bool normal_direction(const Eigen::Vector3d& r_i, const Eigen::Vector3d& dr_i, const Eigen::Vector3d& r_j,
                      const Eigen::Vector3d& dr_j, double centre_tolerance, NormalDirection& out,
                      NormalJacobian& jacobian);

}  // namespace nodus::contact
