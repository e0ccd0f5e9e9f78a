// The normal of a contact element as a function of the state (normal_direction.hpp) and the contact
// element's tangent with that normal linearised (ResponseOptions::linearized_normal): the normal's
// derivative against central finite differences of the normal itself, in each regime of Eq. 41-44 (cross
// product, blend, double cross product); the element's tangent against central finite differences of its
// force, with fixed and with facing particles. Units: mm, N.

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/normal_direction.hpp"

namespace nodus::contact {
namespace {

using beam::ElementVector;
using beam::kElementDofs;
using beam::kNodeDofs;
using Vec3 = Eigen::Vector3d;

constexpr int kPairDofs = 2 * kElementDofs;
constexpr double kPenalty = 1000.0;       // k [N/mm]
constexpr double kRegularization = 0.01;  // p_reg [mm]
constexpr double kDegree = std::numbers::pi / 180.0;

/// The quadratic Lagrange shape functions with nodes at xi = -1, 0, 1, and their derivatives.
std::array<double, 3> lagrange(double xi) {
  return {xi * (xi - 1.0) / 2.0, (1.0 - xi) * (1.0 + xi), xi * (xi + 1.0) / 2.0};
}
std::array<double, 3> lagrange_derivative(double xi) {
  return {xi - 0.5, -2.0 * xi, xi + 0.5};
}

/// Axis position and derivative (along the element coordinate) of element `q` at `xi`.
void axis(const ElementVector& q, double xi, Vec3& r, Vec3& dr) {
  const std::array<double, 3> n = lagrange(xi), dn = lagrange_derivative(xi);
  r.setZero();
  dr.setZero();
  for (int k = 0; k < 3; ++k) {
    r += n[static_cast<std::size_t>(k)] * q.segment<3>(9 * k);
    dr += dn[static_cast<std::size_t>(k)] * q.segment<3>(9 * k);
  }
}

/// A slightly curved element of length 2 h through `centre` along `direction`, with perturbed directors
/// orthogonal to it in the mean.
ElementVector element_along(std::mt19937& rng, const Vec3& centre, const Vec3& direction, double h) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 g1 = direction.unitOrthogonal(), g2 = direction.cross(g1);
  ElementVector q;
  for (int k = 0; k < 3; ++k) {
    const Vec3 wobble = 0.005 * h * Vec3(u(rng), u(rng), u(rng));
    q.segment<3>(9 * k) = centre + (k - 1) * h * direction + wobble;
    q.segment<3>(9 * k + 3) = g1 + 0.05 * Vec3(u(rng), u(rng), u(rng));
    q.segment<3>(9 * k + 6) = g2 + 0.05 * Vec3(u(rng), u(rng), u(rng));
  }
  return q;
}

struct Crossing {
  ContactElement e;
  ElementVector q_i, q_j;
  PairVector q() const {
    PairVector v;
    v << q_i, q_j;
    return v;
  }
};

/// Two elements crossing at `angle`, the particles at random abscissas near the middle, facing each other
/// along the normal of the state, and J moved along that normal until the gap is `gap`.
Crossing crossing(std::mt19937& rng, double angle, double gap) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 0.05, r_i = 0.1, r_j = 0.08;
  Crossing c;
  c.q_i = element_along(rng, Vec3::Zero(), Vec3::UnitX(), h);
  c.q_j = element_along(rng, Vec3(0.0, 0.0, r_i + r_j), Vec3(std::cos(angle), std::sin(angle), 0.0), h);
  c.e.particle_i = {0, 3, 0.3 * u(rng), 0.0, Eigen::Vector2d(r_i, 0.0)};
  c.e.particle_j = {1, 11, 0.3 * u(rng), 0.0, Eigen::Vector2d(r_j, 0.0)};
  // Particles at the facing points of the normal, then J shifted along it. The shift changes the direction
  // between the centres, hence the normal where the double cross product has a part: repeated until the
  // normal stands still.
  const auto directors = [](const ElementVector& q, double xi, Vec3& g1, Vec3& g2) {
    const std::array<double, 3> s = lagrange(xi);
    g1.setZero();
    g2.setZero();
    for (int k = 0; k < 3; ++k) {
      g1 += s[static_cast<std::size_t>(k)] * q.segment<3>(9 * k + 3);
      g2 += s[static_cast<std::size_t>(k)] * q.segment<3>(9 * k + 6);
    }
  };
  NormalDirection n;
  for (int pass = 0; pass < 50; ++pass) {
    Vec3 ri, dri, rj, drj, g1, g2;
    axis(c.q_i, c.e.particle_i.local, ri, dri);
    axis(c.q_j, c.e.particle_j.local, rj, drj);
    EXPECT_TRUE(normal_direction(ri, dri, rj, drj, 1e-12, n));
    directors(c.q_i, c.e.particle_i.local, g1, g2);
    EXPECT_TRUE(facing_point(g1, g2, n.normal, r_i, c.e.particle_i.transverse));
    const Vec3 x_i = ri + c.e.particle_i.transverse.x() * g1 + c.e.particle_i.transverse.y() * g2;
    directors(c.q_j, c.e.particle_j.local, g1, g2);
    EXPECT_TRUE(facing_point(g1, g2, -n.normal, r_j, c.e.particle_j.transverse));
    const Vec3 x_j = rj + c.e.particle_j.transverse.x() * g1 + c.e.particle_j.transverse.y() * g2;
    const double shift = gap - n.normal.dot(x_j - x_i);
    if (std::abs(shift) < 1e-15) break;
    for (int k = 0; k < 3; ++k) c.q_j.segment<3>(9 * k) += shift * n.normal;
  }
  c.e.normal = n.normal;
  return c;
}

