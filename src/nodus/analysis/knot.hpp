#pragma once
/// Topology checks of a rod's centreline: the knot type of an open curve (its Alexander polynomial, after
/// closing the curve far away), the smallest distance between two parts of the curve that lie far apart
/// along it, and the centreline of one beam of a model in a given state.
///
/// Alexander polynomial [Alexander 1928; Rolfsen, Knots and Links, Ch. 7]: one Wirtinger relation per
/// crossing of a planar projection, differentiated with Fox calculus and abelianised (t per generator),
/// gives an n x n matrix over Z[t]; any (n - 1)-minor is Delta(t), defined up to a factor +-t^k.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::analysis {

/// The Alexander polynomial of a knot, normalised so that its lowest power is t^0 and the coefficient of t^0
/// is positive: 1 for the unknot, 1 - t + t^2 for the trefoil (either handedness), 1 - 3t + t^2 for the
/// figure-eight knot. It does not tell a knot from its mirror image, and a few knots with 11 crossings or
/// more share the unknot's Delta = 1.
struct KnotInvariant {
  std::vector<std::int64_t> coefficients{1};  ///< of t^0, t^1, ... (palindromic)
  int crossings = 0;                          ///< crossings of the projection used, closure included
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< projection direction used (unit)

  /// Determinant of the knot, |Delta(-1)|: 1 unknot, 3 trefoil, 5 figure-eight and (2,5) torus knot.
  std::int64_t determinant() const;
  /// Human-readable polynomial, e.g. "1 - t + t^2", "1 - 3t + t^2", "1".
  std::string to_string() const;
  /// Delta = 1 (the unknot, or one of the rare non-trivial knots with the same polynomial).
  bool is_unknot() const;
  /// Delta = 1 - t + t^2 (a trefoil of either handedness).
  bool is_trefoil() const;
};

/// Knot type of the polyline `open_curve` [mm] through its vertices in order.
///
/// An open curve is closed far away: each end is extended radially away from the length-weighted centroid c
/// of the curve (along its end tangent when the end lies at c) to the sphere of radius 4 R about c, R the
/// largest distance of a vertex from c, and the two far points are joined along that sphere (meridian, the
/// great circle normal to the projection direction, meridian), which adds no crossing with the part of the
/// curve inside the ball of radius R. Every such closure is the same knot. A curve whose last vertex repeats
/// its first is taken as closed as it is.
///
/// The closed polygon is projected along each of 24 fixed, generic directions; projections where a vertex
/// falls within 1e-10 R of another segment, a segment is seen end-on, two crossings on one segment coincide,
/// or the two strands of a crossing are within 1e-10 R in space are skipped, and the one with the fewest
/// crossings is used. Delta is computed exactly (determinants modulo three primes near 2^62, interpolated
/// and recombined; provably exact up to 62 crossings, checked against the third prime beyond), and
/// checked to satisfy |Delta(1)| = 1 and Delta(t) = t^deg Delta(1/t).
///
/// Throws std::invalid_argument for fewer than two distinct vertices, and std::runtime_error when every
/// projection is degenerate (the curve touches itself within 1e-10 R).
KnotInvariant knot_invariant(const std::vector<Eigen::Vector3d>& open_curve);

/// Same, projected along `direction` only (any non-zero vector); throws std::runtime_error if that
/// projection is degenerate.
KnotInvariant knot_invariant(const std::vector<Eigen::Vector3d>& open_curve,
                             const Eigen::Vector3d& direction);

/// Where two parts of a curve, far apart along it, come closest.
struct SelfDistance {
  double distance = 0.0;  ///< [mm]; +infinity when no two points of the curve are `separation` apart
  double s1 = 0.0;        ///< reference arc length of the first point [mm]
  double s2 = 0.0;        ///< reference arc length of the second point, s2 - s1 >= separation [mm]
};

/// Smallest distance |x(s1) - x(s2)| [mm] between two points of the polyline `curve` [mm] whose reference
/// arc lengths differ by at least `separation` [mm]; `arc_length` [mm] gives the reference arc length of
/// each vertex (strictly increasing) and is interpolated linearly along each segment. Each pair of segments
/// is solved exactly: the closest points of the two segments, or, when these are closer than `separation`
/// along the curve, the closest points on the line s2 - s1 = separation (a convex quadratic over a
/// polygon). Pairs whose boxes are farther apart than the best distance so far are skipped.
///
/// Two points `separation` apart on a straight stretch are `separation` apart in space: pick `separation`
/// several rod diameters long so that only genuine self-contacts come out below 2 R. Throws
/// std::invalid_argument if the sizes differ, arc_length is not strictly increasing, or separation < 0.
SelfDistance min_self_distance(const std::vector<Eigen::Vector3d>& curve,
                               const std::vector<double>& arc_length, double separation);

/// Where two curves come closest.
struct CurveDistance {
  double distance = 0.0;  ///< [mm]; +infinity when either curve has fewer than two vertices
  double s1 = 0.0;        ///< reference arc length of the point on the first curve [mm]
  double s2 = 0.0;        ///< reference arc length of the point on the second curve [mm]
};

/// Smallest distance [mm] between the polylines `curve1` and `curve2` [mm] (two fibres of a yarn), each with
/// the reference arc length of its vertices (`arc_length1`, `arc_length2`, interpolated linearly along each
/// segment). Each pair of segments is solved exactly; pairs whose boxes are farther apart than the best
/// distance so far are skipped. Throws std::invalid_argument if a curve and its arc lengths differ in size.
CurveDistance min_distance_between(const std::vector<Eigen::Vector3d>& curve1,
                                   const std::vector<double>& arc_length1,
                                   const std::vector<Eigen::Vector3d>& curve2,
                                   const std::vector<double>& arc_length2);

/// The mean centreline of a yarn: vertex k is the mean of vertex k of every curve of `fibres`. The fibres of
/// a yarn have equal numbers of nodes, laid side by side along the yarn axis (docs/yarns.md). Throws
/// std::invalid_argument if `fibres` is empty or the curves differ in their numbers of vertices.
std::vector<Eigen::Vector3d> mean_curve(const std::vector<std::vector<Eigen::Vector3d>>& fibres);

/// The nodes of one beam in order along it.
struct Centreline {
  std::vector<Eigen::Vector3d> points;  ///< current node positions r [mm]
  std::vector<double> arc_length;       ///< reference arc length of each node [mm]
};

/// The centreline of beam `beam` of `model` in `state` (nine values per node, model/model.hpp) as a polyline:
/// with `segments_per_element` = 2 (the default) its 2 n + 1 nodes, element end and middle nodes alike;
/// with more, also points of the quadratic interpolation of each element at equal steps of its reference
/// abscissa, so that the polyline follows the curved axis (the chord between two nodes of an element
/// curved to 1 / kappa departs from it by kappa h^2 / 32, 6 um for h = 0.2 mm at kappa = 5 / mm). Throws
/// std::invalid_argument if state.size() differs from model.num_dofs() or segments_per_element < 1,
/// std::out_of_range for a beam index out of range.
Centreline beam_centreline(const model::Model& model, const Eigen::VectorXd& state, int beam,
                           int segments_per_element = 2);

}  // namespace nodus::analysis
