#pragma once
/// Checks and measures of twisted yarns and strands: how near any two fibres' axes come (nothing may pass
/// through anything), and the helix that a fibre's centreline follows about a yarn axis. Units mm.

#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::analysis {

/// The closest approach of two different beams' surfaces, measured between their axes.
struct AxisGap {
  double gap = 0.0;  ///< min over s, s' of |r_I(s) - r_J(s')| - R_I - R_J [mm] (negative: they overlap)
  int beam_i = -1, beam_j = -1;
  double s_i = 0.0, s_j = 0.0;  ///< the reference arc lengths where it occurs [mm]
};

/// The smallest AxisGap over all pairs of different beams of `model` at state x, the axes sampled at
/// `samples` points per element (quadratic interpolation of the nodes): the sampling overestimates a
/// distance d by at most (h / samples)^2 / (8 d). Pairs whose bounding boxes lie farther apart than the
/// best gap so far are skipped. +infinity gap with fewer than two beams. `end_margin` [mm]: the points within
/// this arc length of either end of a beam are left out (the end sections a rigid body binds, where a
/// roving turned with its body may press into its neighbour where no contact element sits).
AxisGap smallest_axis_gap(const model::Model& model, const Eigen::VectorXd& x, int samples = 8,
                          double end_margin = 0.0);

/// The helix of a fibre's centreline about the axis through `origin` along `axis` (unit), from the nodes of
/// beam `beam` whose reference arc length lies in [from, to].
struct HelixFit {
  double radius = 0.0;         ///< mean distance of the nodes from the axis [mm]
  double radius_spread = 0.0;  ///< max - min of that distance [mm]
  double rate = 0.0;  ///< d(angle about the axis) / d(position along the axis), least squares [rad/mm]
  int nodes = 0;
};
HelixFit fit_helix(const model::Model& model, const Eigen::VectorXd& x, int beam,
                   const Eigen::Vector3d& origin, const Eigen::Vector3d& axis, double from, double to);

/// How far fibre `beam` winds about the centre of the fibres `beams`, the mean of their nodes of equal index
/// (each must have as many nodes as `beam`), seen along `axis` (unit): the angle of the fibre's offset from
/// that centre, projected on the plane normal to `axis`, followed node by node from the first node to the
/// last [rad], positive anticlockwise about `axis`. The count of turns is exact as long as the offset turns
/// by less than half a turn from one node to the next. Fibres whose ends are held cannot change their
/// winding by whole turns without passing through one another: a yarn twisted by turning its end bodies by
/// an angle winds by that angle (tests/long/test_knot_3x1.cpp).
double winding_about_centre(const model::Model& model, const Eigen::VectorXd& x, int beam,
                            const std::vector<int>& beams, const Eigen::Vector3d& axis);

}  // namespace nodus::analysis
