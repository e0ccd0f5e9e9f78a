// Zero modes of one free 3-node beam element (27 dofs). The strain energy is invariant under rigid motions
// x -> Q x + t (Q acting on the centres and on the directors alike, t on the centres only), so:
//  - at the reference (unstressed) state and at any rigidly moved copy of it, the tangent H has exactly six
//    zero eigenvalues, whose null space is spanned by the three translations and the three infinitesimal
//    rotations W x (W skew); the seventh eigenvalue is the softest deformation, estimated below;
//  - at a deformed (stressed) state, differentiating g(x) . (W x) = 0 (the internal force g does no work in a
//    rigid rotation) once more gives H (W x) = W g for every skew W, and g(x + t) = g(x) gives H t = 0: the
//    translations stay exactly null, the rotations are null only where g vanishes.
// Checked with the default fold_stiffness (0) and with the fold stabilisation on (its energy is quartic in
// r1 - 2 r2 + r3, so it adds nothing to H at a straight reference).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "nodus/beam/beam.hpp"
#include "nodus/beam/beam_element.hpp"
#include "nodus/beam/section.hpp"

namespace nodus::beam {
namespace {

using Mat3 = Eigen::Matrix3d;

Mat3 skew(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

/// Applies the 3x3 matrix `a` to every 3-vector block (centres and directors) of x.
ElementVector apply_blockwise(const Mat3& a, const ElementVector& x) {
  ElementVector y;
  for (int b = 0; b < kElementDofs / 3; ++b) y.segment<3>(3 * b) = a * x.segment<3>(3 * b);
  return y;
}

/// A unit translation of the centres along axis `d` (directors unchanged).
ElementVector translation(int d) {
  ElementVector t = ElementVector::Zero();
  for (int i = 0; i < kElementNodes; ++i) t[kNodeDofs * i + d] = 1.0;
  return t;
}

/// The element of the tests: length h = 1 mm, radius R = 0.1 mm, E = 4000 MPa, nu = 0.3, 2 Gauss points,
/// placed at `start` along `direction` with first director `director1`.
struct FreeElement {
  BeamDefinition def;
  ElementProperties props;
  ElementVector x;
  FreeElement(const Vec3& start, const Vec3& direction, const Vec3& director1, double fold_stiffness)
      : def{"b", 1.0, 0.1, 1, start, direction, director1, ElasticConstants{4000.0, 0.3}, 1.0} {
    const Beam beam(def, 0);
    props = beam.element_properties(2);
    props.fold_stiffness = fold_stiffness;
    for (int i = 0; i < kElementNodes; ++i) x.segment<kNodeDofs>(kNodeDofs * i) = beam.reference_node(i);
  }
  double ei() const { return def.material.young_modulus * disc_moments(def.radius).second; }
};

/// Eigenvalues of the symmetric matrix sorted by absolute value.
std::vector<double> eigenvalues_by_magnitude(const ElementMatrix& h) {
  const Eigen::SelfAdjointEigenSolver<ElementMatrix> eig(h, Eigen::EigenvaluesOnly);
  std::vector<double> v(eig.eigenvalues().data(), eig.eigenvalues().data() + kElementDofs);
  std::sort(v.begin(), v.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  return v;
}

ElementMatrix tangent_at(const ElementVector& x, const ElementProperties& props,
                         ElementVector* force = nullptr) {
  ElementVector f;
  ElementMatrix k;
  element_internal_force(x, props, f, &k);
  if (force) *force = f;
  return k;
}

/// A random rotation (axis uniform on the sphere, angle in [-pi, pi]).
Mat3 random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Eigen::AngleAxisd(3.14159 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()).matrix();
}

/// The uniform twist rate tau = 1/h about the axis `t` of a straight element: node i (abscissa s_i = (i - 1)
/// h/2) turns its directors by theta_i = s_i / h, i.e. g1 -> theta t x g1, g2 -> theta t x g2 (theta = -1/2,
/// 0, 1/2). Centres unchanged.
ElementVector uniform_twist(const FreeElement& e) {
  ElementVector v = ElementVector::Zero();
  const Vec3 t = e.def.direction;
  for (int i = 0; i < kElementNodes; ++i) {
    const double theta = 0.5 * (i - 1);
    v.segment<3>(kNodeDofs * i + 3) = theta * t.cross(e.x.segment<3>(kNodeDofs * i + 3));
    v.segment<3>(kNodeDofs * i + 6) = theta * t.cross(e.x.segment<3>(kNodeDofs * i + 6));
  }
  return v;
}

// Reference: the rigid-motion invariance of the energy (six null vectors), and for the seventh eigenvalue the
// closed form of the softest deformation. Why the seventh is E I / h: at a straight unstressed element a
// twist theta(s) of the directors about the axis only changes the shear-like measures q12 = -q21 = -theta'/2,
// each of section stiffness 2 E I (section.hpp), so its energy is (E I / 2) int theta'^2 ds, integrated
// exactly by the 2 Gauss points (theta' is linear): 1/2 theta^T (E I K_1D) theta, with K_1D = (1 / 3h) [[7,
// -8, 1], [-8, 16, -8], [1, -8, 7]] the matrix of the quadratic element (eigenvalues 0, 2/h, 8/h). Each nodal
// theta_i moves both unit directors by theta_i, so the dof vector has |v|^2 = 2 |theta|^2, and the Rayleigh
// quotients of the twists are E I eig(K_1D) / 2: E I / h (linear twist, the eigenvector uniform_twist) and 4
// E I / h (quadratic twist). The other deformations are stiffer: bending has the Rayleigh quotient 2 E I / h
// of the linear rotation of the one director that moves, lowered only a little by the centre displacement
// that follows it (|w|^2 / |psi|^2 ~ h^2 / 16 for h = 1 mm; the computed pair is 0.615 against 2 E I / h =
// 0.628), and stretching or shearing costs E A or mu A, ~ (h / R)^2 times more. So lambda_7 = E I / h = 0.314
// for this element, against lambda_max ~ 1.4e3: a ratio of 2e-4, twelve orders above the round-off of the
// zero modes (~1e-16 lambda_max).
TEST(ZeroModes, ReferenceStatesHaveExactlyTheSixRigidModes) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (double beta : {0.0, 1.0}) {  // default, then the fold stabilisation on
    for (int trial = 0; trial < 6; ++trial) {
      // Trial 0: the reference along x; then rigidly moved copies (random rotation and translation).
      const Mat3 q = trial == 0 ? Mat3::Identity() : random_rotation(rng);
      const Vec3 shift = trial == 0 ? Vec3::Zero() : Vec3(10 * u(rng), 10 * u(rng), 10 * u(rng));
      const FreeElement e(shift, q * Vec3::UnitX(), q * Vec3::UnitY(), beta);
      ElementVector g;
      const ElementMatrix h = tangent_at(e.x, e.props, &g);
      EXPECT_LT(g.norm(), 1e-12 * h.norm()) << "unstressed";
      const std::vector<double> lambda = eigenvalues_by_magnitude(h);
      const double lambda_max = std::abs(lambda.back());
      for (int k = 0; k < 6; ++k)
        EXPECT_LT(std::abs(lambda[k]), 1e-10 * lambda_max)
            << "beta " << beta << " trial " << trial << " k " << k;
      const double ei_h = e.ei() / e.def.length;
      EXPECT_NEAR(lambda[6], ei_h, 1e-9 * ei_h) << "beta " << beta << " trial " << trial;
      EXPECT_GT(lambda[6], 1e-4 * lambda_max);
      // The uniform twist is the eigenvector of E I / h.
      const ElementVector twist = uniform_twist(e);
      EXPECT_LT((h * twist - ei_h * twist).norm(), 1e-10 * lambda_max * twist.norm());
      // The null space: three translations and three infinitesimal rotations W x (about the origin; with
      // the translations, about any point).
      for (int d = 0; d < 3; ++d) {
        const ElementVector t = translation(d);
        EXPECT_LT((h * t).norm(), 1e-12 * h.norm() * t.norm()) << "translation " << d;
        const ElementVector r = apply_blockwise(skew(Vec3::Unit(d)), e.x);
        EXPECT_LT((h * r).norm(), 1e-12 * h.norm() * r.norm()) << "rotation " << d;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 2 * 6 * 3);
}

// Reference: the invariance identities H t = 0 and H (W x) = W g, exact at any state. At a stressed state
// (g != 0) the rotations are no longer null (W g != 0), and what remains is the three translations: exactly
// three eigenvalues below 1e-10 lambda_max. The fourth is a property of the state, not a theorem (a stressed
// element can soften towards buckling): on these seeded states it lies between 6e-5 and 6e-4 lambda_max, and
// the test asks for 1e-5.
TEST(ZeroModes, StressedStatesKeepTheTranslationsAndTheRotationIdentity) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (double beta : {0.0, 1.0}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Mat3 q = random_rotation(rng);
      const Vec3 shift(10 * u(rng), 10 * u(rng), 10 * u(rng));
      FreeElement e(shift, q * Vec3::UnitX(), q * Vec3::UnitY(), beta);
      const double amplitude = 0.05 * (trial + 1);  // every dof, centres [mm] and directors [-]
      for (int i = 0; i < kElementDofs; ++i) e.x[i] += amplitude * u(rng);
      ElementVector g;
      const ElementMatrix h = tangent_at(e.x, e.props, &g);
      ASSERT_GT(g.norm(), 1.0) << "the state is stressed";
      for (int d = 0; d < 3; ++d) {
        const ElementVector t = translation(d);
        EXPECT_LT((h * t).norm(), 1e-12 * h.norm() * t.norm()) << "translation " << d;
        EXPECT_NEAR(g.dot(t), 0.0, 1e-12 * g.norm()) << "the internal forces are self-balanced";
      }
      for (int k = 0; k < 4; ++k) {  // the three axes and a random one
        const Vec3 axis = k < 3 ? Vec3::Unit(k) : Vec3(u(rng), u(rng), u(rng));
        const Mat3 w = skew(axis);
        const ElementVector wx = apply_blockwise(w, e.x);
        const ElementVector wg = apply_blockwise(w, g);
        EXPECT_NEAR(g.dot(wx), 0.0, 1e-12 * g.norm() * wx.norm()) << "no work in a rigid rotation";
        EXPECT_LT((h * wx - wg).norm(), 1e-12 * h.norm() * wx.norm())
            << "beta " << beta << " trial " << trial;
        ++checked;
      }
      const std::vector<double> lambda = eigenvalues_by_magnitude(h);
      const double lambda_max = std::abs(lambda.back());
      for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(lambda[k]), 1e-10 * lambda_max);
      EXPECT_GT(std::abs(lambda[3]), 1e-5 * lambda_max) << "beta " << beta << " trial " << trial;
    }
  }
  EXPECT_EQ(checked, 2 * 5 * 4);
}

}  // namespace
}  // namespace nodus::beam
