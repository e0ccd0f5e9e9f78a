#pragma once
/// Broad phase of the contact detection: a bounding volume hierarchy (Eigen's KdBVH) over the axis-aligned
/// boxes of the elements' axes, so that finding the elements near a point costs O(log n) instead of O(n).

#include <vector>

#include <Eigen/Geometry>
#include <unsupported/Eigen/BVH>

#include "nodus/contact/beam_curve.hpp"

namespace nodus::contact {

using Box3 = Eigen::AlignedBox3d;

/// A box that contains the axis of global element `element`: the box of the three control points of the
/// axis in Bezier form, which contain the quadratic curve (convex hull property).
Box3 element_box(const BeamCurves& curves, int element);

class ElementTree {
 public:
  /// Builds the hierarchy over `elements` (global element indices).
  ElementTree(const BeamCurves& curves, const std::vector<int>& elements);
  /// Builds the hierarchy over entries `ids` with their own `boxes` (as many).
  ElementTree(std::vector<int> ids, std::vector<Box3> boxes);

  /// Appends to `out` the elements whose box meets `box`.
  void query(const Box3& box, std::vector<int>& out) const;

 private:
  std::vector<int> elements_;
  std::vector<Box3> boxes_;            ///< per entry of elements_
  Eigen::KdBVH<double, 3, int> tree_;  ///< over indices into elements_
};

}  // namespace nodus::contact
