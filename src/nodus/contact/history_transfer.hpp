#pragma once
/// What a new detection inherits from the last one [Durville 2012, Sect. 5.2.3]: the penalty of each zone,
/// adjusted by the contact loops, and the committed reversible tangential displacement g_rev of each contact
/// element, the history of friction. Contact elements are rebuilt at each detection at new particles; their
/// history is interpolated along the beams from the old elements' particles.

#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"

namespace nodus::contact {

/// The penalty of each zone of `next` [N/mm]: that of the zone of `old` of the same pair of beams that
/// overlaps it most (overlap on I times overlap on J), or `default_penalty` if none overlaps.
std::vector<double> transfer_penalties(const ContactGeometry& old, const std::vector<double>& old_penalty,
                                       const ContactGeometry& next, double default_penalty);

/// The committed g_rev of each element of `next` [mm]: the old elements' values are stored at the abscissas
/// of both their particles, per pair of beams and side; a new element takes the mean of the values linearly
/// interpolated at its two particles' abscissas (a side whose abscissa lies outside the stored range gives
/// nothing), or zero if neither side gives one.
std::vector<Eigen::Vector3d> transfer_reversible(const ContactGeometry& old,
                                                 const std::vector<Eigen::Vector3d>& old_reversible,
                                                 const ContactGeometry& next);

}  // namespace nodus::contact
