#pragma once
/// The lengths of contact detection [Durville 2012, Sect. 4]: delta_prox, delta_separ, h_dist, l_p and h_c,
/// and their defaults (docs/contact.md).

#include <vector>

#include "nodus/model/model.hpp"

namespace nodus::contact {

/// Which two sections a contact element pairs (contact.section_pairing; docs/contact.md, "Contact elements").
enum class SectionPairing {
  /// The paper's (Eq. 33-36): the zone's intervals paired linearly, x_int(zeta) the midpoint of the paired
  /// axis points, and the plane through it normal to the intermediate geometry cuts each axis.
  plane,
  /// From the same linearly paired abscissas, the pair moved along the zone's other diagonal, (s_I, s_J) +
  /// lambda (b - a, -(d - c)), to where the line between the section centres is normal to the pair's own
  /// t_int = (b - a) r_I' + (d - c) r_J' (Eq. 34). Where the closest points of the two axes do not follow
  /// each other linearly (a strand wrapping round another in a tight knot), the plane cut pairs sections far
  /// from their closest points; this pairing follows them. The same sections as the plane where the paired
  /// points face each other (parallel, antiparallel, and symmetric crossings).
  bisector,
};

/// The five lengths of the detection [mm]. A value <= 0 means "derive the default" (resolve_parameters).
struct DetectionParameters {
  double proximity_distance = 0.0;   ///< delta_prox: largest axis-to-axis distance of a proximity (Eq. 24)
  double separation_distance = 0.0;  ///< delta_separ: smallest arc distance within one beam (Eq. 29)
  double test_point_spacing = 0.0;   ///< h_dist: spacing of test points (Eq. 26-27)
  double matching_length = 0.0;      ///< l_p: length of an elementary matching interval (Eq. 30-32)
  double element_spacing = 0.0;      ///< h_c: spacing of contact elements along a zone (Eq. 46)
  bool self_contact = true;          ///< look for contact between separate parts of each beam
  SectionPairing pairing = SectionPairing::plane;  ///< which sections each contact element pairs
};

/// The parameters with every unset (<= 0) length but h_c replaced by its default, derived from the largest
/// radius R over `beams` (all beams if empty; docs/contact.md): delta_prox = 3 R (1.5 times the contact
/// distance 2 R); h_dist = sqrt(delta_prox^2 - (2 R)^2), at least delta_prox / 2 (a crossing at axis
/// distance 2 R is seen by at least one test point, with a factor 2 to spare, Eq. 27); l_p = 2 h_dist;
/// delta_separ = 4 delta_prox. An unset h_c stays 0: each zone then uses half the smaller element length of
/// its two beams.
/// Throws std::invalid_argument (one line) if the set values are inconsistent: l_p < h_dist, or
/// delta_separ <= delta_prox.
DetectionParameters resolve_parameters(const DetectionParameters& given, const model::Model& model,
                                       const std::vector<int>& beams);
/// The same for the largest radius `radius` of the contact beams.
DetectionParameters resolve_parameters(const DetectionParameters& given, double radius);

}  // namespace nodus::contact
