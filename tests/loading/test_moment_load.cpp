// The moment about a fixed axis: its generalised force is the gradient of the angle, its tangent the Hessian
// (central finite differences), its moment about the section centre is exactly M along the axis, and the
// angle counts whole turns.

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "nodus/loading/moment_load.hpp"
#include "nodus/loading/path.hpp"

namespace nodus::loading {
namespace {

TEST(AxisAngle, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 v0 = axis.unitOrthogonal();
    AxisAngle angle(axis, v0);
    const Vec3 v = Vec3(u(rng), u(rng), u(rng)) + 2.0 * v0;
    const Vec3 g = angle.gradient(v);
    const Eigen::Matrix3d h = angle.hessian(v);
    const double step = 1e-6;
    for (int i = 0; i < 3; ++i) {
      Vec3 vp = v, vm = v;
      vp[i] += step;
      vm[i] -= step;
      EXPECT_NEAR(g[i], (angle.angle(vp) - angle.angle(vm)) / (2 * step), 1e-7);
      const Vec3 column = (angle.gradient(vp) - angle.gradient(vm)) / (2 * step);
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(h(j, i), column[j], 1e-6);
        ++compared;
      }
    }
    EXPECT_LT((h - h.transpose()).norm(), 1e-12);
    // The moment of the generalised force about the centre has a unit component along the axis; it is exactly
    // the unit moment when the director lies in the plane normal to the axis.
    EXPECT_NEAR(v.cross(g).dot(axis), 1.0, 1e-12);
    const Vec3 in_plane = v - v.dot(axis) * axis;
    EXPECT_LT((in_plane.cross(angle.gradient(in_plane)) - axis).norm(), 1e-12);
  }
  EXPECT_EQ(compared, 50 * 9);
}

TEST(AxisAngle, CountsWholeTurns) {
  const Vec3 axis = Vec3::UnitZ();
  AxisAngle angle(axis, Vec3::UnitX());
  const int steps = 50;
  for (int k = 1; k <= steps; ++k) {
    const double phi = 5.0 * std::numbers::pi * k / steps;  // two and a half turns
    const Vec3 v = Eigen::AngleAxisd(phi, axis) * Vec3(2.0, 0.0, 0.3);
    EXPECT_NEAR(angle.angle(v), phi, 1e-12);
    angle.commit(v);
  }
}

TEST(Path, InterpolatesLinearlyAndHolds) {
  Path<double> p(1.0);
  p.add(1.0, 3.0);
  p.add(3.0, -1.0);
  EXPECT_DOUBLE_EQ(p.at(-1.0), 1.0);
  EXPECT_DOUBLE_EQ(p.at(0.5), 2.0);
  EXPECT_DOUBLE_EQ(p.at(2.0), 1.0);
  EXPECT_DOUBLE_EQ(p.at(5.0), -1.0);
}

}  // namespace
}  // namespace nodus::loading
