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
/// overlaps it most (overlap on I times overlap on J), among those whose pairing passes within `reach` plus
/// half the new zone's larger interval of its centre (pairing_distance), or `default_penalty` if none does.
/// `reach` [mm]: the detection's separation distance delta_separ.
std::vector<double> transfer_penalties(const ContactGeometry& old, const std::vector<double>& old_penalty,
                                       const ContactGeometry& next, double default_penalty, double reach);

/// The committed g_rev of each element of `next` [mm]: the old elements' values are stored at the abscissas
/// of both their particles, per pair of beams and side; a new element takes the mean of the values linearly
/// interpolated at its two particles' abscissas (a side whose abscissa lies outside the stored range gives
/// nothing), or zero if neither side gives one. An old zone whose elements straddle the abscissa on that
/// side but whose pairing (its elements' abscissas, as a polyline in the plane (s_I, s_J)) passes farther
/// than `reach` from the new element's is left out: a crossing within another pairing of the same two
/// beams keeps its own history. `reach` [mm]: the detection's separation distance delta_separ (the
/// contacts of a knot slide by up to about l_p between detections).
std::vector<Eigen::Vector3d> transfer_reversible(const ContactGeometry& old,
                                                 const std::vector<Eigen::Vector3d>& old_reversible,
                                                 const ContactGeometry& next, double reach);

}  // namespace nodus::contact