struct Regime {
  const char* name;
  double angle;
  double parallel_weight_lo, parallel_weight_hi;
};
constexpr Regime kRegimes[] = {
    {"cross product, 60 degrees", 60.0 * kDegree, 0.0, 0.0},
    {"blend, 10 degrees", 10.0 * kDegree, 0.05, 0.95},
    {"double cross product, 2 degrees", 2.0 * kDegree, 1.0, 1.0},
};

TEST(NormalDirection, DerivativeMatchesFiniteDifferencesInEachRegime) {
  std::mt19937 rng(71);
  for (const Regime& regime : kRegimes) {
    for (int trial = 0; trial < 4; ++trial) {
      const Crossing c = crossing(rng, regime.angle, -0.004);
      std::array<Vec3, 4> x;
      axis(c.q_i, c.e.particle_i.local, x[0], x[1]);
      axis(c.q_j, c.e.particle_j.local, x[2], x[3]);
      NormalDirection n, plain;
      NormalJacobian jacobian;
      ASSERT_TRUE(normal_direction(x[0], x[1], x[2], x[3], 1e-12, n, jacobian)) << regime.name;
      ASSERT_TRUE(normal_direction(x[0], x[1], x[2], x[3], 1e-12, plain)) << regime.name;
      // The differentiated function is the same function.
      EXPECT_LT((n.normal - plain.normal).norm(), 1e-15) << regime.name;
      EXPECT_NEAR(n.parallel_weight, plain.parallel_weight, 1e-15) << regime.name;
      EXPECT_GE(n.parallel_weight, regime.parallel_weight_lo) << regime.name;
      EXPECT_LE(n.parallel_weight, regime.parallel_weight_hi) << regime.name;
      EXPECT_NEAR(n.normal.norm(), 1.0, 1e-14);
      // Central differences; the normal is smooth (C1 blend, away from the blend's ends by construction of
      // the regimes: 60 and 2 degrees lie in the flat parts of the smoothstep), truncation ~ (h / 0.05)^2.
      const double h = 1e-7;
      NormalJacobian fd;
      for (int m = 0; m < 12; ++m) {
        std::array<Vec3, 4> plus = x, minus = x;
        plus[static_cast<std::size_t>(m / 3)][m % 3] += h;
        minus[static_cast<std::size_t>(m / 3)][m % 3] -= h;
        NormalDirection a, b;
        ASSERT_TRUE(normal_direction(plus[0], plus[1], plus[2], plus[3], 1e-12, a));
        ASSERT_TRUE(normal_direction(minus[0], minus[1], minus[2], minus[3], 1e-12, b));
        fd.col(m) = (a.normal - b.normal) / (2.0 * h);
      }
      const double scale = fd.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 1.0) << regime.name;  // the normal does turn with the state (|d n / d x| ~ 1 / R)
      EXPECT_LT((jacobian - fd).cwiseAbs().maxCoeff(), 1e-6 * scale) << regime.name;
      // A rigid translation of both sections does not turn the normal.
      EXPECT_LT((jacobian.block<3, 3>(0, 0) + jacobian.block<3, 3>(0, 6)).cwiseAbs().maxCoeff(),
                1e-12 * scale);
      // Nor does stretching a tangent (only its direction counts).
      EXPECT_LT((jacobian.block<3, 3>(0, 3) * x[1]).norm(), 1e-12 * scale);
      EXPECT_LT((jacobian.block<3, 3>(0, 9) * x[3]).norm(), 1e-12 * scale);
    }
  }
}

