#pragma once
/// Cross-section of a beam: disc moments and the section stiffness that integrates the constitutive law
/// exactly across a circular section [Durville 2012, Eq. 16-23].

#include <Eigen/Core>

#include "nodus/beam/strain_measures.hpp"

namespace nodus::beam {

/// Integrals over a disc of radius R of the monomials in the transverse coordinates (xi1, xi2).
struct DiscMoments {
  double area;        ///< A = pi R^2 [mm^2]
  double second;      ///< I = int xi1^2 = int xi2^2 = pi R^4 / 4 [mm^4]
  double fourth;      ///< int xi1^4 = int xi2^4 = pi R^6 / 8 [mm^6]
  double mixed_four;  ///< int xi1^2 xi2^2 = pi R^6 / 24 [mm^6]
};

DiscMoments disc_moments(double radius);

/// Elastic constants of the split constitutive law [Eq. 19-23].
struct ElasticConstants {
  double young_modulus;  ///< E [MPa]
  double poisson_ratio;  ///< nu [-]
  double lambda() const {
    return young_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
  double mu() const { return young_modulus / (2 * (1 + poisson_ratio)); }
};

/// Section stiffness D such that the strain energy per unit reference length is 1/2 eps^T D eps, with eps the
/// 15 generalised strains of strain_measures.hpp. The section-constant strain E0 carries the full isotropic
/// law (Poisson effect); the linear and quadratic terms use nu = 0, i.e. s = E E [Eq. 21-23]. The energy
/// variant is used (docs/model.md): W = A (mu E0:E0 + lambda/2 tr(E0)^2) + (E/2) (int E:E dA - A E0:E0).
/// `bending_factor` multiplies the second moment of area in the bending terms (k1^2, k2^2) only [Table 1].
StrainVector section_stresses(const StrainVector& eps, const ElasticConstants& material, double radius,
                              double bending_factor);

using SectionMatrix = Eigen::Matrix<double, kNumStrains, kNumStrains>;

/// The constant matrix D above [N mm^{k}, k depending on the strain component].
SectionMatrix section_stiffness(const ElasticConstants& material, double radius, double bending_factor);

}  // namespace nodus::beam
