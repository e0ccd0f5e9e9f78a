#include "nodus/contact/contact_mechanics.hpp"

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "nodus/beam/shape_functions.hpp"
#include "nodus/contact/normal_direction.hpp"

namespace nodus::contact {

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

bool facing_point(const Eigen::Vector3d& g1, const Eigen::Vector3d& g2, const Eigen::Vector3d& direction,
                  double radius, Eigen::Vector2d& xi) {
  const Eigen::Vector2d w(g1.dot(direction), g2.dot(direction));
  const double size = w.norm();
  if (!(size > 0.0)) return false;
  xi = (radius / size) * w;
  return true;
}

namespace {

/// A particle of `e` moved to the facing point of its section (towards `direction`), and the curvature of
/// the facing point's support function h(G) = R |G^T direction| (G = [g1 g2] at the particle) in the
/// section's directors: d2h/dG2 = R / |w| (I - u u^T) (x) direction direction^T, with w = G^T direction, u =
/// w / |w|; `shape` the particle's shape function values.
struct Facing {
  Particle particle;
  Eigen::Matrix2d curvature = Eigen::Matrix2d::Zero();  ///< R / |w| (I - u u^T)
  Eigen::Vector3d shape = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 2> directors = Eigen::Matrix<double, 3, 2>::Zero();  ///< G = [g1 g2]
};

Facing facing(const Particle& p, const beam::ElementVector& q, const Eigen::Vector3d& direction) {
  Facing f;
  f.particle = p;
  const beam::QuadraticShape sh = beam::quadratic_shape(p.local);
  Eigen::Vector3d g1 = Eigen::Vector3d::Zero(), g2 = Eigen::Vector3d::Zero();
  for (int k = 0; k < beam::kElementNodes; ++k) {
    const double v = sh.value[static_cast<std::size_t>(k)];
    f.shape[k] = v;
    g1 += v * q.segment<3>(beam::kNodeDofs * k + 3);
    g2 += v * q.segment<3>(beam::kNodeDofs * k + 6);
  }
  const double radius = p.transverse.norm();
  Eigen::Vector2d xi;
  if (!facing_point(g1, g2, direction, radius, xi)) return f;
  f.particle.transverse = xi;
  f.directors << g1, g2;
  const Eigen::Vector2d w(g1.dot(direction), g2.dot(direction));
  const Eigen::Vector2d u = w.normalized();
  f.curvature = (radius / w.norm()) * (Eigen::Matrix2d::Identity() - u * u.transpose());
  return f;
}

using NormalMap = Eigen::Matrix<double, 3, 2 * beam::kElementDofs>;

/// The section of a particle's abscissa in state q: axis position, its derivative along the element
/// coordinate, the directors, and the shape functions there.
struct Section {
  Eigen::Vector3d r = Eigen::Vector3d::Zero(), dr = Eigen::Vector3d::Zero();
  Eigen::Vector3d g1 = Eigen::Vector3d::Zero(), g2 = Eigen::Vector3d::Zero();
  beam::QuadraticShape shape{};
};

Section section_at(const Particle& p, const beam::ElementVector& q) {
  Section s;
  s.shape = beam::quadratic_shape(p.local);
  for (int k = 0; k < beam::kElementNodes; ++k) {
    const double v = s.shape.value[static_cast<std::size_t>(k)];
    const double dv = s.shape.derivative[static_cast<std::size_t>(k)];
    s.r += v * q.segment<3>(beam::kNodeDofs * k);
    s.dr += dv * q.segment<3>(beam::kNodeDofs * k);
    s.g1 += v * q.segment<3>(beam::kNodeDofs * k + 3);
    s.g2 += v * q.segment<3>(beam::kNodeDofs * k + 6);
  }
  return s;
}

/// The normal of `e` in the current state (q_i, q_j), at its particles' abscissas, and its derivative with
/// respect to (q_i, q_j); false (nothing written) where it is undefined.
bool current_normal(const ContactElement& e, const beam::ElementVector& q_i, const beam::ElementVector& q_j,
                    Eigen::Vector3d& normal, NormalMap& derivative) {
  // The tangent is the axis derivative along the element coordinate: only its direction counts.
  const Section s_i = section_at(e.particle_i, q_i), s_j = section_at(e.particle_j, q_j);
  NormalDirection n;
  NormalJacobian jacobian;
  const double centre_tolerance = 1e-12 * (e.particle_i.transverse.norm() + e.particle_j.transverse.norm());
  if (!normal_direction(s_i.r, s_i.dr, s_j.r, s_j.dr, centre_tolerance, n, jacobian)) return false;
  normal = n.normal;
  derivative.setZero();
  for (int k = 0; k < beam::kElementNodes; ++k) {
    const auto node = static_cast<std::size_t>(k);
    derivative.block<3, 3>(0, beam::kNodeDofs * k) = s_i.shape.value[node] * jacobian.block<3, 3>(0, 0) +
                                                     s_i.shape.derivative[node] * jacobian.block<3, 3>(0, 3);
    derivative.block<3, 3>(0, beam::kElementDofs + beam::kNodeDofs * k) =
        s_j.shape.value[node] * jacobian.block<3, 3>(0, 6) +
        s_j.shape.derivative[node] * jacobian.block<3, 3>(0, 9);
  }
  return true;
}

/// The derivative of a quantity with respect to the 24 section quantities (r, dr, g1, g2 of I, then of J),
/// carried to the 54 element unknowns (q_I, q_J) through the shape functions.
template <int Rows>
Eigen::Matrix<double, Rows, 2 * beam::kElementDofs> to_unknowns(const Eigen::Matrix<double, Rows, 24>& d,
                                                                const Section& s_i, const Section& s_j) {
  Eigen::Matrix<double, Rows, 2 * beam::kElementDofs> out;
  out.setZero();
  for (int side = 0; side < 2; ++side) {
    const Section& s = side == 0 ? s_i : s_j;
    for (int k = 0; k < beam::kElementNodes; ++k) {
      const double v = s.shape.value[static_cast<std::size_t>(k)];
      const double dv = s.shape.derivative[static_cast<std::size_t>(k)];
      const int col = beam::kElementDofs * side + beam::kNodeDofs * k, in = 12 * side;
      out.template middleCols<3>(col) =
          v * d.template middleCols<3>(in) + dv * d.template middleCols<3>(in + 3);
      out.template middleCols<3>(col + 3) = v * d.template middleCols<3>(in + 6);
      out.template middleCols<3>(col + 6) = v * d.template middleCols<3>(in + 9);
    }
  }
  return out;
}

/// The particles facing each other along the direction between the section centres, and the gap along the
/// normal, with their derivatives with respect to the element unknowns.
struct CentreFacing {
  Eigen::Vector2d xi_i, xi_j;  ///< transverse coordinates of the particles
  double gap = 0.0;
  Eigen::Matrix<double, 2, 2 * beam::kElementDofs> dxi_i, dxi_j;
  Eigen::Matrix<double, 1, 2 * beam::kElementDofs> dgap;
};

/// `normal` and its derivative `dn` (zero for a normal held fixed) with respect to the element unknowns.
CentreFacing centre_facing(const ContactElement& e, const Section& s_i, const Section& s_j,
                           const Eigen::Vector3d& normal, const NormalMap& dn) {
  using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
  using V3 = Eigen::Matrix<Ad, 3, 1>;
  const auto seed = [](const Eigen::Vector3d& v, int first) {
    V3 a;
    for (int k = 0; k < 3; ++k) a[k] = Ad(v[k], 24, first + k);
    return a;
  };
  const V3 r_i = seed(s_i.r, 0), g1_i = seed(s_i.g1, 6), g2_i = seed(s_i.g2, 9);
  const V3 r_j = seed(s_j.r, 12), g1_j = seed(s_j.g1, 18), g2_j = seed(s_j.g2, 21);
  using std::sqrt;
  const V3 centres = r_j - r_i;
  const V3 d = centres / sqrt(centres.squaredNorm());
  // The facing point of a section along `direction`: xi = R w / |w|, w = G^T direction; where the direction
  // runs along the axis (w = 0) the particle keeps its place.
  const auto face = [](const V3& g1, const V3& g2, const V3& direction, const Particle& p) {
    Eigen::Matrix<Ad, 2, 1> w(g1.dot(direction), g2.dot(direction));
    const Ad size = sqrt(w.squaredNorm());
    if (!(size > 0.0)) return Eigen::Matrix<Ad, 2, 1>(Ad(p.transverse.x()), Ad(p.transverse.y()));
    return Eigen::Matrix<Ad, 2, 1>(w * (p.transverse.norm() / size));
  };
  const Eigen::Matrix<Ad, 2, 1> xi_i = face(g1_i, g2_i, d, e.particle_i);
  const Eigen::Matrix<Ad, 2, 1> xi_j = face(g1_j, g2_j, V3(-d), e.particle_j);
  const V3 x_i = r_i + xi_i[0] * g1_i + xi_i[1] * g2_i;
  const V3 x_j = r_j + xi_j[0] * g1_j + xi_j[1] * g2_j;
  const V3 relative = x_j - x_i;
  CentreFacing out;
  Eigen::Matrix<double, 2, 24> dxi_i, dxi_j;
  Eigen::Matrix<double, 3, 24> drelative;
  for (int k = 0; k < 2; ++k) {
    out.xi_i[k] = xi_i[k].value();
    out.xi_j[k] = xi_j[k].value();
    dxi_i.row(k) = xi_i[k].derivatives().transpose();
    dxi_j.row(k) = xi_j[k].derivatives().transpose();
  }
  Eigen::Vector3d rel;
  for (int k = 0; k < 3; ++k) {
    rel[k] = relative[k].value();
    drelative.row(k) = relative[k].derivatives().transpose();
  }
  out.dxi_i = to_unknowns<2>(dxi_i, s_i, s_j);
  out.dxi_j = to_unknowns<2>(dxi_j, s_i, s_j);
  // gap = <x_J - x_I, n>: its derivative through the particles' positions and through the normal.
  out.gap = normal.dot(rel);
  out.dgap = normal.transpose() * to_unknowns<3>(drelative, s_i, s_j) + rel.transpose() * dn;
  return out;
}

/// contact_response with options.centre_facing (and facing_particles).
void centre_facing_response(const ContactElement& e, const beam::ElementVector& q_i,
                            const beam::ElementVector& q_j, const beam::ElementVector& q_i_committed,
                            const beam::ElementVector& q_j_committed, const NormalLaw& normal,
                            const FrictionLaw* friction, const Eigen::Vector3d& reversible_committed,
                            const ResponseOptions& options, ContactResponse& r) {
  constexpr int n = beam::kElementDofs;
  Eigen::Vector3d nrm = e.normal;
  NormalMap dn = NormalMap::Zero();
  if (options.linearized_normal && !current_normal(e, q_i, q_j, nrm, dn)) {
    nrm = e.normal;
    dn.setZero();
  }
  r.normal = nrm;
  const Section s_i = section_at(e.particle_i, q_i), s_j = section_at(e.particle_j, q_j);
  const CentreFacing g = centre_facing(e, s_i, s_j, nrm, dn);
  Particle p_i = e.particle_i, p_j = e.particle_j;
  p_i.transverse = g.xi_i;
  p_j.transverse = g.xi_j;
  const ParticleMap b_i = particle_map(p_i), b_j = particle_map(p_j);
  Eigen::Matrix<double, 3, 2 * n> c;
  c << -b_i, b_j;
  r.gap = g.gap;
  r.normal_reaction = normal_reaction(normal, r.gap);
  const double k_n = normal_stiffness(normal, r.gap);
  Eigen::Vector3d force_on_j = r.normal_reaction * nrm;
  r.friction = FrictionResponse{};
  Mat3 friction_stiffness = Mat3::Zero();
  if (friction) {
    const Eigen::Vector3d du = (b_j * (q_j - q_j_committed)) - (b_i * (q_i - q_i_committed));
    r.friction = friction_response(*friction, r.normal_reaction, nrm, reversible_committed, du);
    force_on_j += r.friction.force;
    friction_stiffness = r.friction.stiffness;  // R_N held fixed, the normal too (as contact_response)
  }
  r.force = -c.transpose() * force_on_j;
  r.tangent = c.transpose() * friction_stiffness * c;
  if (!(r.normal_reaction > 0.0) && !(k_n > 0.0)) return;
  // d force_on_j = -k_N m dgap + R_N dn, m = n (or force_on_j / R_N where the friction force's dependence on
  // R_N is linearised); the residual -C^T force_on_j also moves with the particles: B_I^T F on I gains
  // N_k F dxi_a in the rows of director a of node k, -B_J^T F on J loses as much.
  const Eigen::Vector3d m = options.friction_normal_coupling && r.normal_reaction > 0.0
                                ? Eigen::Vector3d(force_on_j / r.normal_reaction)
                                : nrm;
  r.tangent += c.transpose() * (k_n * m * g.dgap - r.normal_reaction * dn);
  const Eigen::Vector3d applied =
      options.friction_normal_coupling ? force_on_j : Eigen::Vector3d(r.normal_reaction * nrm);
  for (int k = 0; k < beam::kElementNodes; ++k) {
    const double v_i = s_i.shape.value[static_cast<std::size_t>(k)];
    const double v_j = s_j.shape.value[static_cast<std::size_t>(k)];
    for (int a = 0; a < 2; ++a) {
      r.tangent.block<3, 2 * n>(beam::kNodeDofs * k + 3 + 3 * a, 0) += v_i * applied * g.dxi_i.row(a);
      r.tangent.block<3, 2 * n>(n + beam::kNodeDofs * k + 3 + 3 * a, 0) -= v_j * applied * g.dxi_j.row(a);
    }
  }
}

}  // namespace

ContactResponse contact_response(const ContactElement& e, const beam::ElementVector& q_i,
                                 const beam::ElementVector& q_j, const beam::ElementVector& q_i_committed,
                                 const beam::ElementVector& q_j_committed, const NormalLaw& normal,
                                 const FrictionLaw* friction, const Eigen::Vector3d& reversible_committed,
                                 const ResponseOptions& options) {
  ContactResponse r;
  contact_response(e, q_i, q_j, q_i_committed, q_j_committed, normal, friction, reversible_committed, options,
                   r);
  return r;
}

void contact_response(const ContactElement& e, const beam::ElementVector& q_i, const beam::ElementVector& q_j,
                      const beam::ElementVector& q_i_committed, const beam::ElementVector& q_j_committed,
                      const NormalLaw& normal, const FrictionLaw* friction,
                      const Eigen::Vector3d& reversible_committed, const ResponseOptions& options,
                      ContactResponse& r) {
  if (options.facing_particles && options.centre_facing) {
    centre_facing_response(e, q_i, q_j, q_i_committed, q_j_committed, normal, friction, reversible_committed,
                           options, r);
    return;
  }
  constexpr int n = beam::kElementDofs;
  // Facing particles: I's particle is the point of its border furthest along +n, J's along -n. Then the gap
  // is n.(r_J - r_I) - h_I - h_J with h the support function of the section, and the particles' motion along
  // the border does not change it to first order (the force is that of fixed particles at the facing points);
  // the second order adds -R_N d2gap/dq2 = R_N (d2h_I + d2h_J) to the tangent. With fixed particles, a
  // rotation of a section about its axis carries its particle off the line of the force, whose lever arm then
  // turns the section further: a torsional stiffness -R R_N per particle, which in a tightened knot outweighs
  // the rod's torsional stiffness, so that every detection (particles put back facing) twisted the knot back
  // and forth.
  Eigen::Vector3d nrm = e.normal;
  NormalMap dn;
  const bool linearized = options.linearized_normal && current_normal(e, q_i, q_j, nrm, dn);
  r.normal = nrm;
  const Facing f_i = options.facing_particles ? facing(e.particle_i, q_i, nrm) : Facing{e.particle_i};
  const Facing f_j = options.facing_particles ? facing(e.particle_j, q_j, -nrm) : Facing{e.particle_j};
  const ParticleMap b_i = particle_map(f_i.particle), b_j = particle_map(f_j.particle);
  // Relative position of the particles, x_J - x_I = C (q_I, q_J) with C = [-B_I, B_J] (Eq. 65-67).
  Eigen::Matrix<double, 3, 2 * n> c;
  c << -b_i, b_j;
  r.gap = nrm.dot(b_j * q_j - b_i * q_i);  // Eq. 45 with the particles and the normal fixed
  r.normal_reaction = normal_reaction(normal, r.gap);
  Mat3 stiffness = normal_stiffness(normal, r.gap) * nrm * nrm.transpose();
  Eigen::Vector3d force_on_j = r.normal_reaction * nrm;
  r.friction = FrictionResponse{};
  if (friction) {
    const Eigen::Vector3d du = (b_j * (q_j - q_j_committed)) - (b_i * (q_i - q_i_committed));
    r.friction = friction_response(*friction, r.normal_reaction, nrm, reversible_committed, du);
    force_on_j += r.friction.force;
    stiffness += r.friction.stiffness;  // R_N held fixed (the paper's simplification, Sect. 5.3)
    // The friction force is proportional to R_N: d force_on_j / d(x_J - x_I) gains (force / R_N) dR_N/dgap
    // n^T, so K = -d force_on_j / d(x_J - x_I) gains k_N / R_N force n^T (k_N = -dR_N/dgap). Without it
    // Newton converges linearly (|R| halved per iteration in a tightened knot) wherever friction is active.
    if (options.friction_normal_coupling && r.normal_reaction > 0.0)
      stiffness += (normal_stiffness(normal, r.gap) / r.normal_reaction) * r.friction.force * nrm.transpose();
  }
  // The force on J acts as an external load +force_on_j on J's particle and -force_on_j on I's:
  // f_int - f_ext gains -C^T force_on_j; its derivative is C^T K C with K = -d force_on_j / d(x_J - x_I).
  r.force = -c.transpose() * force_on_j;
  r.tangent = c.transpose() * stiffness * c;
  if (options.facing_particles && r.normal_reaction > 0.0) {
    // The force on J's particle, F, acts at the facing points, which move along the borders with the
    // directors: d(B^T F)/dq through xi adds N_k N_l (d2h)_ab F n^T on each side; for F = R_N n this is the
    // curvature of the gap above (symmetric). The part of the friction force is not symmetric and goes with
    // the coupling. (The friction increment's own dependence on where the particle sits, B'(xi) (q -
    // q_committed), is left out: it is of the order of the step's increment.)
    const Mat3 nn = options.friction_normal_coupling ? Mat3(force_on_j * nrm.transpose())
                                                     : Mat3(r.normal_reaction * nrm * nrm.transpose());
    const auto add = [&](int offset, const Facing& f) {
      for (int k = 0; k < beam::kElementNodes; ++k)
        for (int l = 0; l < beam::kElementNodes; ++l)
          for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
              r.tangent.block<3, 3>(offset + beam::kNodeDofs * k + 3 + 3 * a,
                                    offset + beam::kNodeDofs * l + 3 + 3 * b) +=
                  (f.shape[k] * f.shape[l] * f.curvature(a, b)) * nn;
    };
    add(0, f_i);
    add(n, f_j);
  }
  if (linearized && r.normal_reaction > 0.0) {
    // The normal follows the state: force_on_j = R_N(gap) n (+ friction) with n = n(q) and gap = <x_J - x_I,
    // n(q)>, so d force_on_j gains (R_N I - k_N m (x_J - x_I)^T) dn, with m = n, or force_on_j / R_N where
    // the friction force's dependence on R_N is linearised (its projection's turn with n is left out).
    // With facing particles, the facing points also move along the borders as n turns: xi = R w / |w|, w =
    // G^T (+-n), so that d xi / dn = +-curvature G^T, and B^T F (on I; -B^T F on J) gains N_k F (curvature
    // G^T)_a dn in the rows of director a of node k, on both sides alike.
    const double k_n = normal_stiffness(normal, r.gap);
    const Eigen::Vector3d relative = b_j * q_j - b_i * q_i;
    const Eigen::Vector3d m =
        options.friction_normal_coupling ? Eigen::Vector3d(force_on_j / r.normal_reaction) : nrm;
    const NormalMap dforce = r.normal_reaction * dn - k_n * m * (relative.transpose() * dn);
    r.tangent -= c.transpose() * dforce;
    if (options.facing_particles) {
      const Eigen::Vector3d applied =
          options.friction_normal_coupling ? force_on_j : Eigen::Vector3d(r.normal_reaction * nrm);
      const auto add = [&](int offset, const Facing& f) {
        const Eigen::Matrix<double, 2, 2 * n> dxi = f.curvature * (f.directors.transpose() * dn);
        for (int k = 0; k < beam::kElementNodes; ++k)
          for (int a = 0; a < 2; ++a)
            r.tangent.block<3, 2 * n>(offset + beam::kNodeDofs * k + 3 + 3 * a, 0) +=
                f.shape[k] * applied * dxi.row(a);
      };
      add(0, f_i);
      add(n, f_j);
    }
  }
}

}  // namespace nodus::contact
