#include "nodus/beam/strain_measures.hpp"

#include <array>

namespace nodus::beam {
namespace {

/// eps_k = coefficient * (u . v) + constant, with u and v two blocks of y.
struct BilinearMeasure {
  const char* name;
  int u;
  int v;
  double coefficient;
  double constant;
};

constexpr std::array<BilinearMeasure, kNumStrains> kMeasures{{
    {"e11", kG1, kG1, 0.5, -0.5},
    {"e22", kG2, kG2, 0.5, -0.5},
    {"e12", kG1, kG2, 0.5, 0.0},
    {"e13", kG1, kRp, 0.5, 0.0},
    {"e23", kG2, kRp, 0.5, 0.0},
    {"e33", kRp, kRp, 0.5, -0.5},
    {"q11", kG1, kG1p, 0.5, 0.0},
    {"q12", kG1, kG2p, 0.5, 0.0},
    {"q21", kG2, kG1p, 0.5, 0.0},
    {"q22", kG2, kG2p, 0.5, 0.0},
    {"k1", kRp, kG1p, 1.0, 0.0},
    {"k2", kRp, kG2p, 1.0, 0.0},
    {"m11", kG1p, kG1p, 0.5, 0.0},
    {"m22", kG2p, kG2p, 0.5, 0.0},
    {"m12", kG1p, kG2p, 1.0, 0.0},
}};

}  // namespace

StrainVector strain_measures(const KinematicVector& y) {
  StrainVector eps;
  for (int k = 0; k < kNumStrains; ++k) {
    const auto& m = kMeasures[k];
    eps[k] = m.coefficient * y.segment<3>(m.u).dot(y.segment<3>(m.v)) + m.constant;
  }
  return eps;
}

StrainJacobian strain_jacobian(const KinematicVector& y) {
  StrainJacobian jac = StrainJacobian::Zero();
  for (int k = 0; k < kNumStrains; ++k) {
    const auto& m = kMeasures[k];
    jac.block<1, 3>(k, m.u) += m.coefficient * y.segment<3>(m.v).transpose();
    jac.block<1, 3>(k, m.v) += m.coefficient * y.segment<3>(m.u).transpose();
  }
  return jac;
}

KinematicMatrix strain_jacobian_congruence(const KinematicVector& y,
                                           const Eigen::Matrix<double, kNumStrains, kNumStrains>& d) {
  // Row k of J holds coefficient * y_v^T in block u and coefficient * y_u^T in block v (kMeasures).
  StrainJacobian dj = StrainJacobian::Zero();  // D J
  for (int l = 0; l < kNumStrains; ++l) {
    const auto& m = kMeasures[l];
    const Eigen::Vector3d a = m.coefficient * y.segment<3>(m.v);
    const Eigen::Vector3d b = m.coefficient * y.segment<3>(m.u);
    for (int k = 0; k < kNumStrains; ++k) {
      const double dkl = d(k, l);
      if (dkl == 0.0) continue;
      dj.block<1, 3>(k, m.u) += dkl * a.transpose();
      dj.block<1, 3>(k, m.v) += dkl * b.transpose();
    }
  }
  KinematicMatrix k = KinematicMatrix::Zero();  // J^T (D J)
  for (int i = 0; i < kNumStrains; ++i) {
    const auto& m = kMeasures[i];
    k.middleRows<3>(m.u).noalias() += (m.coefficient * y.segment<3>(m.v)) * dj.row(i);
    k.middleRows<3>(m.v).noalias() += (m.coefficient * y.segment<3>(m.u)) * dj.row(i);
  }
  return k;
}

KinematicMatrix weighted_strain_hessian(const StrainVector& w) {
  KinematicMatrix h = KinematicMatrix::Zero();
  for (int k = 0; k < kNumStrains; ++k) {
    const auto& m = kMeasures[k];
    const double c = w[k] * m.coefficient;
    h.block<3, 3>(m.u, m.v).diagonal().array() += c;
    h.block<3, 3>(m.v, m.u).diagonal().array() += c;
  }
  return h;
}

const char* strain_name(int k) {
  return kMeasures.at(static_cast<std::size_t>(k)).name;
}

}  // namespace nodus::beam
