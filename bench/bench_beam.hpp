#pragma once
// The straight beam every benchmark uses: L = 20 mm, R = 0.1 mm (Table 1's rod), E = 4000 MPa, nu = 0.3,
// along x with g1 = y.

#include "nodus/beam/beam.hpp"

namespace nodus::bench {

inline constexpr double kLength = 20.0;  // mm
inline constexpr double kRadius = 0.1;   // mm

inline beam::BeamDefinition benchmark_beam(int elements) {
  beam::BeamDefinition def;
  def.name = "beam";
  def.length = kLength;
  def.radius = kRadius;
  def.elements = elements;
  def.material = {4000.0, 0.3};
  return def;
}

}  // namespace nodus::bench
