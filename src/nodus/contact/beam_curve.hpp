#pragma once
/// The current geometry of the beams of a model in one state, as functions of the reference arc length:
/// axis position and derivative, section directors, and the closest point of an element's axis to a point.

#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::contact {

/// The current geometry of a section of a beam.
struct SectionGeometry {
  Eigen::Vector3d r;   ///< axis position [mm]
  Eigen::Vector3d dr;  ///< dr/ds, derivative along the reference arc length [-]
  Eigen::Vector3d g1;  ///< first director (interpolated, not normalised) [-]
  Eigen::Vector3d g2;  ///< second director [-]
  int element = 0;     ///< global element index
  double local = 0.0;  ///< element coordinate in [-1, 1]
};

/// How far the deformed section `g` of radius `radius` reaches from its centre towards unit `direction`:
/// the support function R |G^T d| of its disc r + xi_1 g1 + xi_2 g2, |xi| <= R [mm].
inline double section_reach(const SectionGeometry& g, const Eigen::Vector3d& direction, double radius) {
  return radius * Eigen::Vector2d(g.g1.dot(direction), g.g2.dot(direction)).norm();
}

/// Closest point of an element's axis to a point, over a range of element coordinates.
struct ClosestPoint {
  double local = 0.0;     ///< element coordinate of the closest point
  double distance = 0.0;  ///< its distance to the point [mm]
};

/// A view of the beams' current geometry in state `x`; keeps references to `model` and `x`. Building one
/// costs nothing (no table over the beams): a section's geometry is read from the three nodes of its element
/// when asked for, so evaluating it at a few particles costs as many element evaluations, however large the
/// model.
class BeamCurves {
 public:
  BeamCurves(const model::Model& model, const Eigen::VectorXd& x) : model_(model), x_(x) {}

  const model::Model& model() const { return model_; }
  double length(int beam) const { return model_.beam(beam).length(); }
  double radius(int beam) const { return model_.beam(beam).radius(); }
  /// Global index of the first element of `beam`.
  int first_element(int beam) const { return model_.first_element(beam); }
  /// Beam of global element `element`.
  int element_beam(int element) const { return model_.element_beam(element); }
  /// Reference arc length of element coordinate `local` of global element `element` [mm].
  double abscissa(int element, double local) const;

  /// Geometry of the section of `beam` at reference arc length s, clamped to [0, L].
  SectionGeometry at(int beam, double s) const;
  /// Same at element coordinate `local` of global element `element`.
  SectionGeometry at_element(int element, double local) const;
  /// Axis position of `beam` at s.
  Eigen::Vector3d position(int beam, double s) const { return at(beam, s).r; }

  /// The axis nodes of global element `element` (columns: first, middle, last node).
  Eigen::Matrix3d element_axis(int element) const;
  /// The closest point to `p` of the axis of global element `element` over local in [lo, hi] within
  /// [-1, 1] (the global minimum of the distance, a quartic in local).
  ClosestPoint closest_point(int element, const Eigen::Vector3d& p, double lo = -1.0, double hi = 1.0) const;

 private:
  const model::Model& model_;
  const Eigen::VectorXd& x_;
};

}  // namespace nodus::contact
