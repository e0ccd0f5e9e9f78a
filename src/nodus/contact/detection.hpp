#pragma once
/// Contact detection [Durville 2012, Sect. 4, Eq. 24-48]: where beams (or two separate parts of one beam)
/// are close, the proximity zones, their intermediate geometries, and the contact elements along them, each
/// a pair of material particles on the two beam surfaces with a normal direction and a gap.
///
/// Conventions (docs/contact.md):
/// - A zone pairs [a, b] on beam I with [c, d] on beam J; c > d when the parts run antiparallel. For a pair
///   of distinct beams I < J; for self-contact I = J and [a, b] is the later part (a > c, a > d).
/// - `normal` is a unit vector pointing from the particle on I towards the particle on J; the gap is
///   <x_J - x_I, normal>, negative when the surfaces overlap. The force on J acts along +normal.

#include <vector>

#include <Eigen/Core>

#include "nodus/contact/contact_element.hpp"
#include "nodus/contact/detection_parameters.hpp"
#include "nodus/contact/proximity_zone.hpp"
#include "nodus/model/model.hpp"

namespace nodus::contact {

/// The outcome of one detection.
struct ContactGeometry {
  std::vector<ProximityZone> zones;
  std::vector<ContactElement> elements;
};

/// Detects contact between the beams listed in `beams` (indices into model.beams(); all beams if empty)
/// in state `x` (nine values per node). Zones come ordered by (beam_i, beam_j, a). `previous`, the last
/// detection (may be null), settles the orientation of zones where the axes cross at more than 60 degrees
/// and either pairing would do: such a zone keeps the orientation of the previous zone it overlaps.
ContactGeometry detect(const model::Model& model, const Eigen::VectorXd& x,
                       const DetectionParameters& parameters, const std::vector<int>& beams = {},
                       const ContactGeometry* previous = nullptr);

}  // namespace nodus::contact
