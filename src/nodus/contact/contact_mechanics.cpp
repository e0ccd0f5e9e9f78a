#include "nodus/contact/contact_mechanics.hpp"

#include "nodus/beam/shape_functions.hpp"

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

ParticleMap particle_map(const Particle& p) {
  const beam::QuadraticShape shape = beam::quadratic_shape(p.local);
  ParticleMap b = ParticleMap::Zero();
  for (int k = 0; k < beam::kElementNodes; ++k) {
    const double v = shape.value[static_cast<std::size_t>(k)];
    b.block<3, 3>(0, beam::kNodeDofs * k).diagonal().setConstant(v);
    b.block<3, 3>(0, beam::kNodeDofs * k + 3).diagonal().setConstant(v * p.transverse.x());
    b.block<3, 3>(0, beam::kNodeDofs * k + 6).diagonal().setConstant(v * p.transverse.y());
  }
  return b;
}

ContactResponse contact_response(const ContactElement& e, const beam::ElementVector& q_i,
                                 const beam::ElementVector& q_j, const beam::ElementVector& q_i_committed,
                                 const beam::ElementVector& q_j_committed, const NormalLaw& normal,
                                 const FrictionLaw* friction, const Eigen::Vector3d& reversible_committed) {
  constexpr int n = beam::kElementDofs;
  const ParticleMap b_i = particle_map(e.particle_i), b_j = particle_map(e.particle_j);
  // Relative position of the particles, x_J - x_I = C (q_I, q_J) with C = [-B_I, B_J] (Eq. 65-67).
  Eigen::Matrix<double, 3, 2 * n> c;
  c << -b_i, b_j;
  const Eigen::Vector3d& nrm = e.normal;
  ContactResponse r;
  r.gap = nrm.dot(b_j * q_j - b_i * q_i);  // Eq. 45 with the particles and the normal fixed
  r.normal_reaction = normal_reaction(normal, r.gap);
  Mat3 stiffness = normal_stiffness(normal, r.gap) * nrm * nrm.transpose();
  Eigen::Vector3d force_on_j = r.normal_reaction * nrm;
  if (friction) {
    const Eigen::Vector3d du = (b_j * (q_j - q_j_committed)) - (b_i * (q_i - q_i_committed));
    r.friction = friction_response(*friction, r.normal_reaction, nrm, reversible_committed, du);
    force_on_j += r.friction.force;
    stiffness += r.friction.stiffness;  // R_N held fixed (the paper's simplification, Sect. 5.3)
  }
  // The force on J acts as an external load +force_on_j on J's particle and -force_on_j on I's:
  // f_int - f_ext gains -C^T force_on_j; its derivative is C^T K C with K = -d force_on_j / d(x_J - x_I).
  r.force = -c.transpose() * force_on_j;
  r.tangent = c.transpose() * stiffness * c;
  return r;
}

}  // namespace nodus::contact
