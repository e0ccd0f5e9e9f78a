#pragma once
/// The clearance between the beams' surfaces: the smallest axis-to-axis distance minus how far the two
/// deformed sections reach towards each other (section_reach: R |G^T d|, R for a section as in the reference
/// state) over every pair of axis points of different beams, or of one beam farther apart along it than
/// delta_separ.
/// Unlike the contact elements, it sees every part of every beam: a pass-through that no contact element
/// covers shows as a clearance far below -2 p_max (the knot checks, docs/contact.md).

#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::contact {

/// Where the clearance is smallest.
struct Clearance {
  /// |r_J(u) - r_I(s)| - R_I |G_I^T d| - R_J |G_J^T d|, d the unit vector between the points [mm];
  /// +infinity if no pair of points qualifies.
  double value = 0.0;
  int beam_i = -1, beam_j = -1;
  double s_i = 0.0, s_j = 0.0;  ///< reference arc lengths [mm]
};

/// The smallest clearance among `beams` (all if empty) in state `x`, over the pairs of axis points whose
/// distance is below `reach` [mm] (larger distances count as no pair). Each element's axis is sampled at
/// `samples` points, each matched to the closest point of every other element within reach (on its own beam,
/// only over the parts farther than `separation` [mm] along it), so the distance is exact at the samples and
/// too large by O(h^2 / samples^2) between them. `parallel`: element by element on the OpenMP threads.
Clearance min_clearance(const model::Model& model, const Eigen::VectorXd& x, const std::vector<int>& beams,
                        double separation, double reach, int samples = 9, bool parallel = false);

}  // namespace nodus::contact
