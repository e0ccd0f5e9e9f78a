#pragma once
/// The normal contact law: the regularised penalty of Durville 2012, Eq. 53. Conventions in
/// contact_mechanics.hpp and docs/contact.md: gap < 0 when the surfaces overlap, R_N >= 0.

namespace nodus::contact {

/// The quadratic regularisation of the penalty (Eq. 53).
struct NormalLaw {
  double penalty = 0.0;         ///< k_c [N/mm], > 0
  double regularization = 0.0;  ///< p_reg [mm], > 0
};

/// R_N [N]: 0 for gap >= 0; k gap^2 / (2 p_reg) for -p_reg <= gap <= 0; -k (gap + p_reg / 2) below. C1.
double normal_reaction(const NormalLaw& law, double gap);
/// -dR_N/dgap >= 0 [N/mm].
double normal_stiffness(const NormalLaw& law, double gap);

}  // namespace nodus::contact
