#include "nodus/beam/section.hpp"

#include <numbers>

namespace nodus::beam {

DiscMoments disc_moments(double radius) {
  const double r2 = radius * radius;
  const double pi = std::numbers::pi;
  return {pi * r2, pi * r2 * r2 / 4.0, pi * r2 * r2 * r2 / 8.0, pi * r2 * r2 * r2 / 24.0};
}

SectionMatrix section_stiffness(const ElasticConstants& material, double radius, double bending_factor) {
  const DiscMoments d = disc_moments(radius);
  const double young = material.young_modulus;
  const double lambda = material.lambda();
  const double mu = material.mu();
  SectionMatrix D = SectionMatrix::Zero();
  // Section-constant part, full isotropic law: A (mu E0:E0 + lambda/2 tr(E0)^2), shear terms counted twice.
  for (int i : {kE11, kE22, kE33}) {
    for (int j : {kE11, kE22, kE33}) D(i, j) = d.area * lambda;
    D(i, i) += 2.0 * d.area * mu;
  }
  for (int i : {kE12, kE13, kE23}) D(i, i) = 4.0 * d.area * mu;
  // Linear terms, nu = 0: (E/2) int (xi_a q_ba)^2 counted twice for E_13 and E_23; bending (E/2) f I k_a^2.
  for (int i : {kQ11, kQ12, kQ21, kQ22}) D(i, i) = 2.0 * young * d.second;
  D(kK1, kK1) = D(kK2, kK2) = young * bending_factor * d.second;
  // Quadratic terms of E_33: coupling with e33 through int xi_a^2, and their own square.
  D(kE33, kM11) = D(kM11, kE33) = young * d.second;
  D(kE33, kM22) = D(kM22, kE33) = young * d.second;
  D(kM11, kM11) = D(kM22, kM22) = young * d.fourth;
  D(kM11, kM22) = D(kM22, kM11) = young * d.mixed_four;
  D(kM12, kM12) = young * d.mixed_four;
  return D;
}

StrainVector section_stresses(const StrainVector& eps, const ElasticConstants& material, double radius,
                              double bending_factor) {
  return section_stiffness(material, radius, bending_factor) * eps;
}

}  // namespace nodus::beam
