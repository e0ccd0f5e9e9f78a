#pragma once
// A twisted bundle of parallel fibres for the contact benchmarks: n fibres of radius R = 0.1 mm and length
// 10 mm (100 elements each unless told), their axes on a hexagonal lattice of spacing 2.02 R (nearly
// touching) around the bundle axis z, each twisted into a helix about z so that the outermost fibre has a
// helix angle of 20 degrees. Neighbours in a layer run side by side; fibres of successive layers cross at
// small angles, as in a twisted yarn.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::bench {

struct Bundle {
  model::Model model;
  Eigen::VectorXd x;  ///< the twisted state
};

/// `spacing_factor`: the lattice spacing over R (2.02: nearly touching; below 2: neighbours overlap).
inline Bundle twisted_bundle(int fibres, int elements = 100, double length = 10.0, double radius = 0.1,
                             double spacing_factor = 2.02) {
  // Hexagonal lattice points nearest the axis.
  const double spacing = spacing_factor * radius;
  std::vector<Eigen::Vector2d> points;
  const int span = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(fibres)))) + 2;
  for (int i = -span; i <= span; ++i)
    for (int j = -span; j <= span; ++j)
      points.emplace_back(spacing * (i + 0.5 * j), spacing * (std::sqrt(3.0) / 2.0) * j);
  std::stable_sort(points.begin(), points.end(),
                   [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.norm() < b.norm(); });
  points.resize(static_cast<std::size_t>(fibres));
  const double outer = std::max(points.back().norm(), spacing);
  const double twist = std::tan(20.0 * std::numbers::pi / 180.0) / outer;  // rad per mm along z

  Bundle b;
  for (int f = 0; f < fibres; ++f) {
    beam::BeamDefinition def;
    def.name = "fibre" + std::to_string(f);
    def.length = length;
    def.radius = radius;
    def.elements = elements;
    def.material = {4000.0, 0.3};
    def.direction = Eigen::Vector3d::UnitZ();
    def.director1 = Eigen::Vector3d::UnitX();
    b.model.add_beam(def);
  }
  b.x = b.model.reference();
  for (int f = 0; f < fibres; ++f) {
    const Eigen::Vector2d p = points[static_cast<std::size_t>(f)];
    const double rho = p.norm(), phase = std::atan2(p.y(), p.x());
    const double angle = std::atan(twist * rho);  // helix angle of this fibre
    const beam::Beam& beam = b.model.beam(f);
    for (int i = 0; i < beam.num_nodes(); ++i) {
      const double s = beam.abscissa(i);  // arc length along the helix
      const double z = s * std::cos(angle), phi = phase + twist * z;
      const Eigen::Vector3d r(rho * std::cos(phi), rho * std::sin(phi), z);
      const Eigen::Vector3d t =
          Eigen::Vector3d(-std::sin(angle) * std::sin(phi), std::sin(angle) * std::cos(phi), std::cos(angle));
      Eigen::Vector3d g1 = Eigen::Vector3d::UnitX() - t.x() * t;
      g1.normalize();
      auto node = b.x.segment<beam::kNodeDofs>(beam::kNodeDofs * beam.node(i));
      node.head<3>() = r;
      node.segment<3>(3) = g1;
      node.segment<3>(6) = t.cross(g1);
    }
  }
  return b;
}

}  // namespace nodus::bench
