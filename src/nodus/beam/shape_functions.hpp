#pragma once
/// Quadratic Lagrange shape functions of the 3-node beam element and Gauss-Legendre rules on [-1, 1]
/// [Durville 2012, Eq. 66-67].

#include <array>
#include <span>

namespace nodus::beam {

/// Values and derivatives d/dxi of the three shape functions at xi in [-1, 1]; nodes at xi = -1, 0, 1.
struct QuadraticShape {
  std::array<double, 3> value;
  std::array<double, 3> derivative;
};

inline QuadraticShape quadratic_shape(double xi) {
  return {{0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)}, {xi - 0.5, -2.0 * xi, xi + 0.5}};
}

struct GaussPoint {
  double xi;
  double weight;
};

/// Gauss-Legendre rule with n points (1 <= n <= 5), exact for polynomials of degree 2n - 1.
std::span<const GaussPoint> gauss_rule(int n);

}  // namespace nodus::beam
