#pragma once
/// The lengths of contact detection [Durville 2012, Sect. 4]: delta_prox, delta_separ, h_dist, l_p and h_c,
/// and their defaults (docs/contact.md).

#include <vector>

#include "nodus/model/model.hpp"

namespace nodus::contact {

/// The five lengths of the detection [mm]. A value <= 0 means "derive the default" (resolve_parameters).
struct DetectionParameters {
  double proximity_distance = 0.0;   ///< delta_prox: largest axis-to-axis distance of a proximity (Eq. 24)
  double separation_distance = 0.0;  ///< delta_separ: smallest arc distance within one beam (Eq. 29)
  double test_point_spacing = 0.0;   ///< h_dist: spacing of test points (Eq. 26-27)
  double matching_length = 0.0;      ///< l_p: length of an elementary matching interval (Eq. 30-32)
  double element_spacing = 0.0;      ///< h_c: spacing of contact elements along a zone (Eq. 46)
  bool self_contact = true;          ///< look for contact between separate parts of each beam
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

}  // namespace nodus::contact
