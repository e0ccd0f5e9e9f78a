#include "nodus/beam/beam_element.hpp"

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

}  // namespace

KinematicVector element_kinematics(const ElementVector& x_e, double length, double xi) {
  return kinematic_map(length, xi) * x_e;
}

double element_energy(const ElementVector& x_e, const ElementProperties& props) {
  double energy = 0.0;
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) {
    const StrainVector eps = strain_measures(element_kinematics(x_e, props.length, gp.xi));
    energy += 0.5 * gp.weight * 0.5 * props.length * eps.dot(props.stiffness * eps);
  }
  return energy;
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
}

}  // namespace nodus::beam
