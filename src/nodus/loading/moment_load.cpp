#include "nodus/loading/moment_load.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

namespace nodus::loading {

AxisAngle::AxisAngle(const Vec3& axis, const Vec3& v0) : axis_(axis.normalized()) {
  const Vec3 in_plane = v0 - v0.dot(axis_) * axis_;
  if (in_plane.norm() < 1e-6 * v0.norm())
    throw std::invalid_argument("AxisAngle: director parallel to the axis");
  b1_ = in_plane.normalized();
  b2_ = axis_.cross(b1_);
}

double AxisAngle::angle(const Vec3& v) const {
  const double raw = std::atan2(v.dot(b2_), v.dot(b1_));
  const double two_pi = 2.0 * std::numbers::pi;
  // The representative of raw + 2 pi k closest to the committed angle.
  return raw + two_pi * std::round((committed_ - raw) / two_pi);
}

Vec3 AxisAngle::gradient(const Vec3& v) const {
  const double a = v.dot(b1_), b = v.dot(b2_);
  return (a * b2_ - b * b1_) / (a * a + b * b);
}

Eigen::Matrix3d AxisAngle::hessian(const Vec3& v) const {
  const double a = v.dot(b1_), b = v.dot(b2_);
  const double rho2 = a * a + b * b;
  const Vec3 w = a * b2_ - b * b1_;
  const Vec3 p = a * b1_ + b * b2_;
  return (b2_ * b1_.transpose() - b1_ * b2_.transpose()) / rho2 - 2.0 * w * p.transpose() / (rho2 * rho2);
}

}  // namespace nodus::loading
