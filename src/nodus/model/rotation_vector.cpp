#include "nodus/model/rotation_vector.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace nodus::model {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

/// s, c and their first two derivatives in t = phi^2.
struct Coefficients {
  double s, s1, s2, c, c1, c2;
};

Coefficients coefficients(double t) {
  Coefficients k{};
  if (t < 4.0) {
    // The power series s = sum_m (-t)^m / (2m+1)!, c = sum_m (-t)^m / (2m+2)!, differentiated term by term:
    // d/dt (-t)^m = -m (-t)^(m-1), d^2/dt^2 (-t)^m = m (m-1) (-t)^(m-2). For t < 4 the terms fall below
    // 1e-17 of the sums before m = 20; the closed forms below lose digits to cancellation at small t.
    double fact_s = 1.0, fact_c = 2.0;              // (2m+1)!, (2m+2)!
    double p0 = 1.0, previous = 0.0, before = 0.0;  // (-t)^m, (-t)^(m-1), (-t)^(m-2)
    for (int m = 0; m < 20; ++m) {
      const double p1 = m >= 1 ? -m * previous : 0.0;           // d/dt (-t)^m
      const double p2 = m >= 2 ? m * (m - 1.0) * before : 0.0;  // d^2/dt^2 (-t)^m
      k.s += p0 / fact_s;
      k.c += p0 / fact_c;
      k.s1 += p1 / fact_s;
      k.c1 += p1 / fact_c;
      k.s2 += p2 / fact_s;
      k.c2 += p2 / fact_c;
      before = previous;
      previous = p0;
      p0 *= -t;
      fact_s *= (2.0 * m + 2.0) * (2.0 * m + 3.0);
      fact_c *= (2.0 * m + 3.0) * (2.0 * m + 4.0);
    }
    return k;
  }
  const double phi = std::sqrt(t), sn = std::sin(phi), cs = std::cos(phi);
  const double p2 = t, p3 = t * phi, p4 = t * t, p5 = p4 * phi, p6 = p4 * t;
  k.s = sn / phi;
  k.c = (1.0 - cs) / p2;
  k.s1 = (phi * cs - sn) / (2.0 * p3);
  k.c1 = (phi * sn - 2.0 + 2.0 * cs) / (2.0 * p4);
  k.s2 = (3.0 * sn - 3.0 * phi * cs - p2 * sn) / (4.0 * p5);
  k.c2 = (p2 * cs - 5.0 * phi * sn + 8.0 - 8.0 * cs) / (4.0 * p6);
  return k;
}

}  // namespace

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Mat3 rotation_matrix(const Vec3& theta) {
  const Coefficients k = coefficients(theta.squaredNorm());
  const Mat3 a = skew(theta);
  return Mat3::Identity() + k.s * a + k.c * a * a;
}

RotationDerivatives rotation_derivatives(const Vec3& theta, bool second) {
  const Coefficients k = coefficients(theta.squaredNorm());
  const Mat3 a = skew(theta), a2 = a * a;
  std::array<Mat3, 3> e;
  for (int i = 0; i < 3; ++i) e[static_cast<std::size_t>(i)] = skew(Vec3::Unit(i));
  RotationDerivatives out;
  out.q = Mat3::Identity() + k.s * a + k.c * a2;
  std::array<Mat3, 3> ea;  // E_k A + A E_k
  for (std::size_t i = 0; i < 3; ++i) {
    ea[i] = e[i] * a + a * e[i];
    const double th = theta[static_cast<int>(i)];
    out.first[i] = 2.0 * th * k.s1 * a + k.s * e[i] + 2.0 * th * k.c1 * a2 + k.c * ea[i];
  }
  if (!second) return out;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const double ti = theta[static_cast<int>(i)], tj = theta[static_cast<int>(j)];
      const double delta = i == j ? 1.0 : 0.0;
      out.second[i][j] = (4.0 * ti * tj * k.s2 + 2.0 * delta * k.s1) * a + 2.0 * ti * k.s1 * e[j] +
                         2.0 * tj * k.s1 * e[i] + (4.0 * ti * tj * k.c2 + 2.0 * delta * k.c1) * a2 +
                         2.0 * ti * k.c1 * ea[j] + 2.0 * tj * k.c1 * ea[i] +
                         k.c * (e[i] * e[j] + e[j] * e[i]);
    }
  return out;
}

Vec3 rotation_vector(const Mat3& q, const Vec3& near) {
  const Eigen::AngleAxisd aa(q);
  const double angle = aa.angle();
  if (angle == 0.0) {
    // The identity: whole turns about the direction of `near`.
    const double n = near.norm();
    if (n == 0.0) return Vec3::Zero();
    const double turns = std::round(n / (2.0 * std::numbers::pi));
    return near / n * (2.0 * std::numbers::pi * turns);
  }
  const Vec3 axis = aa.axis();
  // Candidates angle + 2 pi k along the axis (and the opposite axis covers negative angles).
  const double along = near.dot(axis);
  const double turns = std::round((along - angle) / (2.0 * std::numbers::pi));
  return axis * (angle + 2.0 * std::numbers::pi * turns);
}

std::array<Vec3, 2> rotate_directors(const Vec3& g1, const Vec3& g2, const Vec3& d1, const Vec3& d2) {
  const Mat3 a =
      (g1.squaredNorm() + g2.squaredNorm()) * Mat3::Identity() - g1 * g1.transpose() - g2 * g2.transpose();
  const Eigen::LLT<Mat3> factor(a);
  const Vec3 omega = factor.solve(g1.cross(d1) + g2.cross(d2));
  if (factor.info() != Eigen::Success || !omega.allFinite()) return {g1 + d1, g2 + d2};
  const Mat3 q = rotation_matrix(omega);
  return {q * g1 + (d1 - omega.cross(g1)), q * g2 + (d2 - omega.cross(g2))};
}

}  // namespace nodus::model
