// Contact mechanics against independent references [Durville 2012, Sect. 5, Eq. 49-79]: the regularised
// penalty law (Eq. 53) against its formula, its continuity and its derivative; the return mapping of the
// regularised Coulomb friction (Eq. 55-64) against its definition and its derivative; the particle map
// (Eq. 65-67) against the quadratic Lagrange interpolation written out here; and the element's residual and
// tangent over the 54 unknowns against the particle positions, the potential of the normal reaction, and
// central finite differences. Units: mm, N.

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "nodus/contact/contact_mechanics.hpp"

namespace nodus::contact {
namespace {

using beam::ElementVector;
using beam::kElementDofs;
using beam::kElementNodes;
using beam::kNodeDofs;

constexpr int kPairDofs = 2 * kElementDofs;
constexpr double kPenalty = 1000.0;       // k [N/mm]
constexpr double kRegularization = 0.01;  // p [mm]

NormalLaw normal_law() {
  return {kPenalty, kRegularization};
}

// ---------------------------------------------------------------------------------------------------------
// Independent references.

/// Eq. 53, written from the paper: 0 for g >= 0, k g^2 / (2 p) on [-p, 0], -k (g + p / 2) below.
double reference_reaction(double g) {
  const double k = kPenalty, p = kRegularization;
  if (g >= 0.0) return 0.0;
  if (g >= -p) return k * g * g / (2.0 * p);
  return -k * (g + 0.5 * p);
}

/// Psi(g) = -integral_0^g R_N(s) ds, so that dPsi/dg = -R_N: 0 for g >= 0; -k g^3 / (6 p) on [-p, 0];
/// k p^2 / 6 + k ((g + p/2)^2 - p^2/4) / 2 below (continuous at -p: both k p^2 / 6).
double reference_potential(double g) {
  const double k = kPenalty, p = kRegularization;
  if (g >= 0.0) return 0.0;
  if (g >= -p) return -k * g * g * g / (6.0 * p);
  return k * p * p / 6.0 + 0.5 * k * ((g + 0.5 * p) * (g + 0.5 * p) - 0.25 * p * p);
}

/// The quadratic Lagrange shape functions with nodes at xi = -1, 0, 1.
std::array<double, 3> lagrange(double xi) {
  return {xi * (xi - 1.0) / 2.0, (1.0 - xi) * (1.0 + xi), xi * (xi + 1.0) / 2.0};
}

/// Position of a material particle: sum_k N_k(xi3) (r_k + xi1 g1_k + xi2 g2_k), q = 3 nodes x (r, g1, g2).
Vec3 particle_position(const Particle& p, const ElementVector& q) {
  const std::array<double, 3> n = lagrange(p.local);
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const Vec3 r = q.segment<3>(9 * k), g1 = q.segment<3>(9 * k + 3), g2 = q.segment<3>(9 * k + 6);
    x += n[static_cast<std::size_t>(k)] * (r + p.transverse.x() * g1 + p.transverse.y() * g2);
  }
  return x;
}

/// The generalised force on the 27 unknowns of a point force f at the particle: d(<x, f>)/dq = B^T f.
ElementVector spread(const Particle& p, const Vec3& f) {
  const std::array<double, 3> n = lagrange(p.local);
  ElementVector out;
  for (int k = 0; k < 3; ++k) {
    const double v = n[static_cast<std::size_t>(k)];
    out.segment<3>(9 * k) = v * f;
    out.segment<3>(9 * k + 3) = v * p.transverse.x() * f;
    out.segment<3>(9 * k + 6) = v * p.transverse.y() * f;
  }
  return out;
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

/// A random unit vector orthogonal to n.
Vec3 random_tangent(std::mt19937& rng, const Vec3& n) {
  const Vec3 v = random_unit(rng);
  return (v - v.dot(n) * n).normalized();
}

Eigen::Matrix3d tangential_projector(const Vec3& n) {
  return Eigen::Matrix3d::Identity() - n * n.transpose();
}

// ---------------------------------------------------------------------------------------------------------
// 1. The normal law.

TEST(ContactNormalLaw, ValuesFollowEq53) {
  const NormalLaw law = normal_law();
  // Hand-computed with k = 1000 N/mm, p = 0.01 mm.
  struct Case {
    double gap, reaction, stiffness;
  };
  const Case cases[] = {
      {0.005, 0.0, 0.0},         // apart
      {0.0, 0.0, 0.0},           // touching
      {-0.0025, 0.3125, 250.0},  // 1000 * 0.0025^2 / 0.02; 1000 * 0.0025 / 0.01
      {-0.005, 1.25, 500.0},     // 1000 * 0.005^2 / 0.02
      {-0.01, 5.0, 1000.0},      // k p / 2: end of the zone
      {-0.015, 10.0, 1000.0},    // -1000 * (-0.015 + 0.005)
      {-0.04, 35.0, 1000.0},     // -1000 * (-0.04 + 0.005)
  };
  int compared = 0;
  for (const Case& c : cases) {
    EXPECT_NEAR(normal_reaction(law, c.gap), c.reaction, 1e-12 * kPenalty * kRegularization) << c.gap;
    EXPECT_NEAR(normal_reaction(law, c.gap), reference_reaction(c.gap), 1e-12 * kPenalty * kRegularization);
    EXPECT_NEAR(normal_stiffness(law, c.gap), c.stiffness, 1e-12 * kPenalty) << c.gap;
    compared += 3;
  }
  EXPECT_EQ(compared, 21);
}

TEST(ContactNormalLaw, ReactionAndItsDerivativeAreContinuousAtTheJoints) {
  const NormalLaw law = normal_law();
  const double p = kRegularization, k = kPenalty;
  int compared = 0;
  for (const double joint : {0.0, -p}) {
    // Values just either side of the joint.
    const double d = 1e-12 * p;
    const double below = normal_reaction(law, joint - d), above = normal_reaction(law, joint + d);
    EXPECT_NEAR(below, above, 1e-9 * k * p) << "R_N at " << joint;
    EXPECT_NEAR(normal_reaction(law, joint), reference_reaction(joint), 1e-12 * k * p);
    EXPECT_NEAR(normal_stiffness(law, joint - d), normal_stiffness(law, joint + d), 1e-9 * k) << joint;
    // One-sided derivatives from each side by three-point formulas, exact for the quadratic pieces of R_N:
    // f'(x) = (3 f(x) - 4 f(x - h) + f(x - 2h)) / 2h from below, (-3 f(x) + 4 f(x + h) - f(x + 2h)) / 2h
    // from above.
    const double h = 1e-3 * p;
    auto r = [&](double g) { return normal_reaction(law, g); };
    const double left = (3.0 * r(joint) - 4.0 * r(joint - h) + r(joint - 2.0 * h)) / (2.0 * h);
    const double right = (-3.0 * r(joint) + 4.0 * r(joint + h) - r(joint + 2.0 * h)) / (2.0 * h);
    EXPECT_NEAR(left, right, 1e-9 * k) << "dR_N/dgap at " << joint;
    EXPECT_NEAR(-left, normal_stiffness(law, joint), 1e-9 * k) << joint;
    compared += 5;
  }
  // The expected one-sided limits: R_N(0) = 0, R_N(-p) = k p / 2; -dR_N/dgap = 0 at 0 and k at -p.
  EXPECT_NEAR(normal_reaction(law, -p), 0.5 * k * p, 1e-12 * k * p);
  EXPECT_NEAR(normal_stiffness(law, -p), k, 1e-12 * k);
  EXPECT_EQ(normal_stiffness(law, 0.0), 0.0);
  EXPECT_EQ(compared, 10);
}

TEST(ContactNormalLaw, StiffnessIsMinusTheDerivativeOfTheReaction) {
  const NormalLaw law = normal_law();
  const double p = kRegularization, k = kPenalty;
  // 20 gaps -2.9p, -2.7p, ..., 0.9p: the nearest to a joint (0 or -p) is 0.1p away, far beyond the step.
  // R_N is piecewise quadratic, so central differences are exact but for rounding (~1e-16 * 35 N / 2e-6 mm).
  const double h = 1e-4 * p;
  int compared = 0;
  for (int i = 0; i < 20; ++i) {
    const double g = -3.0 * p + (i + 0.5) * 0.2 * p;
    const double fd = -(normal_reaction(law, g + h) - normal_reaction(law, g - h)) / (2.0 * h);
    EXPECT_NEAR(normal_stiffness(law, g), fd, 1e-9 * k) << "gap " << g;
    EXPECT_GE(normal_stiffness(law, g), 0.0);
    ++compared;
  }
  EXPECT_EQ(compared, 20);
}

// ---------------------------------------------------------------------------------------------------------
// 2. Friction.

constexpr double kMu = 0.3;
constexpr double kReaction = 5.0;  // R_N [N]

TEST(ContactFriction, StickKeepsTheProjectedTrial) {
  const FrictionLaw law{kMu, 0.02};
  std::mt19937 rng(11);
  int compared = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3 n = random_unit(rng);
    // Committed value with a normal component (the normal has turned since), increment of any direction:
    // |P (g_n + du)| <= 0.6 g_max.
    const Vec3 committed = 0.3 * law.max_reversible * random_unit(rng);
    const Vec3 du = 0.3 * law.max_reversible * random_unit(rng);
    const FrictionResponse r = friction_response(law, kReaction, n, committed, du);
    const Vec3 expected = tangential_projector(n) * (committed + du);
    ASSERT_LE(expected.norm(), law.max_reversible);
    EXPECT_FALSE(r.slip);
    EXPECT_LT((r.reversible - expected).norm(), 1e-15);
    EXPECT_LT((r.force + kMu * kReaction / law.max_reversible * expected).norm(), 1e-13);
    EXPECT_NEAR(r.force.dot(n), 0.0, 1e-14 * kMu * kReaction);
    EXPECT_NEAR(r.reversible.dot(n), 0.0, 1e-16);
    compared += 4;
  }
  EXPECT_EQ(compared, 40);
}

TEST(ContactFriction, SlipReachesTheCoulombLimit) {
  const FrictionLaw law{kMu, 0.02};
  std::mt19937 rng(12);
  int compared = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3 n = random_unit(rng);
    // A tangential increment of 3 g_max plus a normal part, and a committed value of 0.5 g_max:
    // |trial| >= 2.5 g_max.
    const Vec3 committed = 0.5 * law.max_reversible * random_unit(rng);
    const Vec3 du = law.max_reversible * (3.0 * random_tangent(rng, n) + random_unit(rng).dot(n) * n);
    const FrictionResponse r = friction_response(law, kReaction, n, committed, du);
    const Vec3 tangential_trial = tangential_projector(n) * (committed + du);
    ASSERT_GT(tangential_trial.norm(), 2.0 * law.max_reversible);
    EXPECT_TRUE(r.slip);
    EXPECT_NEAR(r.reversible.norm(), law.max_reversible, 1e-15);
    EXPECT_NEAR(r.reversible.dot(n), 0.0, 1e-16);
    EXPECT_NEAR(r.force.norm(), kMu * kReaction, 1e-13);
    EXPECT_NEAR(r.force.dot(n), 0.0, 1e-14 * kMu * kReaction);
    // Opposite to the tangential trial direction.
    EXPECT_LT((r.force / (kMu * kReaction) + tangential_trial.normalized()).norm(), 1e-14);
    EXPECT_LT((r.reversible / law.max_reversible - tangential_trial.normalized()).norm(), 1e-14);
    compared += 6;
  }
  EXPECT_EQ(compared, 60);
}

