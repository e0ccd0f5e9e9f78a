#include "nodus/beam/beam.hpp"

#include <cmath>
#include <stdexcept>

namespace nodus::beam {

Beam::Beam(BeamDefinition definition, int first_node) : def_(std::move(definition)), first_node_(first_node) {
  if (!(def_.length > 0) || !(def_.radius > 0) || def_.elements < 1)
    throw std::invalid_argument("Beam: length, radius and element count must be positive");
  if (std::abs(def_.direction.norm() - 1) > 1e-12 || std::abs(def_.director1.norm() - 1) > 1e-12 ||
      std::abs(def_.direction.dot(def_.director1)) > 1e-12)
    throw std::invalid_argument("Beam: direction and director1 must be orthonormal");
}

NodeVector Beam::reference_node(int local) const {
  NodeVector q;
  q << def_.start + abscissa(local) * def_.direction, def_.director1, director2();
  return q;
}

ElementProperties Beam::element_properties(int gauss_points) const {
  return {element_length(), section_stiffness(def_.material, def_.radius, def_.bending_factor), gauss_points};
}

}  // namespace nodus::beam
