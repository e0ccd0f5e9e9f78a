// The rotation-vector parametrisation of rigid bodies: Q(theta) against Eigen's angle-axis, and its first
// and second derivatives against central finite differences, from theta = 0 to several turns. The director
// update of Newton's increments (rotate_directors): exact on a rigid turn, additive on a stretch, and equal
// to g + d to first order.
#include <array>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "nodus/model/rotation_vector.hpp"

namespace nodus::model {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

const Vec3 kThetas[] = {Vec3::Zero(),          Vec3(1e-4, -2e-4, 3e-5), Vec3(0.3, -0.2, 0.5),
                        Vec3(1.1, 1.3, -0.4),  Vec3(0.0, 0.0, 3.1),     Vec3(-2.0, 4.0, 1.0),
                        Vec3(12.0, -3.0, 20.0)};

Mat3 angle_axis(const Vec3& theta) {
  const double angle = theta.norm();
  return angle == 0.0 ? Mat3::Identity() : Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

TEST(RotationVector, MatrixIsRodriguesRotation) {
  for (const Vec3& theta : kThetas) {
    const Mat3 q = rotation_matrix(theta);
    EXPECT_LT((q - angle_axis(theta)).norm(), 1e-14 * (1.0 + theta.norm())) << theta.transpose();
    EXPECT_LT((q.transpose() * q - Mat3::Identity()).norm(), 1e-14);
    EXPECT_LT((rotation_derivatives(theta).q - q).norm(), 1e-15);
  }
}

TEST(RotationVector, FirstAndSecondDerivativesMatchFiniteDifferences) {
  const double h = 1e-5;
  for (const Vec3& theta : kThetas) {
    const RotationDerivatives d = rotation_derivatives(theta);
    for (int k = 0; k < 3; ++k) {
      const Vec3 step = h * Vec3::Unit(k);
      const Mat3 fd = (rotation_matrix(theta + step) - rotation_matrix(theta - step)) / (2 * h);
      EXPECT_LT((d.first[static_cast<std::size_t>(k)] - fd).norm(), 1e-9) << theta.transpose() << " k " << k;
      const RotationDerivatives plus = rotation_derivatives(theta + step, false);
      const RotationDerivatives minus = rotation_derivatives(theta - step, false);
      for (int l = 0; l < 3; ++l) {
        const auto kk = static_cast<std::size_t>(k), ll = static_cast<std::size_t>(l);
        const Mat3 fd2 = (plus.first[ll] - minus.first[ll]) / (2 * h);
        EXPECT_LT((d.second[kk][ll] - fd2).norm(), 1e-8) << theta.transpose() << " k " << k << " l " << l;
        EXPECT_LT((d.second[kk][ll] - d.second[ll][kk]).norm(), 1e-14);
      }
    }
  }
}

// Across t = |theta|^2 = 4, where the power series hands over to the closed forms, Q and its derivatives
// are continuous to round-off.
TEST(RotationVector, SeriesAndClosedFormsAgreeWhereTheyMeet) {
  const Vec3 axis = Vec3(1.0, 2.0, -2.0) / 3.0;
  const RotationDerivatives below = rotation_derivatives(axis * (2.0 - 1e-12));
  const RotationDerivatives above = rotation_derivatives(axis * (2.0 + 1e-12));
  EXPECT_LT((below.q - above.q).norm(), 1e-11);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_LT((below.first[k] - above.first[k]).norm(), 1e-11);
    for (std::size_t l = 0; l < 3; ++l) EXPECT_LT((below.second[k][l] - above.second[k][l]).norm(), 1e-10);
  }
}

TEST(RotationVector, LogarithmCountsTurnsAboutTheAxis) {
  const Vec3 axis = Vec3(0.0, 0.6, 0.8);
  for (double angle : {0.0, 0.4, -2.5, 7.0, -20.0, 33.6}) {
    const Vec3 theta = angle * axis;
    const Vec3 back = rotation_vector(rotation_matrix(theta), theta + 0.3 * axis);
    EXPECT_LT((back - theta).norm(), 1e-12 * (1.0 + std::abs(angle))) << angle;
  }
  // Without a hint beyond half a turn, the principal value.
  const Vec3 theta = 1.0 * Vec3(0.0, 0.0, 1.0);
  EXPECT_LT((rotation_vector(rotation_matrix(theta), Vec3::Zero()) - theta).norm(), 1e-14);
}

/// Directors that are neither unit nor orthogonal (a deformed section): 1.1 and 0.9 long, 80 degrees apart.
std::array<Vec3, 2> deformed_section() {
  const Vec3 g1 = 1.1 * Vec3(0.2, 1.0, -0.3).normalized();
  const Vec3 n = g1.cross(Vec3(0.4, 0.1, 1.0)).normalized();
  const Vec3 g2 = 0.9 * (std::cos(80.0 * std::numbers::pi / 180.0) * g1.normalized() +
                         std::sin(80.0 * std::numbers::pi / 180.0) * n.cross(g1.normalized()));
  return {g1, g2};
}

TEST(DirectorUpdate, TurnsALinearisedRotationExactly) {
  const auto [g1, g2] = deformed_section();
  for (const Vec3& omega : {Vec3(1e-3, 0.0, -2e-3), Vec3(0.1, -0.05, 0.2), Vec3(0.9, 0.4, -1.2)}) {
    const auto [n1, n2] = rotate_directors(g1, g2, omega.cross(g1), omega.cross(g2));
    const Mat3 q = angle_axis(omega);
    EXPECT_LT((n1 - q * g1).norm(), 1e-14) << omega.transpose();
    EXPECT_LT((n2 - q * g2).norm(), 1e-14) << omega.transpose();
    // The additive update stretches the section by |omega|^2 / 2; this one keeps lengths and angle.
    EXPECT_NEAR(n1.norm(), g1.norm(), 1e-14);
    EXPECT_NEAR(n1.dot(n2), g1.dot(g2), 1e-14);
  }
}

TEST(DirectorUpdate, AddsAnIncrementThatDoesNotTurnTheSection) {
  // A uniform stretch of the section: g_i x d_i = 0, no rotation.
  const auto [g1, g2] = deformed_section();
  const auto [n1, n2] = rotate_directors(g1, g2, 0.05 * g1, 0.05 * g2);
  EXPECT_LT((n1 - 1.05 * g1).norm(), 1e-15);
  EXPECT_LT((n2 - 1.05 * g2).norm(), 1e-15);
}

TEST(DirectorUpdate, EqualsTheSumToFirstOrder) {
  // |update(g, e d) - (g + e d)| = O(e^2): halving e divides it by 4.
  const auto [g1, g2] = deformed_section();
  const Vec3 d1(0.3, -0.7, 0.2), d2(-0.4, 0.1, 0.9);
  auto gap = [&](double e) {
    const auto [n1, n2] = rotate_directors(g1, g2, e * d1, e * d2);
    return std::hypot((n1 - g1 - e * d1).norm(), (n2 - g2 - e * d2).norm());
  };
  for (const double e : {1e-2, 1e-3}) {
    ASSERT_GT(gap(e), 0.0);
    EXPECT_NEAR(gap(e) / gap(e / 2), 4.0, 0.05) << e;
  }
}

TEST(DirectorUpdate, DegenerateDirectorsAreAdded) {
  const Vec3 g(1.0, 0.0, 0.0), d1(0.0, 0.1, 0.0), d2(0.0, 0.0, 0.1);
  const auto [n1, n2] = rotate_directors(g, 2.0 * g, d1, d2);
  EXPECT_EQ(n1, g + d1);
  EXPECT_EQ(n2, 2.0 * g + d2);
}

}  // namespace
}  // namespace nodus::model
