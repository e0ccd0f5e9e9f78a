// The rotation-vector parametrisation of rigid bodies: Q(theta) against Eigen's angle-axis, and its first
// and second derivatives against central finite differences, from theta = 0 to several turns.
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

}  // namespace
}  // namespace nodus::model
