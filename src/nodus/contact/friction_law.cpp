#include "nodus/contact/friction_law.hpp"

namespace nodus::contact {

using Mat3 = Eigen::Matrix3d;

FrictionResponse friction_response(const FrictionLaw& law, double normal_reaction, const Eigen::Vector3d& n,
                                   const Eigen::Vector3d& reversible_committed, const Eigen::Vector3d& du) {
  FrictionResponse r;
  if (!(law.coefficient > 0.0) || !(normal_reaction > 0.0)) return r;  // apart: no force, no memory
  const Mat3 tangential = Mat3::Identity() - n * n.transpose();
  const Eigen::Vector3d trial = tangential * (reversible_committed + du);
  const double size = trial.norm(), g_max = law.max_reversible;
  const double scale = law.coefficient * normal_reaction;
  if (size <= g_max) {  // stick
    r.reversible = trial;
    r.force = -scale / g_max * trial;
    r.stiffness = scale / g_max * tangential;
  } else {  // slip
    const Eigen::Vector3d t = trial / size;
    r.reversible = g_max * t;
    r.force = -scale * t;
    r.stiffness = scale / size * (Mat3::Identity() - t * t.transpose()) * tangential;
    r.slip = true;
  }
  return r;
}

}  // namespace nodus::contact
