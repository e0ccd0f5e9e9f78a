#pragma once
/// The rotation of a rigid body as a rotation vector theta (axis times angle [rad]) and the exact first and
/// second derivatives of its matrix, for Newton's tangent. Rodrigues' formula, written in t = |theta|^2 so
/// that every coefficient is smooth at theta = 0:
///
///   Q(theta) = I + s(t) A + c(t) A^2,   A = [theta]x,   s = sin(phi) / phi,   c = (1 - cos(phi)) / phi^2,
///
/// phi = sqrt(t). With E_k = [e_k]x and primes d/dt:
///
///   dQ/dtheta_k = 2 theta_k s' A + s E_k + 2 theta_k c' A^2 + c (E_k A + A E_k),
///
/// and d^2Q/dtheta_k dtheta_l follows by differentiating once more (rotation_vector.cpp). The map is smooth
/// everywhere, but its differential is singular where phi is a nonzero multiple of 2 pi: a free body must
/// not turn that far from its parametrisation's origin (docs/bodies.md).

#include <array>

#include <Eigen/Core>

namespace nodus::model {

/// Q(theta) and its derivatives.
struct RotationDerivatives {
  Eigen::Matrix3d q;                                     ///< Q(theta)
  std::array<Eigen::Matrix3d, 3> first;                  ///< dQ / dtheta_k
  std::array<std::array<Eigen::Matrix3d, 3>, 3> second;  ///< d^2 Q / dtheta_k dtheta_l (symmetric in k, l)
};

/// [v]x, the matrix of the cross product v x .
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// Q(theta).
Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& theta);

/// Q(theta) with its first and (if `second`) second derivatives.
RotationDerivatives rotation_derivatives(const Eigen::Vector3d& theta, bool second = true);

/// The rotation vector of Q (angle in [0, pi]) shifted by whole turns along its axis to lie nearest to
/// `near`: composing rotations about one axis keeps counting turns.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& q, const Eigen::Vector3d& near);

/// How a Newton increment moves the section directors of the beams' nodes
/// (simulation::EquilibriumProblem::step, the scenario's solver.director_update).
enum class DirectorUpdate {
  rotation,  ///< the rigid-turn part of the increments as a finite rotation (rotate_directors)
  additive,  ///< g_i + d_i
};

/// The section directors reached from (g1, g2) by the increments (d1, d2) of a Newton step. The part of the
/// increments that is a linearised rotation, omega x g_i with omega fitted in least squares
/// (sum_i (|g_i|^2 I - g_i g_i^T) omega = sum_i g_i x d_i), is applied as the finite rotation Q(omega); the
/// rest is added: g_i' = Q(omega) g_i + (d_i - omega x g_i). To first order in d this is g_i + d_i, so Newton
/// keeps its rate; for a rigid turn it keeps the directors' lengths and angle, which g_i + d_i would stretch
/// by |omega|^2 / 2 (docs/model.md, "Director update"). Degenerate directors (parallel or zero) are
/// returned as g_i + d_i.
std::array<Eigen::Vector3d, 2> rotate_directors(const Eigen::Vector3d& g1, const Eigen::Vector3d& g2,
                                                const Eigen::Vector3d& d1, const Eigen::Vector3d& d2);

}  // namespace nodus::model
