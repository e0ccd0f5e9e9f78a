#include "nodus/beam/beam_element.hpp"

#include <array>

#include <Eigen/Geometry>

#include "nodus/beam/shape_functions.hpp"

namespace nodus::beam {
namespace {

/// The structure of the kinematic map B (y = B x_e at xi): each field of a node (its positions, d1, d2, at
/// `offset` in the node's unknowns) enters the kinematic blocks listed, times the shape value N or its
/// derivative dN/ds: r' = sum dN r, g_a = sum N d_a, g_a' = sum dN d_a. The functions below
/// read it to apply B and B^T without forming B.
struct FieldBlock {
  int block;        ///< first row of the kinematic block (KinematicBlock)
  bool derivative;  ///< times dN/ds, else N
};
struct FieldMap {
  int offset;  ///< of the field in the node's unknowns
  int count;   ///< blocks used of `blocks`
  FieldBlock blocks[2];
};
constexpr FieldMap kFieldMaps[] = {{0, 1, {{kRp, true}, {kRp, true}}},
                                   {3, 2, {{kG1, false}, {kG1p, true}}},
                                   {6, 2, {{kG2, false}, {kG2p, true}}}};

/// y = B x_e at xi, without multiplying by B's zeros (kFieldMaps): 45 multiplications where the product
/// with the dense 15 x 27 map takes 405.
KinematicVector mapped_kinematics(double length, double xi, const ElementVector& x_e) {
  const QuadraticShape shape = quadratic_shape(xi);
  const double dxi_ds = 2.0 / length;
  KinematicVector y = KinematicVector::Zero();
  for (int i = 0; i < kElementNodes; ++i) {
    const double n = shape.value[i];
    const double dn = shape.derivative[i] * dxi_ds;
    for (const FieldMap& f : kFieldMaps)
      for (int j = 0; j < f.count; ++j)
        y.segment<3>(f.blocks[j].block) +=
            (f.blocks[j].derivative ? dn : n) * x_e.segment<3>(kNodeDofs * i + f.offset);
  }
  return y;
}

/// force += w B^T v for the kinematic map B at xi, without multiplying by B's zeros (kFieldMaps).
void add_mapped_force(double length, double xi, double w, const KinematicVector& v, ElementVector& force) {
  const QuadraticShape shape = quadratic_shape(xi);
  const double dxi_ds = 2.0 / length;
  for (int i = 0; i < kElementNodes; ++i) {
    const double n = w * shape.value[i];
    const double dn = w * shape.derivative[i] * dxi_ds;
    for (const FieldMap& f : kFieldMaps)
      for (int j = 0; j < f.count; ++j)
        force.segment<3>(kNodeDofs * i + f.offset) +=
            (f.blocks[j].derivative ? dn : n) * v.segment<3>(f.blocks[j].block);
  }
}

/// tangent += w B^T K B for the kinematic map B at xi, without multiplying by B's zeros (kFieldMaps):
/// about 2,300 multiplications instead of the 34,000 of the dense product. The element tangents were most of
/// the flagship's assembly (docs/performance.md).
void add_mapped_tangent(double length, double xi, double w, const KinematicMatrix& k,
                        ElementMatrix& tangent) {
  const QuadraticShape shape = quadratic_shape(xi);
  const double dxi_ds = 2.0 / length;
  Eigen::Matrix<double, kKinematicSize, kElementDofs> kb;  // K B
  for (int i = 0; i < kElementNodes; ++i) {
    const double n = shape.value[i];
    const double dn = shape.derivative[i] * dxi_ds;
    for (const FieldMap& f : kFieldMaps) {
      auto column = kb.middleCols<3>(kNodeDofs * i + f.offset);
      column = (f.blocks[0].derivative ? dn : n) * k.middleCols<3>(f.blocks[0].block);
      for (int j = 1; j < f.count; ++j)
        column += (f.blocks[j].derivative ? dn : n) * k.middleCols<3>(f.blocks[j].block);
    }
  }
  for (int i = 0; i < kElementNodes; ++i) {
    const double n = w * shape.value[i];
    const double dn = w * shape.derivative[i] * dxi_ds;
    for (const FieldMap& f : kFieldMaps) {
      Eigen::Matrix<double, 3, kElementDofs> row =
          (f.blocks[0].derivative ? dn : n) * kb.middleRows<3>(f.blocks[0].block);
      for (int j = 1; j < f.count; ++j)
        row += (f.blocks[j].derivative ? dn : n) * kb.middleRows<3>(f.blocks[j].block);
      tangent.middleRows<3>(kNodeDofs * i + f.offset) += row;
    }
  }
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

/// The skew matrix [a]x with [a]x b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

/// The orientation barrier (orientation_barrier_energy). Adds dW/dx_e to `force` and, if `tangent` is not
/// null, its Hessian. At a point with m = J0 - J > 0, W_p = c m^2 with c = gamma (h/2) (D33/2), so dW_p/dy =
/// -2 c m dJ/dy and d2W_p/dy2 = 2 c (dJ/dy dJ/dy^T - m d2J/dy2); J = r' . (g1 x g2) is trilinear in (r', g1,
/// g2): dJ/dr' = g1 x g2, dJ/dg1 = g2 x r', dJ/dg2 = r' x g1, and its second derivatives are the skew
/// matrices d2J/dr'dg1 = -[g2]x, d2J/dr'dg2 = [g1]x, d2J/dg1dg2 = -[r']x (and their transposes).
double add_orientation_barrier(const ElementVector& x_e, const ElementProperties& props, ElementVector* force,
                               ElementMatrix* tangent) {
  if (props.fold_barrier <= 0.0) return 0.0;
  const double c = props.fold_barrier * 0.5 * props.length * 0.5 * props.stiffness(kE33, kE33);
  double energy = 0.0;
  const auto add_point = [&](double xi) {
    const KinematicVector y = mapped_kinematics(props.length, xi, x_e);
    const double m = kOrientationThreshold - orientation(y);
    if (!(m > 0.0)) return;
    energy += c * m * m;
    if (!force && !tangent) return;
    const Eigen::Vector3d rp = y.segment<3>(kRp), g1 = y.segment<3>(kG1), g2 = y.segment<3>(kG2);
    KinematicVector dj = KinematicVector::Zero();
    dj.segment<3>(kRp) = g1.cross(g2);
    dj.segment<3>(kG1) = g2.cross(rp);
    dj.segment<3>(kG2) = rp.cross(g1);
    if (force) add_mapped_force(props.length, xi, -2.0 * c * m, dj, *force);
    if (tangent) {
      KinematicMatrix d2j = KinematicMatrix::Zero();
      d2j.block<3, 3>(kRp, kG1) = -skew(g2);
      d2j.block<3, 3>(kRp, kG2) = skew(g1);
      d2j.block<3, 3>(kG1, kG2) = -skew(rp);
      d2j.block<3, 3>(kG1, kRp) = d2j.block<3, 3>(kRp, kG1).transpose();
      d2j.block<3, 3>(kG2, kRp) = d2j.block<3, 3>(kRp, kG2).transpose();
      d2j.block<3, 3>(kG2, kG1) = d2j.block<3, 3>(kG1, kG2).transpose();
      add_mapped_tangent(props.length, xi, 2.0 * c, dj * dj.transpose() - m * d2j, *tangent);
    }
  };
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) add_point(gp.xi);
  add_point(0.0);
  return energy;
}

}  // namespace

double orientation(const KinematicVector& y) {
  return y.segment<3>(kRp).dot(y.segment<3>(kG1).cross(y.segment<3>(kG2)));
}

double orientation_barrier_energy(const ElementVector& x_e, const ElementProperties& props) {
  return add_orientation_barrier(x_e, props, nullptr, nullptr);
}

double fold_energy(const ElementVector& x_e, const ElementProperties& props) {
  return add_fold(x_e, props, nullptr, nullptr);
}

KinematicVector element_kinematics(const ElementVector& x_e, double length, double xi) {
  return mapped_kinematics(length, xi, x_e);
}

double element_energy(const ElementVector& x_e, const ElementProperties& props) {
  double energy = 0.0;
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) {
    const StrainVector eps = strain_measures(element_kinematics(x_e, props.length, gp.xi));
    energy += 0.5 * gp.weight * 0.5 * props.length * eps.dot(props.stiffness * eps);
  }
  return energy + fold_energy(x_e, props) + orientation_barrier_energy(x_e, props);
}

void element_internal_force(const ElementVector& x_e, const ElementProperties& props, ElementVector& force,
                            ElementMatrix* tangent) {
  force.setZero();
  if (tangent) tangent->setZero();
  for (const GaussPoint& gp : gauss_rule(props.gauss_points)) {
    const double w = gp.weight * 0.5 * props.length;
    const KinematicVector y = mapped_kinematics(props.length, gp.xi, x_e);
    const StrainVector eps = strain_measures(y);
    const StrainJacobian jac = strain_jacobian(y);
    const StrainVector sigma = props.stiffness.lazyProduct(eps);  // section stress resultants
    add_mapped_force(props.length, gp.xi, w, jac.transpose().lazyProduct(sigma), force);
    if (tangent) {
      const KinematicMatrix k_y =
          strain_jacobian_congruence(y, props.stiffness) + weighted_strain_hessian(sigma);
      add_mapped_tangent(props.length, gp.xi, w, k_y, *tangent);
    }
  }
  add_fold(x_e, props, &force, tangent);
  add_orientation_barrier(x_e, props, &force, tangent);
}

}  // namespace nodus::beam
