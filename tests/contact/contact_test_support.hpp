#pragma once
// Assemblies of beams placed along given space curves, for the contact detection tests. A beam's current
// state is set node by node from an exact curve r(s) (s: reference arc length), with unit directors
// orthogonal to the exact tangent, so that the reference answers are those of the exact curves.

#include <functional>
#include <string>

#include <Eigen/Geometry>

#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"

namespace nodus::contact::testing {

using Curve = std::function<Vec3(double)>;

/// A straight beam definition of given length, radius and element count (material irrelevant to geometry).
inline beam::BeamDefinition beam_definition(double length, double radius, int elements) {
  beam::BeamDefinition d;
  d.name = "beam";
  d.length = length;
  d.radius = radius;
  d.elements = elements;
  d.material = {4000.0, 0.3};
  return d;
}

/// Sets the nodes of `beam` in `x` on `curve`: positions r(s), g1 the unit component of `hint(s)` normal
/// to the tangent (central difference of the curve, step 1e-6 L), g2 = t x g1.
inline void place_beam(const model::Model& model, Eigen::VectorXd& x, int beam, const Curve& curve,
                       const Curve& hint) {
  const beam::Beam& b = model.beam(beam);
  const double step = 1e-6 * b.length();
  for (int i = 0; i < b.num_nodes(); ++i) {
    const double s = b.abscissa(i);
    const Vec3 t = (curve(s + step) - curve(s - step)).normalized();
    Vec3 g1 = hint(s) - hint(s).dot(t) * t;
    g1.normalize();
    auto node = x.segment<beam::kNodeDofs>(beam::kNodeDofs * b.node(i));
    node.head<3>() = curve(s);
    node.segment<3>(3) = g1;
    node.segment<3>(6) = t.cross(g1);
  }
}

/// A straight line from `start` with unit direction `direction`.
inline Curve line(const Vec3& start, const Vec3& direction) {
  const Vec3 u = direction.normalized();
  return [start, u](double s) -> Vec3 { return start + s * u; };
}

/// A constant director hint.
inline Curve constant(const Vec3& v) {
  return [v](double) { return v; };
}

/// Applies the rigid motion y = Q y + c to every position of `x`, and Q to every director.
inline Eigen::VectorXd moved(const Eigen::VectorXd& x, const Eigen::Matrix3d& q, const Vec3& c) {
  Eigen::VectorXd y = x;
  for (Eigen::Index n = 0; n < x.size() / beam::kNodeDofs; ++n) {
    auto node = y.segment<beam::kNodeDofs>(beam::kNodeDofs * n);
    node.head<3>() = q * node.head<3>() + c;
    node.segment<3>(3) = q * node.segment<3>(3);
    node.segment<3>(6) = q * node.segment<3>(6);
  }
  return y;
}

}  // namespace nodus::contact::testing
