#include "nodus/contact/penalty_law.hpp"

namespace nodus::contact {

double normal_reaction(const NormalLaw& law, double gap) {
  if (gap >= 0.0) return 0.0;
  const double k = law.penalty, p = law.regularization;
  if (gap >= -p) return k * gap * gap / (2.0 * p);
  return -k * (gap + 0.5 * p);
}

double normal_stiffness(const NormalLaw& law, double gap) {
  if (gap >= 0.0) return 0.0;
  const double k = law.penalty, p = law.regularization;
  if (gap >= -p) return -k * gap / p;
  return k;
}

}  // namespace nodus::contact