TEST(ContactFriction, NoForceAndNoMemoryWithoutFrictionOrPressure) {
  std::mt19937 rng(13);
  const Vec3 n = random_unit(rng);
  const Vec3 committed = 0.005 * random_unit(rng), du = 0.01 * random_unit(rng);
  for (const auto& [mu, reaction] : {std::pair{0.0, kReaction}, std::pair{kMu, 0.0}}) {
    const FrictionResponse r = friction_response({mu, 0.02}, reaction, n, committed, du);
    EXPECT_EQ(r.force, Vec3::Zero()) << mu << " " << reaction;
    EXPECT_EQ(r.reversible, Vec3::Zero()) << mu << " " << reaction;
    EXPECT_EQ(r.stiffness, Eigen::Matrix3d::Zero());
    EXPECT_FALSE(r.slip);
  }
}

TEST(ContactFriction, StiffnessIsMinusTheDerivativeOfTheForce) {
  const FrictionLaw law{kMu, 0.02};
  const double g_max = law.max_reversible;
  // Stick: the force is linear in du, central differences are exact but for rounding. Slip: the error is
  // ~(h / |trial|)^2 ~ 1e-15. Rounding: ~1e-16 * mu R_N / h, i.e. 1e-9 of the stiffness scale mu R_N / g_max.
  const double h = 1e-7 * g_max, scale = kMu * kReaction / g_max;
  int compared = 0;
  for (const unsigned seed : {21u, 22u, 23u, 24u, 25u}) {
    std::mt19937 rng(seed);
    const Vec3 n = random_unit(rng);
    for (const bool slip : {false, true}) {
      const Vec3 committed = (slip ? 0.5 : 0.3) * g_max * random_unit(rng);
      const Vec3 du = slip ? Vec3(g_max * (3.0 * random_tangent(rng, n) + 0.7 * n))
                           : Vec3(0.3 * g_max * random_unit(rng));
      const FrictionResponse r = friction_response(law, kReaction, n, committed, du);
      ASSERT_EQ(r.slip, slip);
      for (int m = 0; m < 3; ++m) {
        Vec3 plus = du, minus = du;
        plus[m] += h;
        minus[m] -= h;
        const Vec3 fd = -(friction_response(law, kReaction, n, committed, plus).force -
                          friction_response(law, kReaction, n, committed, minus).force) /
                        (2.0 * h);
        for (int l = 0; l < 3; ++l) {
          EXPECT_NEAR(r.stiffness(l, m), fd[l], 1e-6 * scale) << "seed " << seed << " slip " << slip;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 5 * 2 * 9);
}

// ---------------------------------------------------------------------------------------------------------
// 3. The particle map.

TEST(ContactParticleMap, MapsTheUnknownsToTheParticlePosition) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (const double xi : {-1.0, -0.6, 0.0, 0.25, 1.0, u(rng), u(rng), u(rng)}) {
    for (int trial = 0; trial < 3; ++trial) {
      Particle p;
      p.local = xi;
      const double angle = 3.0 * u(rng);
      p.transverse = 0.1 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      ElementVector q;
      for (int i = 0; i < kElementDofs; ++i) q[i] = u(rng);
      const ParticleMap b = particle_map(p);
      const Vec3 expected = particle_position(p, q);
      EXPECT_LT((b * q - expected).norm(), 1e-14) << "xi " << xi;
      // The transpose spreads a point force: B^T f = d<x, f>/dq.
      const Vec3 f = random_unit(rng);
      EXPECT_LT((b.transpose() * f - spread(p, f)).norm(), 1e-15) << "xi " << xi;
      compared += 2;
    }
  }
  EXPECT_EQ(compared, 8 * 3 * 2);
  static_assert(kElementNodes * kNodeDofs == 27);
}

// ---------------------------------------------------------------------------------------------------------
// 4. The contact element.

/// A contact element built by hand and its two elements' states, current and committed.
struct Pair {
  ContactElement e;
  ElementVector q_i, q_j, qc_i, qc_j;
  Vec3 reversible_committed = Vec3::Zero();

  PairVector q() const {
    PairVector v;
    v << q_i, q_j;
    return v;
  }
};

/// Random states of two elements, placed so that the gap is `gap`; committed states differ by up to
/// `increment` in every unknown. Particle I: element 3 of beam 0, radius 0.1 mm; J: element 11 of beam 1,
/// radius 0.08 mm.
Pair random_pair(std::mt19937& rng, double gap, double increment) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Pair p;
  p.e.particle_i.beam = 0;
  p.e.particle_i.element = 3;
  p.e.particle_i.local = u(rng);
  const double a = 3.0 * u(rng), b = 3.0 * u(rng);
  p.e.particle_i.transverse = 0.1 * Eigen::Vector2d(std::cos(a), std::sin(a));
  p.e.particle_j.beam = 1;
  p.e.particle_j.element = 11;
  p.e.particle_j.local = u(rng);
  p.e.particle_j.transverse = 0.08 * Eigen::Vector2d(std::cos(b), std::sin(b));
  p.e.normal = random_unit(rng);
  for (int i = 0; i < kElementDofs; ++i) {
    p.q_i[i] = u(rng);
    p.q_j[i] = u(rng);
  }
  // Moving J's three node positions by s n moves its particle by s n (the shape functions sum to 1).
  const double shift = gap - p.e.normal.dot(particle_position(p.e.particle_j, p.q_j) -
                                            particle_position(p.e.particle_i, p.q_i));
  for (int k = 0; k < 3; ++k) p.q_j.segment<3>(9 * k) += shift * p.e.normal;
  for (int i = 0; i < kElementDofs; ++i) {
    p.qc_i[i] = p.q_i[i] - increment * u(rng);
    p.qc_j[i] = p.q_j[i] - increment * u(rng);
  }
  p.e.position_i = particle_position(p.e.particle_i, p.q_i);
  p.e.position_j = particle_position(p.e.particle_j, p.q_j);
  p.e.gap = gap;
  return p;
}

double test_gap(const Pair& p, const PairVector& q) {
  return p.e.normal.dot(particle_position(p.e.particle_j, q.tail<kElementDofs>()) -
                        particle_position(p.e.particle_i, q.head<kElementDofs>()));
}

/// Relative displacement of J's particle from I's since the committed state.
Vec3 test_increment(const Pair& p, const PairVector& q) {
  return (particle_position(p.e.particle_j, q.tail<kElementDofs>()) -
          particle_position(p.e.particle_j, p.qc_j)) -
         (particle_position(p.e.particle_i, q.head<kElementDofs>()) -
          particle_position(p.e.particle_i, p.qc_i));
}

/// The residual contribution of a force F on J's particle (-F on I's): [B_I^T F; -B_J^T F].
PairVector residual_of(const Pair& p, const Vec3& force_on_j) {
  PairVector v;
  v << spread(p.e.particle_i, force_on_j), -spread(p.e.particle_j, force_on_j);
  return v;
}

/// The residual with the reaction of the normal law at q and friction evaluated with a frozen R_N.
PairVector frozen_residual(const Pair& p, const PairVector& q, const FrictionLaw* friction, double frozen) {
  Vec3 f = reference_reaction(test_gap(p, q)) * p.e.normal;
  if (friction)
    f += friction_response(*friction, frozen, p.e.normal, p.reversible_committed, test_increment(p, q)).force;
  return residual_of(p, f);
}

ContactResponse evaluate(const Pair& p, const PairVector& q, const FrictionLaw* friction) {
  return contact_response(p.e, q.head<kElementDofs>(), q.tail<kElementDofs>(), p.qc_i, p.qc_j, normal_law(),
                          friction, p.reversible_committed);
}

/// Central finite differences of `f` over the 54 unknowns. Step: the normal part is quadratic (zone) or
/// linear (beyond) in the gap and the stick friction linear in du, so central differences are exact but for
/// rounding unless the stencil crosses a joint (gap 0 or -p, |trial| = g_max); a step h moves the gap and
/// du by at most ~h (|B| <= 1 entrywise, transverse <= 0.1 mm), and h = 1e-6 mm is far from the distances
/// to the joints (>= 0.4 p = 4e-3 mm; |trial| is 2x or 1/3x g_max). Rounding: the gap is a difference of
/// O(1 mm) positions, known to ~1e-16 mm, so the force errs by ~k 1e-16 mm and the derivative by
/// ~k 1e-10; slip truncation ~(h / |trial|)^2 ~ 1e-8.
template <class F>
PairMatrix finite_difference(const PairVector& q, F&& f) {
  const double h = 1e-6;
  PairMatrix k;
  for (int m = 0; m < kPairDofs; ++m) {
    PairVector plus = q, minus = q;
    plus[m] += h;
    minus[m] -= h;
    k.col(m) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return k;
}

/// Counts and compares entrywise, to `tol` times the largest entry of `expected`.
int expect_matrix_near(const PairMatrix& actual, const PairMatrix& expected, double tol, const char* what) {
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 0.0) << what;
  int compared = 0;
  for (int j = 0; j < kPairDofs; ++j)
    for (int i = 0; i < kPairDofs; ++i) {
      EXPECT_NEAR(actual(i, j), expected(i, j), tol * scale) << what << " entry " << i << "," << j;
      ++compared;
    }
  return compared;
}

/// The two gaps: inside the regularisation zone and beyond it (away from the joints 0 and -p).
constexpr double kGaps[] = {-0.4 * kRegularization, -2.5 * kRegularization};

TEST(ContactResponse, GapAndForceFollowFromTheParticles) {
  std::mt19937 rng(41);
  int compared = 0;
  for (const double gap : kGaps) {
    for (int regime = 0; regime < 3; ++regime) {  // frictionless, stick, slip
      Pair p = random_pair(rng, gap, 0.02);
      const PairVector q = p.q();
      const Vec3 du = test_increment(p, q);
      p.reversible_committed = 0.001 * random_unit(rng);
      const Vec3 trial = tangential_projector(p.e.normal) * (p.reversible_committed + du);
      ASSERT_GT(trial.norm(), 1e-3);
      const FrictionLaw law{kMu, regime == 1 ? 2.0 * trial.norm() : trial.norm() / 3.0};
      const FrictionLaw* friction = regime == 0 ? nullptr : &law;
      const ContactResponse r = evaluate(p, q, friction);

      EXPECT_NEAR(r.gap, test_gap(p, q), 1e-14) << "gap " << gap;
      EXPECT_NEAR(r.gap, gap, 1e-13);
      const double reaction = reference_reaction(test_gap(p, q));
      EXPECT_NEAR(r.normal_reaction, reaction, 1e-12 * reaction);
      FrictionResponse expected_friction;
      if (friction)
        expected_friction = friction_response(law, reaction, p.e.normal, p.reversible_committed, du);
      EXPECT_LT((r.friction.force - expected_friction.force).norm(), 1e-12 * reaction);
      EXPECT_LT((r.friction.reversible - expected_friction.reversible).norm(), 1e-15);
      EXPECT_EQ(r.friction.slip, regime == 2);
      const PairVector expected = residual_of(p, reaction * p.e.normal + r.friction.force);
      EXPECT_LT((r.force - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff())
          << "gap " << gap << " regime " << regime;
      compared += 7;
    }
  }
  EXPECT_EQ(compared, 2 * 3 * 7);
}

TEST(ContactResponse, FrictionlessForceIsTheGradientOfThePotential) {
  std::mt19937 rng(42);
  int compared = 0;
  for (const double gap : kGaps) {
    for (int trial = 0; trial < 2; ++trial) {
      const Pair p = random_pair(rng, gap, 0.0);
      const PairVector q = p.q();
      const PairVector force = evaluate(p, q, nullptr).force;
      const double scale = force.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      // Psi is cubic in the gap (zone) or quadratic: truncation (h / p)^2 ~ 1e-8, rounding ~1e-10.
      const double h = 1e-6;
      for (int m = 0; m < kPairDofs; ++m) {
        PairVector plus = q, minus = q;
        plus[m] += h;
        minus[m] -= h;
        const double fd =
            (reference_potential(test_gap(p, plus)) - reference_potential(test_gap(p, minus))) / (2.0 * h);
        EXPECT_NEAR(force[m], fd, 1e-6 * scale) << "gap " << gap << " dof " << m;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 2 * 2 * kPairDofs);
}

TEST(ContactResponse, FrictionlessTangentIsTheSymmetricPsdDerivativeOfTheForce) {
  std::mt19937 rng(43);
  int compared = 0;
  for (const double gap : kGaps) {
    for (int trial = 0; trial < 2; ++trial) {
      const Pair p = random_pair(rng, gap, 0.0);
      const PairVector q = p.q();
      const ContactResponse r = evaluate(p, q, nullptr);
      const PairMatrix fd =
          finite_difference(q, [&](const PairVector& x) { return evaluate(p, x, nullptr).force; });
      compared += expect_matrix_near(r.tangent, fd, 1e-6, "frictionless tangent");

      const double scale = r.tangent.cwiseAbs().maxCoeff();
      EXPECT_LE((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(), 1e-14 * scale);
      const Eigen::SelfAdjointEigenSolver<PairMatrix> eig(r.tangent);
      const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
      EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-9 * largest);
      // Rank one: k_N(gap) C^T n n^T C, its eigenvalue k_N |C^T n|^2 with C^T n = [-B_I^T n; B_J^T n].
      const double k_n = kPenalty * std::min(1.0, -gap / kRegularization);
      const double expected = k_n * residual_of(p, p.e.normal).squaredNorm();
      EXPECT_NEAR(eig.eigenvalues()[kPairDofs - 1], expected, 1e-12 * expected);
      EXPECT_LE(std::abs(eig.eigenvalues()[kPairDofs - 2]), 1e-12 * expected);
    }
  }
  EXPECT_EQ(compared, 2 * 2 * kPairDofs * kPairDofs);
}

TEST(ContactResponse, FrictionTangentIsTheDerivativeWithFrozenReaction) {
  std::mt19937 rng(44);
  int compared = 0;
  for (const double gap : kGaps) {
    for (const bool slip : {false, true}) {
      Pair p = random_pair(rng, gap, 0.02);
      const PairVector q = p.q();
      p.reversible_committed = 0.001 * random_unit(rng);
      const Vec3 trial = tangential_projector(p.e.normal) * (p.reversible_committed + test_increment(p, q));
      ASSERT_GT(trial.norm(), 1e-3);
      const FrictionLaw law{kMu, slip ? trial.norm() / 3.0 : 2.0 * trial.norm()};
      const ContactResponse r = evaluate(p, q, &law);
      ASSERT_EQ(r.friction.slip, slip);
      const double frozen = reference_reaction(test_gap(p, q));

      // Whole tangent against FD of [normal part] + [friction part with R_N frozen].
      const PairMatrix fd =
          finite_difference(q, [&](const PairVector& x) { return frozen_residual(p, x, &law, frozen); });
      compared += expect_matrix_near(r.tangent, fd, 1e-6, slip ? "tangent (slip)" : "tangent (stick)");

      // The friction part alone (the code's tangent minus its frictionless tangent), to its own scale.
      const PairMatrix friction_tangent = r.tangent - evaluate(p, q, nullptr).tangent;
      const PairMatrix fd_friction = finite_difference(q, [&](const PairVector& x) {
        return residual_of(
            p,
            friction_response(law, frozen, p.e.normal, p.reversible_committed, test_increment(p, x)).force);
      });
      compared += expect_matrix_near(friction_tangent, fd_friction, 1e-6,
                                     slip ? "friction tangent (slip)" : "friction tangent (stick)");
    }
  }
  EXPECT_EQ(compared, 2 * 2 * 2 * kPairDofs * kPairDofs);
}

/// Facing particles (ResponseOptions::facing_particles) with the friction force's dependence on R_N
/// (friction_normal_coupling): the tangent is the exact derivative of the force, the particles moving along
/// their borders with the directors. The committed state is the current one (du = 0), so that the friction
/// increment does not depend on where the particles sit.
TEST(ContactResponse, FacingParticlesTangentIsTheDerivativeOfTheForce) {
  std::mt19937 rng(46);
  int compared = 0;
  const ResponseOptions options{true, true};
  for (const double gap : kGaps) {
    for (int regime = 0; regime < 3; ++regime) {  // frictionless, stick, slip
      Pair p = random_pair(rng, gap, 0.0);
      // Particles at the facing points of the current sections, then J moved along n to the gap wanted.
      const auto face = [](Particle& particle, const ElementVector& q, const Vec3& direction) {
        const std::array<double, 3> n = lagrange(particle.local);
        Vec3 g1 = Vec3::Zero(), g2 = Vec3::Zero();
        for (int k = 0; k < kElementNodes; ++k) {
          g1 += n[static_cast<std::size_t>(k)] * q.segment<3>(kNodeDofs * k + 3);
          g2 += n[static_cast<std::size_t>(k)] * q.segment<3>(kNodeDofs * k + 6);
        }
        ASSERT_TRUE(facing_point(g1, g2, direction, particle.transverse.norm(), particle.transverse));
      };
      face(p.e.particle_i, p.q_i, p.e.normal);
      face(p.e.particle_j, p.q_j, -p.e.normal);
      const double shift = gap - p.e.normal.dot(particle_position(p.e.particle_j, p.q_j) -
                                                particle_position(p.e.particle_i, p.q_i));
      for (int k = 0; k < 3; ++k) p.q_j.segment<3>(9 * k) += shift * p.e.normal;
      p.qc_i = p.q_i;
      p.qc_j = p.q_j;
      const PairVector q = p.q();
      p.reversible_committed = 0.001 * tangential_projector(p.e.normal) * random_unit(rng);
      const double size = p.reversible_committed.norm();
      const FrictionLaw law{kMu, regime == 1 ? 2.0 * size : size / 3.0};
      const FrictionLaw* friction = regime == 0 ? nullptr : &law;
      const auto response = [&](const PairVector& x) {
        return contact_response(p.e, x.head<kElementDofs>(), x.tail<kElementDofs>(), p.qc_i, p.qc_j,
                                normal_law(), friction, p.reversible_committed, options);
      };
      const ContactResponse r = response(q);
      EXPECT_NEAR(r.gap, gap, 1e-12);
      // At the facing points the force is that of fixed particles there.
      const ContactResponse fixed = evaluate(p, q, friction);
      EXPECT_LT((r.force - fixed.force).cwiseAbs().maxCoeff(), 1e-12 * fixed.force.cwiseAbs().maxCoeff());
      if (friction) {
        EXPECT_EQ(r.friction.slip, regime == 2);
      }
      const PairMatrix fd = finite_difference(q, [&](const PairVector& x) { return response(x).force; });
      compared += expect_matrix_near(r.tangent, fd, 1e-6, "facing particles");
    }
  }
  EXPECT_EQ(compared, 2 * 3 * kPairDofs * kPairDofs);
}

TEST(ContactResponse, RigidTranslationDoesNoWork) {
  std::mt19937 rng(45);
  int compared = 0;
  for (const double gap : kGaps) {
    for (int regime = 0; regime < 3; ++regime) {
      Pair p = random_pair(rng, gap, 0.02);
      const PairVector q = p.q();
      p.reversible_committed = 0.001 * random_unit(rng);
      const Vec3 trial = tangential_projector(p.e.normal) * (p.reversible_committed + test_increment(p, q));
      const FrictionLaw law{kMu, regime == 1 ? 2.0 * trial.norm() : trial.norm() / 3.0};
      const ContactResponse r = evaluate(p, q, regime == 0 ? nullptr : &law);
      // v on the position of all six nodes: both particles move by v, the relative position is unchanged.
      const Vec3 v = random_unit(rng);
      PairVector translation = PairVector::Zero();
      for (int k = 0; k < 2 * kElementNodes; ++k) translation.segment<3>(kNodeDofs * k) = v;
      EXPECT_NEAR(r.force.dot(translation), 0.0, 1e-14 * r.force.norm() * translation.norm());
      EXPECT_LE((r.tangent * translation).norm(), 1e-13 * r.tangent.cwiseAbs().maxCoeff());
      compared += 2;
    }
  }
  EXPECT_EQ(compared, 2 * 3 * 2);
}

TEST(ContactResponse, NothingWhenApart) {
  std::mt19937 rng(46);
  Pair p = random_pair(rng, 0.3 * kRegularization, 0.02);
  p.reversible_committed = 0.001 * random_unit(rng);
  const FrictionLaw law{kMu, 0.01};
  for (const FrictionLaw* friction : {static_cast<const FrictionLaw*>(nullptr), &law}) {
    const ContactResponse r = evaluate(p, p.q(), friction);
    EXPECT_NEAR(r.gap, 0.3 * kRegularization, 1e-13);
    EXPECT_EQ(r.normal_reaction, 0.0);
    EXPECT_EQ(r.force, PairVector::Zero());
    EXPECT_EQ(r.tangent, PairMatrix::Zero());
    EXPECT_EQ(r.friction.force, Vec3::Zero());
  }
}

}  // namespace
}  // namespace nodus::contact
