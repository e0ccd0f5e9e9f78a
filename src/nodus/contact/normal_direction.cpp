#include "nodus/contact/normal_direction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

namespace nodus::contact {
namespace {

/// The normal is the cross product of the tangents (Eq. 42) above this crossing angle, the double cross
/// product (Eq. 44) below kParallelBelow, and a smooth blend of the two between (docs/contact.md).
const double kSinParallelBelow = std::sin(5.0 * std::numbers::pi / 180.0);
const double kSinCrossAbove = std::sin(15.0 * std::numbers::pi / 180.0);

template <class T>
using Vec3T = Eigen::Matrix<T, 3, 1>;

template <class T>
T length_of(const Vec3T<T>& v) {
  using std::sqrt;
  return sqrt(v.squaredNorm());
}

template <class T>
Vec3T<T> unit(const Vec3T<T>& v) {
  return v / length_of(v);
}

template <class T>
T smoothstep(T t) {
  t = std::clamp(t, T(0.0), T(1.0));
  return t * t * (3.0 - 2.0 * t);
}

/// The normal (Eq. 41-44) for a scalar type T: double, or an automatic-differentiation scalar.
template <class T>
bool compute(const Vec3T<T>& r_i, const Vec3T<T>& dr_i, const Vec3T<T>& r_j, const Vec3T<T>& dr_j,
             double centre_tolerance, Vec3T<T>& d, Vec3T<T>& normal, T& parallel_weight) {
  const Vec3T<T> centres = r_j - r_i;
  const Vec3T<T> t_i = unit(dr_i);
  Vec3T<T> t_j = unit(dr_j);
  if (t_i.dot(t_j) < 0.0) t_j = -t_j;  // antiparallel parts: compare like with like
  const Vec3T<T> cross = t_i.cross(t_j);
  const T sin_angle = length_of(cross);
  if (length_of(centres) > centre_tolerance) {
    d = unit(centres);
  } else if (sin_angle > 0.0) {
    d = cross / sin_angle;  // the axes meet: the common normal is the only candidate
  } else {
    return false;
  }
  const T w = smoothstep(T((sin_angle - kSinParallelBelow) / (kSinCrossAbove - kSinParallelBelow)));
  Vec3T<T> n_cross = Vec3T<T>::Zero();
  if (sin_angle > 0.0) n_cross = (cross.dot(d) < 0.0 ? Vec3T<T>(-cross) : cross) / sin_angle;
  const Vec3T<T> t_mean = unit(Vec3T<T>(t_i + t_j));
  Vec3T<T> n_parallel = d - d.dot(t_mean) * t_mean;
  if (length_of(n_parallel) > 0.0) n_parallel = unit(n_parallel);
  normal = w * n_cross + (1.0 - w) * n_parallel;
  if (!(length_of(normal) > 1e-12)) return false;
  normal = unit(normal);
  parallel_weight = 1.0 - w;
  return true;
}

}  // namespace

bool normal_direction(const Eigen::Vector3d& r_i, const Eigen::Vector3d& dr_i, const Eigen::Vector3d& r_j,
                      const Eigen::Vector3d& dr_j, double centre_tolerance, NormalDirection& out) {
  return compute<double>(r_i, dr_i, r_j, dr_j, centre_tolerance, out.d, out.normal, out.parallel_weight);
}

bool normal_direction(const Eigen::Vector3d& r_i, const Eigen::Vector3d& dr_i, const Eigen::Vector3d& r_j,
                      const Eigen::Vector3d& dr_j, double centre_tolerance, NormalDirection& out,
                      NormalJacobian& jacobian) {
  using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 12, 1>>;
  const auto seed = [](const Eigen::Vector3d& v, int first) {
    Vec3T<Ad> a;
    for (int k = 0; k < 3; ++k) a[k] = Ad(v[k], 12, first + k);
    return a;
  };
  Vec3T<Ad> d, normal;
  Ad parallel_weight;
  if (!compute<Ad>(seed(r_i, 0), seed(dr_i, 3), seed(r_j, 6), seed(dr_j, 9), centre_tolerance, d, normal,
                   parallel_weight))
    return false;
  for (int k = 0; k < 3; ++k) {
    out.d[k] = d[k].value();
    out.normal[k] = normal[k].value();
    jacobian.row(k) = normal[k].derivatives().transpose();
  }
  out.parallel_weight = parallel_weight.value();
  return true;
}

}  // namespace nodus::contact