/// The element's force and tangent with the normal following the state (frictionless).
ContactResponse respond(const Crossing& c, const PairVector& x, bool facing, bool linearized = true,
                        bool centre_facing = false) {
  ResponseOptions options;
  options.facing_particles = facing;
  options.linearized_normal = linearized;
  options.centre_facing = centre_facing;
  const NormalLaw law{kPenalty, kRegularization};
  return contact_response(c.e, x.head<kElementDofs>(), x.tail<kElementDofs>(), x.head<kElementDofs>(),
                          x.tail<kElementDofs>(), law, nullptr, Vec3::Zero(), options);
}

/// Central differences of f at q, h = 1e-7 mm against distances to the law's joints >= 4e-3 mm and lengths
/// >= 0.05 mm: truncation ~ (h / 0.05)^2 relative, rounding ~ 1e-16 / h.
template <class F>
PairMatrix finite_difference(const PairVector& q, F&& f) {
  const double h = 1e-7;
  PairMatrix fd;
  for (int m = 0; m < kPairDofs; ++m) {
    PairVector plus = q, minus = q;
    plus[m] += h;
    minus[m] -= h;
    fd.col(m) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return fd;
}

TEST(LinearizedNormal, TangentIsTheDerivativeOfTheForce) {
  std::mt19937 rng(72);
  int compared = 0;
  for (const Regime& regime : kRegimes) {
    for (const double gap : {-0.4 * kRegularization, -2.5 * kRegularization}) {
      for (const bool facing : {false, true}) {
        const Crossing c = crossing(rng, regime.angle, gap);
        const PairVector q = c.q();
        const ContactResponse r = respond(c, q, facing);
        EXPECT_NEAR(r.gap, gap, 1e-12) << regime.name;
        EXPECT_LT((r.normal - c.e.normal).norm(), 1e-14) << regime.name;
        // The same force as the element with the state's normal fixed: only the tangent differs.
        ResponseOptions fixed_options;
        fixed_options.facing_particles = facing;
        const ContactResponse fixed =
            contact_response(c.e, c.q_i, c.q_j, c.q_i, c.q_j, {kPenalty, kRegularization}, nullptr,
                             Vec3::Zero(), fixed_options);
        EXPECT_LT((r.force - fixed.force).cwiseAbs().maxCoeff(), 1e-12 * fixed.force.cwiseAbs().maxCoeff());
        const PairMatrix fd =
            finite_difference(q, [&](const PairVector& x) { return respond(c, x, facing).force; });
        const double scale = fd.cwiseAbs().maxCoeff();
        ASSERT_GT(scale, 0.0);
        EXPECT_LT((r.tangent - fd).cwiseAbs().maxCoeff(), 1e-6 * scale)
            << regime.name << ", gap " << gap << (facing ? ", facing" : ", fixed");
        // The part the normal's turn adds is not negligible: without it the tangent is off.
        EXPECT_GT((fixed.tangent - fd).cwiseAbs().maxCoeff(), 1e-3 * scale) << regime.name;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 3 * 2 * 2);
}

/// Particles facing each other along the centres' direction (ResponseOptions::centre_facing): the tangent
/// is the derivative of the force, the particles moving with the centres and the directors, with the normal
/// held fixed and with the normal following the state.
TEST(CentreFacing, TangentIsTheDerivativeOfTheForce) {
  std::mt19937 rng(73);
  int compared = 0;
  for (const Regime& regime : kRegimes) {
    for (const double gap : {-0.4 * kRegularization, -2.5 * kRegularization}) {
      for (const bool linearized : {false, true}) {
        const Crossing c = crossing(rng, regime.angle, gap);
        const PairVector q = c.q();
        const ContactResponse r = respond(c, q, true, linearized, true);
        ASSERT_LT(r.gap, 0.0) << regime.name;
        const PairMatrix fd = finite_difference(
            q, [&](const PairVector& x) { return respond(c, x, true, linearized, true).force; });
        const double scale = fd.cwiseAbs().maxCoeff();
        ASSERT_GT(scale, 0.0);
        EXPECT_LT((r.tangent - fd).cwiseAbs().maxCoeff(), 1e-6 * scale)
            << regime.name << ", gap " << gap << (linearized ? ", linearized" : ", fixed normal");
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 3 * 2 * 2);
}

/// Two straight beams crossing at right angles, I along x through the origin, J along y at height D: the
/// sections at x = u on I and y = v on J, off the crossing. Along the normal (e_z) the facing points sit a
/// full radius towards each other wherever the sections are, so that the gap is D - R_I - R_J all along the
/// zone; along the centres' direction the gap is D - R_I D / hypot(v, D) - R_J D / hypot(u, D) (the
/// closed form of the detection's elements, docs/contact.md), which grows away from the crossing.
TEST(CentreFacing, GapGrowsAwayFromACrossingWhereTheNormalsFacingPointsDoNot) {
  const double r_i = 0.1, r_j = 0.08, depth = 0.17, h = 0.05;
  ContactElement e;
  e.normal = Vec3::UnitZ();
  ElementVector q_i, q_j;
  for (int k = 0; k < 3; ++k) {
    q_i.segment<3>(9 * k) = Vec3((k - 1) * h, 0.0, 0.0);
    q_i.segment<3>(9 * k + 3) = Vec3::UnitY();
    q_i.segment<3>(9 * k + 6) = Vec3::UnitZ();
    q_j.segment<3>(9 * k) = Vec3(0.0, (k - 1) * h, depth);
    q_j.segment<3>(9 * k + 3) = Vec3::UnitX();
    q_j.segment<3>(9 * k + 6) = Vec3::UnitZ();
  }
  const NormalLaw law{kPenalty, kRegularization};
  int compared = 0;
  for (const double u : {0.0, 0.02, 0.04}) {
    for (const double v : {0.0, 0.03}) {
      e.particle_i = {0, 0, u / h, 0.0, Eigen::Vector2d(0.0, r_i)};
      e.particle_j = {1, 1, v / h, 0.0, Eigen::Vector2d(0.0, -r_j)};
      ResponseOptions along_normal;
      along_normal.facing_particles = true;
      ResponseOptions along_centres = along_normal;
      along_centres.centre_facing = true;
      const ContactResponse a =
          contact_response(e, q_i, q_j, q_i, q_j, law, nullptr, Vec3::Zero(), along_normal);
      const ContactResponse b =
          contact_response(e, q_i, q_j, q_i, q_j, law, nullptr, Vec3::Zero(), along_centres);
      EXPECT_NEAR(a.gap, depth - r_i - r_j, 1e-14) << u << " " << v;
      EXPECT_NEAR(b.gap, depth - r_i * depth / std::hypot(v, depth) - r_j * depth / std::hypot(u, depth),
                  1e-14)
          << u << " " << v;
      compared += 2;
    }
  }
  EXPECT_EQ(compared, 12);
}

}  // namespace
}  // namespace nodus::contact
