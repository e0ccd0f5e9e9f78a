#pragma once
/// A straight beam, its mesh of 3-node quadratic elements and its reference placement
/// [Durville 2012, Sect. 3.1, Eq. 9-11].

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nodus/beam/beam_element.hpp"
#include "nodus/beam/section.hpp"

namespace nodus::beam {

using Vec3 = Eigen::Vector3d;
using NodeVector = Eigen::Matrix<double, kNodeDofs, 1>;

/// Where a straight beam lies in its reference configuration and what it is made of.
struct BeamDefinition {
  std::string name;
  double length = 1.0;             ///< L [mm]
  double radius = 0.01;            ///< R [mm]
  int elements = 1;                ///< number of quadratic elements
  Vec3 start = Vec3::Zero();       ///< centre of the first end section [mm]
  Vec3 direction = Vec3::UnitX();  ///< unit axis direction
  Vec3 director1 = Vec3::UnitY();  ///< unit first director, orthogonal to direction
  ElasticConstants material{1.0, 0.0};
  double bending_factor = 1.0;  ///< multiplies I in bending [Table 1]
};

/// A beam of the model: its definition and where its nodes sit in the global numbering.
class Beam {
 public:
  Beam(BeamDefinition definition, int first_node);

  const BeamDefinition& definition() const { return def_; }
  const std::string& name() const { return def_.name; }
  double length() const { return def_.length; }
  double radius() const { return def_.radius; }
  int num_elements() const { return def_.elements; }
  int num_nodes() const { return 2 * def_.elements + 1; }
  double element_length() const { return def_.length / def_.elements; }
  /// Global index of local node `local` (0 .. 2n).
  int node(int local) const { return first_node_ + local; }
  int first_node() const { return first_node_; }
  /// Reference arc length of local node `local` [mm].
  double abscissa(int local) const { return 0.5 * element_length() * local; }
  /// Second unit director, g2 = t x g1.
  Vec3 director2() const { return def_.direction.cross(def_.director1); }
  /// Reference values (r, g1, g2) of local node `local`.
  NodeVector reference_node(int local) const;
  ElementProperties element_properties(int gauss_points) const;

 private:
  BeamDefinition def_;
  int first_node_;
};

}  // namespace nodus::beam
