#pragma once
/// Contact detection [Durville 2012, Sect. 4, Eq. 24-48]: where beams (or two separate parts of one beam)
/// are close, the proximity zones, their intermediate geometries, and the contact elements along them, each
/// a pair of material particles on the two beam surfaces with a normal direction and a gap.
///
/// Conventions (docs/contact.md):
/// - A zone pairs [a, b] on beam I with [c, d] on beam J; c > d when the parts run antiparallel. For a pair
///   of distinct beams I < J; for self-contact I = J and [a, b] is the later part (a > c, a > d).
/// - `normal` is a unit vector pointing from the particle on I towards the particle on J; the gap is
///   <x_J - x_I, normal>, negative when the surfaces overlap. The force on J (next issue) acts along +normal.

#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::contact {

using Vec3 = Eigen::Vector3d;

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

/// A material particle of a beam: the point of reference coordinates (xi1, xi2, xi3) [Eq. 9], where xi3 is
/// the reference arc length along the axis and (xi1, xi2) the coordinates on the section in the director
/// basis. Its current position is r(xi3) + xi1 g1(xi3) + xi2 g2(xi3), linear in the 27 unknowns of
/// `element`.
struct Particle {
  int beam = 0;
  int element = 0;                                       ///< global element index (model numbering)
  double local = 0.0;                                    ///< coordinate of xi3 in the element, in [-1, 1]
  double abscissa = 0.0;                                 ///< xi3 [mm]
  Eigen::Vector2d transverse = Eigen::Vector2d::Zero();  ///< (xi1, xi2), of norm R [mm]
};

/// A proximity zone Z_IJ = [a, b] x [c, d] (Eq. 24-25, 31-32) and its contact elements.
struct ProximityZone {
  int beam_i = 0;
  int beam_j = 0;
  double a = 0.0, b = 0.0;  ///< interval on beam I [mm], a < b
  double c = 0.0, d = 0.0;  ///< interval on beam J [mm]; c > d for antiparallel parts
  int first_element = 0;    ///< index of its first contact element in ContactGeometry::elements
  int num_elements = 0;     ///< number of its contact elements
};

/// A contact element (Eq. 48): the pair of particles candidate to contact at one point of an intermediate
/// geometry, its normal direction and gap.
struct ContactElement {
  int zone = 0;
  double zeta = 0.0;                 ///< relative abscissa on the intermediate geometry, in [0, 1]
  Vec3 intermediate = Vec3::Zero();  ///< x_int(zeta) [mm] (Eq. 33)
  Particle particle_i;               ///< on beam I
  Particle particle_j;               ///< on beam J
  Vec3 position_i = Vec3::Zero();    ///< current position of particle_i [mm]
  Vec3 position_j = Vec3::Zero();    ///< current position of particle_j [mm]
  Vec3 normal = Vec3::UnitZ();       ///< unit, from I towards J (Eq. 41-44)
  double gap = 0.0;                  ///< <position_j - position_i, normal> [mm] (Eq. 45)
  double parallel_weight = 0.0;      ///< 1: double-cross-product normal only (Eq. 44); 0: cross (Eq. 42)
};

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

/// The contact element at relative abscissa `zeta` in [0, 1] of `zone` in state `x` (Eq. 33-45), built as
/// detect() builds the elements of a zone (the `zone` field of `out` is left as it is). False if the plane
/// normal to the intermediate geometry misses one of the two axes.
bool contact_element_at(const model::Model& model, const Eigen::VectorXd& x, const ProximityZone& zone,
                        double zeta, ContactElement& out);

/// Recomputes, in state `x`, the normal of contact element `e` for its particles as they are (Eq. 41-44; the
/// fixed point on normal directions of Sect. 6), with its positions and gap. False if it is undefined.
/// With `facing`, the particles are first moved, at their abscissas, to the points of their sections' borders
/// that face each other along the new normal (as contact_response places them with facing_particles).
/// Reads only the two elements that carry the particles: its cost does not depend on the size of the model.
bool update_normal(const model::Model& model, const Eigen::VectorXd& x, ContactElement& e,
                   bool facing = false);

}  // namespace nodus::contact
