#pragma once
/// The cross-section of a twisted yarn before twisting: where its straight fibres cross the section plane
/// (Durville 2012, Sect. 7.3-7.6: rovings of fibres laid side by side, then twisted). Pure geometry in the
/// section plane, coordinates (u, v) [mm] on two orthonormal axes of that plane; docs/yarns.md draws it.
///
/// A roving is a compact bundle of n fibres of radius R whose neighbours are d = 2 R + c apart (c the
/// clearance). The m rovings of a yarn sit at the angles 2 pi k / m around the yarn axis (k = 0 .. m - 1),
/// each one the same pattern turned with its angle, at the smallest distance rho from the axis at which no
/// two fibres of different rovings are closer than d: the closest such fibres are then exactly d apart.

#include <vector>

#include <Eigen/Core>

namespace nodus::model {

using Vec2 = Eigen::Vector2d;

/// How the fibres of one roving are packed in its section.
enum class RovingPacking {
  /// The n points of a hexagonal (triangular) lattice of spacing d nearest to a centre, the centre chosen
  /// among a lattice point, the centroid of a lattice triangle and the midpoint of a lattice bond as the one
  /// whose n points have the smallest second moment (n = 1: one fibre, n = 3: a triangle, n = 7: a hexagon
  /// around a fibre). Neighbours are exactly d apart, no two fibres closer.
  hexagonal,
  /// n fibres evenly on a circle of radius d / (2 sin(pi / n)): neighbours on the circle exactly d apart
  /// (n = 1: one fibre at the centre, n = 2: a pair d apart).
  ring,
};

/// The fibre centres of one roving [mm], centroid at the origin, in a deterministic order (by distance from
/// the lattice centre, then by angle). `fibres` >= 1, `spacing` d > 0.
std::vector<Vec2> roving_pattern(RovingPacking packing, int fibres, double spacing);

/// The cross-section of a yarn.
struct YarnLayout {
  /// fibres[k][j]: centre of fibre j of roving k [mm], the yarn axis at the origin.
  std::vector<std::vector<Vec2>> fibres;
  double roving_distance = 0.0;  ///< rho: distance of each roving's centroid from the yarn axis [mm]
  double pattern_angle = 0.0;  ///< phi: turn of roving 0's pattern (that of roving k: phi + 2 pi k / m) [rad]
};

/// The yarn of `rovings` m >= 1 rovings of `fibres_per_roving` n >= 1 fibres, neighbours `spacing` d > 0
/// apart (d = 2 R + clearance). Roving k's fibre j sits at
///   x_kj = rho e(theta_k) + Q(theta_k + phi) p_j,   theta_k = 2 pi k / m,
/// with p_j = roving_pattern(packing, n, d), e(a) = (cos a, sin a) and Q(a) the rotation by a. For m = 1,
/// rho = 0 (the roving is centred). For m >= 2, rho is the smallest distance beyond which no two fibres of
/// different rovings are closer than d: each pair's distance |rho w + v| (w = e(theta_k) - e(theta_l),
/// v = Q(theta_k + phi) p_a - Q(theta_l + phi) p_b) equals d at the larger root of
///   |w|^2 rho^2 + 2 (w . v) rho + |v|^2 - d^2 = 0,
/// and rho is the largest of these roots over all pairs (0 if none). The pattern's turn phi is the one of
/// the angles 2 pi i / 720 (i = 0 .. 719) that gives the smallest yarn (the largest |x_kj|), the first on a
/// tie (a relative 1e-12).
YarnLayout yarn_layout(RovingPacking packing, int rovings, int fibres_per_roving, double spacing);

}  // namespace nodus::model
