#pragma once
/// Generalised strain measures of the 9-dof beam [Durville 2012, Eq. 16-17].
///
/// With x(xi) = r + xi_a g_a, the Green-Lagrange strain in the material basis is
/// E_ij = (c_i . c_j - delta_ij) / 2 with c_a = g_a and c_3 = r' + xi_a g_a'. It is exactly quadratic in
/// (xi1, xi2): E = E0 + xi_a E_a + xi_a xi_b E_ab. Its coefficients are 15 scalars, each a bilinear form of
/// the kinematic vector y = (r', g1, g2, g1', g2') (the derivative ' is with respect to the reference arc
/// length):
///
///   section-constant (E0):  e11 = (g1.g1 - 1)/2, e22 = (g2.g2 - 1)/2, e12 = g1.g2/2,
///                           e13 = g1.r'/2, e23 = g2.r'/2, e33 = (r'.r' - 1)/2
///   linear, shear:          q_ba = g_b.g_a'/2, the coefficient of xi_a in E_b3 (q11, q12, q21, q22)
///   linear, axial:          k_a = r'.g_a', the coefficient of xi_a in E_33 (bending curvatures)
///   quadratic, axial:       m11 = g1'.g1'/2, m22 = g2'.g2'/2, m12 = g1'.g2' (coefficients of xi1^2, xi2^2,
///                           xi1 xi2 in E_33)
///
/// Because each measure is a bilinear form plus a constant, its gradient is H_k y and its Hessian H_k is
/// constant.

#include <Eigen/Core>

namespace nodus::beam {

inline constexpr int kNumStrains = 15;
inline constexpr int kKinematicSize = 15;

/// Offsets of the five 3-vectors inside the kinematic vector y.
enum KinematicBlock : int { kRp = 0, kG1 = 3, kG2 = 6, kG1p = 9, kG2p = 12 };

/// Indices of the strain measures.
enum Strain : int {
  kE11 = 0,
  kE22,
  kE12,
  kE13,
  kE23,
  kE33,
  kQ11,
  kQ12,
  kQ21,
  kQ22,
  kK1,
  kK2,
  kM11,
  kM22,
  kM12
};

using KinematicVector = Eigen::Matrix<double, kKinematicSize, 1>;
using StrainVector = Eigen::Matrix<double, kNumStrains, 1>;
using StrainJacobian = Eigen::Matrix<double, kNumStrains, kKinematicSize>;
using KinematicMatrix = Eigen::Matrix<double, kKinematicSize, kKinematicSize>;

/// The 15 strain measures at one point of the axis.
StrainVector strain_measures(const KinematicVector& y);

/// d eps / d y.
StrainJacobian strain_jacobian(const KinematicVector& y);

/// J^T D J for J = strain_jacobian(y) and a matrix D of the strain measures' space (the section stiffness),
/// without multiplying by the zeros of J (six non-zeros a row) and of D: about 1,700 multiplications for a
/// section stiffness where the dense products take 6,750.
KinematicMatrix strain_jacobian_congruence(const KinematicVector& y,
                                           const Eigen::Matrix<double, kNumStrains, kNumStrains>& d);

/// sum_k w_k d^2 eps_k / dy^2 (constant in y).
KinematicMatrix weighted_strain_hessian(const StrainVector& w);

/// Short names of the strain measures, in index order (for output).
const char* strain_name(int k);

}  // namespace nodus::beam
