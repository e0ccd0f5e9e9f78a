#pragma once
/// Proximity zones [Durville 2012, Sect. 4.1, Eq. 24-32]: the pairs of parts of beams (or of separate parts
/// of one beam) whose axes come within delta_prox, found from test points along each beam matched to the
/// closest points of the others, and merged so that the result does not depend on which beam found them.

#include <vector>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"
#include "nodus/contact/detection_parameters.hpp"

namespace nodus::contact {

/// A proximity zone Z_IJ = [a, b] x [c, d] (Eq. 24-25, 31-32) and its contact elements.
struct ProximityZone {
  int beam_i = 0;
  int beam_j = 0;
  double a = 0.0, b = 0.0;  ///< interval on beam I [mm], a < b
  double c = 0.0, d = 0.0;  ///< interval on beam J [mm]; c > d for antiparallel parts
  int first_element = 0;    ///< index of its first contact element in ContactGeometry::elements
  int num_elements = 0;     ///< number of its contact elements
};

/// The distance from `p` to the segment [a, b] (in the plane of abscissas (s_I, s_J)).
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The distance in the plane of abscissas (s_I, s_J) from (s_i, s_j) to `zone`'s pairing, the segment from
/// (a, c) to (b, d) along which its contact elements sit [mm]. Zones of one pair of beams whose boxes
/// [a, b] x [c, d] overlap may still pair different parts: two fibres of a yarn paired side by side all along
/// it also cross where the yarn's knot crosses itself, inside that box but far from its pairing.
double pairing_distance(const ProximityZone& zone, double s_i, double s_j);

/// The proximity zones between the beams `beams` (sorted, unique) of `curves`, ordered by (beam_i, beam_j,
/// a); `tree` holds their elements. Zones whose orientation is weakly decided (axes crossing at more than 60
/// degrees) keep that of an overlapping zone of `previous` (may be null). `parallel`: beam by beam on the
/// OpenMP threads (the result does not depend on it).
std::vector<ProximityZone> find_zones(const BeamCurves& curves, const ElementTree& tree,
                                      const std::vector<int>& beams, const DetectionParameters& prm,
                                      const std::vector<ProximityZone>* previous, bool parallel);

}  // namespace nodus::contact
