#include "nodus/contact/beam_curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "nodus/beam/shape_functions.hpp"

namespace nodus::contact {

namespace {

constexpr int kDofs = beam::kNodeDofs;

/// The real roots in [lo, hi] of c0 + c1 t + c2 t^2 + c3 t^3, found by bisection on the monotone pieces
/// between the roots of the derivative (robust where a closed form loses digits).
int cubic_roots(const std::array<double, 4>& c, double lo, double hi, std::array<double, 3>& roots) {
  const auto value = [&](double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); };
  std::array<double, 4> knots{lo, hi, hi, hi};
  int num_knots = 1;
  // Stationary points of the cubic: 3 c3 t^2 + 2 c2 t + c1 = 0.
  const double qa = 3.0 * c[3], qb = 2.0 * c[2], qc = c[1];
  std::array<double, 2> stationary{};
  int num_stationary = 0;
  if (std::abs(qa) > 1e-300) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      if (q != 0.0) stationary[num_stationary++] = q / qa;
      stationary[num_stationary++] = q != 0.0 ? qc / q : 0.0;
    }
  } else if (std::abs(qb) > 1e-300) {
    stationary[num_stationary++] = -qc / qb;
  }
  std::sort(stationary.begin(), stationary.begin() + num_stationary);
  for (int i = 0; i < num_stationary; ++i)
    if (stationary[i] > lo && stationary[i] < hi) knots[num_knots++] = stationary[i];
  knots[num_knots++] = hi;

  int count = 0;
  for (int k = 0; k + 1 < num_knots; ++k) {
    double a = knots[k], b = knots[k + 1];
    double fa = value(a), fb = value(b);
    if (fa == 0.0) {
      roots[count++] = a;
      continue;
    }
    if ((fa < 0.0) == (fb < 0.0)) continue;
    for (int it = 0; it < 100 && b - a > 1e-15; ++it) {
      const double m = 0.5 * (a + b), fm = value(m);
      if ((fm < 0.0) == (fa < 0.0)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    if (count < 3) roots[count++] = 0.5 * (a + b);
  }
  return count;
}

}  // namespace

double BeamCurves::abscissa(int element, double local) const {
  const int beam = element_beam(element);
  const double h = model_.beam(beam).element_length();
  return h * (element - first_element(beam) + 0.5 * (local + 1.0));
}

SectionGeometry BeamCurves::at(int beam, double s) const {
  const beam::Beam& b = model_.beam(beam);
  const double h = b.element_length();
  const double t = std::clamp(s, 0.0, b.length()) / h;
  const int e = std::clamp(static_cast<int>(std::floor(t)), 0, b.num_elements() - 1);
  return at_element(first_element(beam) + e, std::clamp(2.0 * (t - e) - 1.0, -1.0, 1.0));
}

SectionGeometry BeamCurves::at_element(int element, double local) const {
  const int beam = element_beam(element);
  const beam::Beam& b = model_.beam(beam);
  const int first_node = b.node(2 * (element - first_element(beam)));
  const beam::QuadraticShape shape = beam::quadratic_shape(local);
  SectionGeometry g{Eigen::Vector3d::Zero(),
                    Eigen::Vector3d::Zero(),
                    Eigen::Vector3d::Zero(),
                    Eigen::Vector3d::Zero(),
                    element,
                    local};
  const double dxi_ds = 2.0 / b.element_length();
  for (int k = 0; k < 3; ++k) {
    const auto node = x_.segment<kDofs>(kDofs * (first_node + k));
    g.r += shape.value[k] * node.head<3>();
    g.dr += shape.derivative[k] * dxi_ds * node.head<3>();
    g.g1 += shape.value[k] * node.segment<3>(3);
    g.g2 += shape.value[k] * node.segment<3>(6);
  }
  return g;
}

Eigen::Matrix3d BeamCurves::element_axis(int element) const {
  const int beam = element_beam(element);
  const int first_node = model_.beam(beam).node(2 * (element - first_element(beam)));
  Eigen::Matrix3d nodes;
  for (int k = 0; k < 3; ++k) nodes.col(k) = x_.segment<3>(kDofs * (first_node + k));
  return nodes;
}

ClosestPoint BeamCurves::closest_point(int element, const Eigen::Vector3d& p, double lo, double hi) const {
  // r(t) = A + B t + C t^2 from the nodal positions at t = -1, 0, 1.
  const Eigen::Matrix3d nodes = element_axis(element);
  const Eigen::Vector3d a = nodes.col(1) - p;
  const Eigen::Vector3d b = 0.5 * (nodes.col(2) - nodes.col(0));
  const Eigen::Vector3d c = 0.5 * (nodes.col(0) + nodes.col(2)) - nodes.col(1);
  const auto distance = [&](double t) { return (a + t * (b + t * c)).norm(); };
  // Stationary points of |r - p|^2 / 2: <A - p + B t + C t^2, B + 2 C t> = 0, a cubic.
  const std::array<double, 4> coefficients{a.dot(b), b.dot(b) + 2.0 * a.dot(c), 3.0 * b.dot(c),
                                           2.0 * c.dot(c)};
  ClosestPoint best{lo, distance(lo)};
  const double d_hi = distance(hi);
  if (d_hi < best.distance) best = {hi, d_hi};
  std::array<double, 3> roots{};
  const int n = cubic_roots(coefficients, lo, hi, roots);
  for (int i = 0; i < n; ++i) {
    const double d = distance(roots[i]);
    if (d < best.distance) best = {roots[i], d};
  }
  return best;
}

}  // namespace nodus::contact
