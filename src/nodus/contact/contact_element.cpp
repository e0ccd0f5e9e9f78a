#include "nodus/contact/contact_element.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/normal_direction.hpp"

namespace nodus::contact {
namespace {

double clamp_to(double s, double length) {
  return std::clamp(s, 0.0, length);
}

/// The abscissa where the plane through `x` normal to `t` cuts the axis of `beam` (Eq. 36), by safeguarded
/// Newton from `s`; false if the plane misses the beam.
bool cut_axis(const BeamCurves& curves, int beam, const Eigen::Vector3d& x, const Eigen::Vector3d& t,
              double& s) {
  const double length = curves.length(beam);
  const double tol = 1e-12 * length;
  const auto residual = [&](double v) { return (curves.position(beam, v) - x).dot(t); };
  double f = residual(s);
  for (int it = 0; it < 60; ++it) {
    const double slope = curves.at(beam, s).dr.dot(t);
    if (!(std::abs(slope) > 0.0)) return false;
    double step = -f / slope;
    double next = clamp_to(s + step, length), f_next = residual(next);
    for (int halve = 0; halve < 30 && std::abs(f_next) >= std::abs(f) && std::abs(next - s) > tol; ++halve) {
      step *= 0.5;
      next = clamp_to(s + step, length);
      f_next = residual(next);
    }
    const double moved = std::abs(next - s);
    s = next;
    f = f_next;
    if (moved <= tol) break;
  }
  // A root: the residual is at rounding level of the plane's offset.
  return std::abs(f) <= 1e-9 * t.norm() * curves.model().beam(beam).element_length();
}

/// The transverse material coordinates of the point where the direction `d`, projected on the section, meets
/// the section's border xi1^2 + xi2^2 = R^2 (Eq. 38-40).
Eigen::Vector2d border_point(const SectionGeometry& g, const Eigen::Vector3d& d, double radius) {
  const Eigen::Vector3d nu = g.g1.cross(g.g2).normalized();
  const Eigen::Vector3d projected = d - d.dot(nu) * nu;
  Eigen::Matrix2d gram;
  gram << g.g1.dot(g.g1), g.g1.dot(g.g2), g.g2.dot(g.g1), g.g2.dot(g.g2);
  const Eigen::Vector2d eta = gram.ldlt().solve(Eigen::Vector2d(g.g1.dot(projected), g.g2.dot(projected)));
  return radius * eta / eta.norm();
}

Particle make_particle(int beam, double s, const SectionGeometry& g, const Eigen::Vector2d& transverse) {
  return {beam, g.element, g.local, s, transverse};
}

/// The direction d between the section centres (Eq. 37) and the normal (Eq. 41-44), oriented from I towards
/// J, of the sections `gi` and `gj`; false if neither is defined (coincident centres of parallel axes).
bool section_normal(const SectionGeometry& gi, const SectionGeometry& gj, double length_scale,
                    Eigen::Vector3d& d, Eigen::Vector3d& normal, double& parallel_weight) {
  NormalDirection n;
  if (!normal_direction(gi.r, gi.dr, gj.r, gj.dr, 1e-12 * length_scale, n)) return false;
  d = n.d;
  normal = n.normal;
  parallel_weight = n.parallel_weight;
  return true;
}

/// SectionPairing::bisector: moves the linearly paired abscissas (s_i, s_j) of `zone` along its other
/// diagonal, (s_i, s_j) + lambda (b - a, -(d - c)), to a root of f(lambda) = <r_J - r_I, t> / |t|, with t the
/// pair's own Eq. 34 tangent (b - a) r_I' + (d - c) r_J': the centre line normal to it. Safeguarded Newton
/// from lambda = 0 (finite-difference slope, steps of at most a quarter of the zone); false if no root is
/// found (f is NaN where t vanishes), or if it lies beyond a beam's end.
bool bisector_pair(const BeamCurves& curves, const ProximityZone& zone, double& s_i, double& s_j) {
  const double s_i0 = s_i, s_j0 = s_j, di = zone.b - zone.a, dj = zone.d - zone.c;
  const auto f = [&](double lambda) {
    const SectionGeometry p = curves.at(zone.beam_i, s_i0 + lambda * di);
    const SectionGeometry q = curves.at(zone.beam_j, s_j0 - lambda * dj);
    const Eigen::Vector3d t = di * p.dr + dj * q.dr;
    const double norm = t.norm();
    return norm > 0.0 ? (q.r - p.r).dot(t) / norm : std::numeric_limits<double>::quiet_NaN();
  };
  constexpr double kDelta = 1e-7;  // of the zone's extent: the slope's finite difference
  double lambda = 0.0, value = f(0.0);
  for (int it = 0; it < 50 && std::isfinite(value) && value != 0.0; ++it) {
    const double slope = (f(lambda + kDelta) - f(lambda - kDelta)) / (2.0 * kDelta);
    if (!(std::abs(slope) > 0.0)) break;
    double step = std::clamp(-value / slope, -0.25, 0.25), next = lambda + step, next_value = f(next);
    for (int halve = 0; halve < 30 && !(std::abs(next_value) < std::abs(value)); ++halve) {
      step *= 0.5;
      next = lambda + step;
      next_value = f(next);
    }
    if (!(std::abs(next_value) < std::abs(value))) break;  // no decrease: at the root to rounding
    lambda = next;
    value = next_value;
    if (std::abs(step) <= 1e-15) break;
  }
  // A root: the centre line's component along t at rounding level of the distances involved.
  const double length = std::max(curves.model().beam(zone.beam_i).element_length(),
                                 curves.model().beam(zone.beam_j).element_length());
  if (!(std::abs(value) <= 1e-9 * length)) return false;
  s_i = s_i0 + lambda * di;
  s_j = s_j0 - lambda * dj;
  // Beyond a beam's end the sections are its end section (BeamCurves::at clamps): such a root pairs a
  // section with a point off the beam, as the plane's cut missing the beam does; no element there.
  const auto on_beam = [&](int beam, double s) {
    return s >= -1e-12 * curves.length(beam) && s <= (1.0 + 1e-12) * curves.length(beam);
  };
  return on_beam(zone.beam_i, s_i) && on_beam(zone.beam_j, s_j);
}

/// The contact element at relative abscissa zeta of `zone` (Eq. 33-45), its sections paired by `pairing`;
/// false if the plane normal to the intermediate geometry misses one of the axes (bisector: no pair is
/// found), the axes meet, or the sections of one beam lie less than `self_separation` apart.
bool make_element(const BeamCurves& curves, const ProximityZone& zone, double zeta, SectionPairing pairing,
                  double self_separation, ContactElement& out) {
  const int bi = zone.beam_i, bj = zone.beam_j;
  double s_i = zone.a + zeta * (zone.b - zone.a);
  double s_j = zone.c + zeta * (zone.d - zone.c);
  const SectionGeometry gi0 = curves.at(bi, s_i), gj0 = curves.at(bj, s_j);
  const Eigen::Vector3d x_int = 0.5 * (gi0.r + gj0.r);                                            // Eq. 33
  const Eigen::Vector3d t_int = 0.5 * ((zone.b - zone.a) * gi0.dr + (zone.d - zone.c) * gj0.dr);  // Eq. 34
  if (!(t_int.norm() > 0.0)) return false;
  if (pairing == SectionPairing::bisector) {
    if (!bisector_pair(curves, zone, s_i, s_j)) return false;
  } else if (!cut_axis(curves, bi, x_int, t_int, s_i) || !cut_axis(curves, bj, x_int, t_int, s_j)) {
    return false;
  }
  // The cut must lie on the part of the axis that the zone pairs. Where an axis runs nearly along the plane
  // (at the end of a zone, where the strands of a knot part), Newton may land on another crossing of the
  // plane with the axis, even on the other part of the same beam: a self-contact element pairing a section
  // with itself (gap -2R, R_N 127 N in the tightened knot). Such an element is not created. Margin: half the
  // zone's interval on either side.
  const auto inside = [](double v, double lo, double hi) {
    if (lo > hi) std::swap(lo, hi);
    const double margin = 0.5 * (hi - lo);
    return v >= lo - margin && v <= hi + margin;
  };
  if (!inside(s_i, zone.a, zone.b) || !inside(s_j, zone.c, zone.d)) return false;
  // Two sections of one beam closer along its axis than detection pairs points (delta_separ, Eq. 29, less
  // l_p, the zones' padding at both ends) are not two parts of the beam pressing on each other. In a zone of
  // a tightly coiled part the bisector's equation has the trivial root s_i = s_j (the centre line vanishes):
  // in the knot pulled at 3.4 N an element paired s = 7.8598 mm with itself, a gap of -2R that refused every
  // step as a surface passing through (docs/knot.md, "The tightening force").
  if (bi == bj && std::abs(s_i - s_j) < self_separation) return false;
  const SectionGeometry gi = curves.at(bi, s_i), gj = curves.at(bj, s_j);

  Eigen::Vector3d d, normal;
  double parallel_weight = 0.0;
  if (!section_normal(gi, gj, curves.length(bi), d, normal, parallel_weight)) return false;

  const Eigen::Vector2d xi_i = border_point(gi, d, curves.radius(bi));
  const Eigen::Vector2d xi_j = border_point(gj, -d, curves.radius(bj));
  out.zeta = zeta;
  out.intermediate = x_int;
  out.particle_i = make_particle(bi, s_i, gi, xi_i);
  out.particle_j = make_particle(bj, s_j, gj, xi_j);
  out.position_i = gi.r + xi_i.x() * gi.g1 + xi_i.y() * gi.g2;
  out.position_j = gj.r + xi_j.x() * gj.g1 + xi_j.y() * gj.g2;
  out.normal = normal;
  out.gap = (out.position_j - out.position_i).dot(normal);  // Eq. 45
  out.parallel_weight = parallel_weight;
  return true;
}

/// The contact elements of a zone: the paper's uniform grid of `count` elements (Eq. 46-48), shifted when the
/// gap has a marked minimum (a crossing) so that one element sits at it. The uniform grid may miss the
/// minimum by half a spacing, which for two circular beams crossing at a steep angle leaves a gap larger than
/// the true one by about (h_c / 2)^2 / (4 R) (0.0017 mm for R = 0.1 mm, h_c = 0.05 mm: close to the paper's
/// p_max). The minimum is the vertex of the parabola through the smallest gap of the uniform grid and its
/// two neighbours; the grid is shifted only when that vertex lies lower by more than 1e-4 R, so that on
/// parallel parts, where the gap is flat and its minimum is noise, the elements keep their places from one
/// detection to the next.
}  // namespace

std::vector<ContactElement> zone_elements(const BeamCurves& curves, const ProximityZone& zone, int count,
                                          SectionPairing pairing, double self_separation) {
  const double step = 1.0 / (count - 1);
  std::vector<ContactElement> uniform;
  std::size_t smallest = 0;
  for (int i = 0; i < count; ++i) {
    ContactElement e;
    if (!make_element(curves, zone, static_cast<double>(i) / (count - 1), pairing, self_separation, e))
      continue;
    if (!uniform.empty() && e.gap < uniform[smallest].gap) smallest = uniform.size();
    uniform.push_back(e);
  }
  const std::size_t k = smallest;
  if (k == 0 || k + 1 >= uniform.size()) return uniform;
  const double tol = 1e-9 * step;
  if (std::abs(uniform[k].zeta - uniform[k - 1].zeta - step) > tol ||
      std::abs(uniform[k + 1].zeta - uniform[k].zeta - step) > tol)
    return uniform;  // a neighbour is missing
  const double g0 = uniform[k - 1].gap, g1 = uniform[k].gap, g2 = uniform[k + 1].gap;
  const double curvature = g0 - 2.0 * g1 + g2;
  if (!(curvature > 0.0)) return uniform;
  const double gain = 0.125 * (g0 - g2) * (g0 - g2) / curvature;
  if (!(gain > 1e-4 * 0.5 * (curves.radius(zone.beam_i) + curves.radius(zone.beam_j)))) return uniform;
  const double shift = 0.5 * (g0 - g2) / curvature;                       // in units of step, in [-1/2, 1/2]
  const double anchor = std::fmod(uniform[k].zeta + shift * step, step);  // in [0, step)
  std::vector<ContactElement> shifted;
  for (int i = 0; anchor + i * step <= 1.0 + 1e-12; ++i) {
    ContactElement e;
    if (make_element(curves, zone, std::min(1.0, anchor + i * step), pairing, self_separation, e))
      shifted.push_back(e);
  }
  return shifted;
}

bool contact_element_at(const model::Model& model, const Eigen::VectorXd& x, const ProximityZone& zone,
                        double zeta, ContactElement& out, SectionPairing pairing, double self_separation) {
  return make_element(BeamCurves(model, x), zone, zeta, pairing, self_separation, out);
}

bool update_normal(const model::Model& model, const Eigen::VectorXd& x, ContactElement& e, bool facing,
                   bool along_centres) {
  const BeamCurves curves(model, x);
  const SectionGeometry gi = curves.at_element(e.particle_i.element, e.particle_i.local);
  const SectionGeometry gj = curves.at_element(e.particle_j.element, e.particle_j.local);
  Eigen::Vector3d d;
  if (!section_normal(gi, gj, curves.length(e.particle_i.beam), d, e.normal, e.parallel_weight)) return false;
  if (facing) {
    const Eigen::Vector3d direction = along_centres ? d : e.normal;
    facing_point(gi.g1, gi.g2, direction, curves.radius(e.particle_i.beam), e.particle_i.transverse);
    facing_point(gj.g1, gj.g2, -direction, curves.radius(e.particle_j.beam), e.particle_j.transverse);
  }
  const Eigen::Vector2d& a = e.particle_i.transverse;
  const Eigen::Vector2d& b = e.particle_j.transverse;
  e.position_i = gi.r + a.x() * gi.g1 + a.y() * gi.g2;
  e.position_j = gj.r + b.x() * gj.g1 + b.y() * gj.g2;
  e.gap = (e.position_j - e.position_i).dot(e.normal);
  return true;
}

double centre_overlap(const model::Model& model, const Eigen::VectorXd& x, const ContactElement& e) {
  const BeamCurves curves(model, x);
  const SectionGeometry gi = curves.at_element(e.particle_i.element, e.particle_i.local);
  const SectionGeometry gj = curves.at_element(e.particle_j.element, e.particle_j.local);
  const Eigen::Vector3d centres = gj.r - gi.r;
  const double distance = centres.norm();
  if (!(distance > 0.0)) return curves.radius(e.particle_i.beam) + curves.radius(e.particle_j.beam);
  const Eigen::Vector3d d = centres / distance;
  return section_reach(gi, d, curves.radius(e.particle_i.beam)) +
         section_reach(gj, d, curves.radius(e.particle_j.beam)) - distance;
}

}  // namespace nodus::contact
