#pragma once
/// Contact elements [Durville 2012, Sect. 4.2-4.3, Eq. 33-48]: along the intermediate geometry of a proximity
/// zone, the sections of the two beams cut by the plane normal to it, the pair of material particles on their
/// borders candidate to contact, the normal direction between them and the gap. Conventions in detection.hpp.

#include <vector>

#include <Eigen/Core>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/detection_parameters.hpp"
#include "nodus/contact/proximity_zone.hpp"
#include "nodus/model/model.hpp"

namespace nodus::contact {

using Vec3 = Eigen::Vector3d;

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

/// The `count` contact elements of `zone` in the state of `curves` (Eq. 46-48; see contact_element.cpp for
/// how the grid is placed), their sections paired by `pairing`; the `zone` field of each is left 0. In a zone
/// of a beam with itself, no element pairs two sections less than `self_separation` apart along the axis
/// (detection: delta_separ - l_p, the least distance of the points it pairs on one beam, Eq. 29, within its
/// zones' padding).
std::vector<ContactElement> zone_elements(const BeamCurves& curves, const ProximityZone& zone, int count,
                                          SectionPairing pairing = SectionPairing::plane,
                                          double self_separation = 0.0);

/// The contact element at relative abscissa `zeta` in [0, 1] of `zone` in state `x` (Eq. 33-45), built as
/// detect() builds the elements of a zone, which passes delta_separ - l_p as `self_separation` (the `zone`
/// field of `out` is left as it is). False if the plane normal to the intermediate geometry misses one of the
/// two axes (with SectionPairing::bisector: if no pair of sections on the line of zeta has its centre line
/// normal to their mean tangent), or if, in a zone of a beam with itself, the two sections lie less than
/// `self_separation` apart along the axis.
bool contact_element_at(const model::Model& model, const Eigen::VectorXd& x, const ProximityZone& zone,
                        double zeta, ContactElement& out, SectionPairing pairing = SectionPairing::plane,
                        double self_separation = 0.0);

/// Recomputes, in state `x`, the normal of contact element `e` for its particles as they are (Eq. 41-44; the
/// fixed point on normal directions of Sect. 6), with its positions and gap. False if it is undefined.
/// With `facing`, the particles are first moved, at their abscissas, to the points of their sections' borders
/// that face each other along the new normal (as contact_response places them with facing_particles), or,
/// with `along_centres` too, along the direction between the section centres
/// (ResponseOptions::centre_facing). Reads only the two elements that carry the particles: its cost does not
/// depend on the size of the model.
bool update_normal(const model::Model& model, const Eigen::VectorXd& x, ContactElement& e,
                   bool facing = false, bool along_centres = false);

/// The overlap of the two sections of contact element `e` in state `x` along the line of their centres:
/// h_I(d) + h_J(-d) - |r_J - r_I| [mm], d = (r_J - r_I) / |r_J - r_I|, with h(d) = R |G^T d| the distance
/// from the centre to the section's border point furthest along d (the section as its directors G = [g1 g2]
/// have deformed it). Positive: the tubes overlap there. It is the penetration along the centres' direction,
/// and does not depend on the element's normal, whose orientation a large relative rotation within a step may
/// flip so that an overlap shows a positive gap.
double centre_overlap(const model::Model& model, const Eigen::VectorXd& x, const ContactElement& e);

}  // namespace nodus::contact
