#pragma once
/// The guard against passing through within a step: did two beam axes cross each other between two states?
///
/// The contact elements and the clearance (clearance.hpp) look at one state. A step whose Newton solve jumps
/// a strand through another (the knot pulled at 3.5 N: one step of 61 iterations took it from a trefoil to an
/// unknot) ends in a state where the strands lie apart again, and both see nothing wrong. This check follows
/// the axes from the step's start to its end instead: each element's axis is taken as the polyline through
/// its three nodes, each node moves on the straight line from its start to its end position, and two segments
/// of the polylines cross when, at some instant of that motion, they meet. Two segments meet only when their
/// four end points are coplanar, a cubic in the instant (the edge-edge test of continuous collision
/// detection); its roots in the step are found by bisection between its critical points, and at each the
/// segments are tested for meeting.
///
/// What it does not see: segments parallel throughout (the cubic vanishes identically; a pass-through between
/// curved axes shows at a neighbouring, non-parallel pair), and a crossing that the straight-line motion of
/// the nodes does not make (a step that goes round, not through). The chord of a quadratic element departs
/// from its axis by at most h^2 kappa / 32 (h the element length, kappa the curvature): 8e-4 mm on the knot's
/// tightest coil (h = 0.067 mm, kappa = 1 / 0.18 mm), against 2 R = 0.2 mm between axes in contact.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::contact {

/// Where two axes crossed.
struct Crossing {
  double instant = 0.0;  ///< fraction of the step, in (0, 1]
  int beam_i = -1, beam_j = -1;
  double s_i = 0.0, s_j = 0.0;  ///< reference arc lengths where the axes met [mm]
};

/// Where two segments met while moving: their coordinates along each (0 at the first point, 1 at the second).
struct SegmentMeeting {
  double instant = 0.0;  ///< in (0, 1]
  double u = 0.0, v = 0.0;
};

/// Segments p0-p1 and q0-q1 move, each end point on a straight line from its position in `start` to its
/// position in `end` (columns: p0, p1, q0, q1). The first instant in (0, 1] at which they meet, if any.
std::optional<SegmentMeeting> segments_meet(const Eigen::Matrix<double, 3, 4>& start,
                                            const Eigen::Matrix<double, 3, 4>& end);

/// The first crossing found between the axes of `beams` (all if empty) moving from state `x0` to state `x1`:
/// pairs of different beams, and pairs of one beam's parts more than `separation` [mm] apart along it (as the
/// clearance and the contact detection pair them). `parallel`: segment by segment on the OpenMP threads.
/// Which crossing is reported when there are several depends on nothing but the states.
std::optional<Crossing> find_crossing(const model::Model& model, const Eigen::VectorXd& x0,
                                      const Eigen::VectorXd& x1, const std::vector<int>& beams,
                                      double separation, bool parallel = false);

}  // namespace nodus::contact
