#include "nodus/beam/beam_element.hpp"

#include <array>

#include "nodus/beam/shape_functions.hpp"

namespace nodus::beam {
namespace {

using KinematicMap = Eigen::Matrix<double, kKinematicSize, kElementDofs>;

/// B such that y = B x_e at xi.
KinematicMap kinematic_map(double length, double xi) {
  const QuadraticShape shape = quadratic_shape(xi);
  const double dxi_ds = 2.0 / length;
  KinematicMap b = KinematicMap::Zero();
  for (int i = 0; i < kElementNodes; ++i) {
    const double n = shape.value[i];
    const double dn = shape.derivative[i] * dxi_ds;
    const int c = kNodeDofs * i;
    for (int d = 0; d < 3; ++d) {
      b(kRp + d, c + d) = dn;
      b(kG1 + d, c + 3 + d) = n;
      b(kG2 + d, c + 6 + d) = n;
      b(kG1p + d, c + 3 + d) = dn;
      b(kG2p + d, c + 6 + d) = dn;
    }
  }
  return b;
}

/// The fold stabilisation (fold_energy): W = c q^2 with v = r1 - 2 r2 + r3, q = |b|^2 = (4/h^2) |v|^2 and
/// c = beta (h/2) (D33/2) / 36. Adds dW/dx_e to `force` and, if `tangent` is not null, its Hessian.
double add_fold(const ElementVector& x_e, const ElementProperties& props, ElementVector* force,
                ElementMatrix* tangent) {
  if (props.fold_stiffness <= 0.0) return 0.0;
  const double h = props.length;
  const double c = props.fold_stiffness * 0.5 * h * 0.5 * props.stiffness(kE33, kE33) / 36.0;
  constexpr std::array<double, kElementNodes> kCoefficient{1.0, -2.0, 1.0};
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int i = 0; i < kElementNodes; ++i) v += kCoefficient[i] * x_e.segment<3>(kNodeDofs * i);
  const double scale = 4.0 / (h * h);
  const double q = scale * v.squaredNorm();
  if (force) {
    const Eigen::Vector3d dw_dv = 4.0 * c * q * scale * v;  // d(c q^2)/dv = 2 c q dq/dv, dq/dv = 2 scale v
    for (int i = 0; i < kElementNodes; ++i) force->segment<3>(kNodeDofs * i) += kCoefficient[i] * dw_dv;
  }
  if (tangent) {
    const Eigen::Matrix3d hv =
        4.0 * c * scale * (q * Eigen::Matrix3d::Identity() + 2.0 * scale * v * v.transpose());
    for (int i = 0; i < kElementNodes; ++i)
      for (int j = 0; j < kElementNodes; ++j)
        tangent->block<3, 3>(kNodeDofs * i, kNodeDofs * j) += kCoefficient[i] * kCoefficient[j] * hv;
  }
  return c * q * q;
}

}  // namespace

double fold_energy(const ElementVector& x_e, const ElementProperties& props) {
  return add_fold(x_e, props, nullptr, nullptr);
}

KinematicVector element_kinematics(const ElementVector& x_e, double length, double xi) {
  return kinematic_map(length, xi) * x_e;
}

double element_energy(const ElementVector& x_e, const ElementProperties& props) {
  double energy = 0.0;
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) {
    const StrainVector eps = strain_measures(element_kinematics(x_e, props.length, gp.xi));
    energy += 0.5 * gp.weight * 0.5 * props.length * eps.dot(props.stiffness * eps);
  }
  return energy + fold_energy(x_e, props);
}

void element_internal_force(const ElementVector& x_e, const ElementProperties& props, ElementVector& force,
                            ElementMatrix* tangent) {
  force.setZero();
  if (tangent) tangent->setZero();
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) {
    const double w = gp.weight * 0.5 * props.length;
    const KinematicMap b = kinematic_map(props.length, gp.xi);
    const KinematicVector y = b * x_e;
    const StrainVector eps = strain_measures(y);
    const StrainJacobian jac = strain_jacobian(y);
    const StrainVector sigma = props.stiffness * eps;  // section stress resultants
    force.noalias() += w * b.transpose() * (jac.transpose() * sigma);
    if (tangent) {
      const KinematicMatrix k_y = jac.transpose() * props.stiffness * jac + weighted_strain_hessian(sigma);
      tangent->noalias() += w * b.transpose() * k_y * b;
    }
  }
  add_fold(x_e, props, &force, tangent);
}

}  // namespace nodus::beam
