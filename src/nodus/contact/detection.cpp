#include "nodus/contact/detection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"
#include "nodus/contact/contact_mechanics.hpp"

namespace nodus::contact {

namespace {

/// The normal is the cross product of the tangents (Eq. 42) above this crossing angle, the double cross
/// product (Eq. 44) below kParallelBelow, and a smooth blend of the two between (docs/contact.md).
const double kSinParallelBelow = std::sin(5.0 * std::numbers::pi / 180.0);
const double kSinCrossAbove = std::sin(15.0 * std::numbers::pi / 180.0);

/// A test point's closest point on one branch of a beam (Eq. 28-29).
struct Match {
  int beam = 0;        ///< beam of the closest point
  double s = 0.0;      ///< its abscissa [mm]
  bool later = false;  ///< self-contact: the closest point lies beyond the test point (s > s_n)
};

/// Successive test points of one beam matched to one branch of another (Eq. 30).
struct Chain {
  int beam = 0;
  bool later = false;
  int first = 0, last = 0;           ///< test point indices
  std::vector<double> tests, match;  ///< abscissas of the test points and of their matches
};

/// A zone before merging the ones found from both beams.
struct RawZone {
  int beam_i = 0, beam_j = 0;
  double a = 0.0, b = 0.0, lo = 0.0, hi = 0.0;  ///< [a, b] on I, [lo, hi] on J, lo <= hi
  bool antiparallel = false;
  double evidence = 1.0;  ///< |cos| of the angle between the axes when they decided the orientation, else 1
};

double clamp_to(double s, double length) {
  return std::clamp(s, 0.0, length);
}

/// The branches of the beams near `p`: runs of consecutive candidate elements of one beam, on each side of
/// the excluded neighbourhood for the test point's own beam; the closest point on each within delta_prox.
void closest_points(const BeamCurves& curves, int beam, double s_n, const Eigen::Vector3d& p,
                    std::vector<int>& candidates, const DetectionParameters& prm, std::vector<Match>& out) {
  std::sort(candidates.begin(), candidates.end());
  struct Best {
    double distance = 0.0, s = 0.0;
    bool at_clip = false, valid = false;
  };
  for (int side = 0; side < 3;
       ++side) {  // 0: other beams; 1: own beam, earlier part; 2: own beam, later part
    if (side > 0 && !prm.self_contact) break;
    Best best;
    int run_beam = -1, previous = -2;
    const auto flush = [&] {
      if (best.valid && !best.at_clip && best.distance <= prm.proximity_distance)
        out.push_back({run_beam, best.s, side == 2});
      best = Best{};
    };
    for (int e : candidates) {
      const int b = curves.element_beam(e);
      if ((side == 0) == (b == beam)) continue;
      double lo = -1.0, hi = 1.0;
      bool clip_lo = false, clip_hi = false;
      if (side > 0) {
        const double s0 = curves.abscissa(e, -1.0), s1 = curves.abscissa(e, 1.0), h = s1 - s0;
        if (side == 1) {
          const double limit = s_n - prm.separation_distance;
          if (s0 > limit) continue;
          if (s1 > limit) {
            hi = 2.0 * (limit - s0) / h - 1.0;
            clip_hi = true;
          }
        } else {
          const double limit = s_n + prm.separation_distance;
          if (s1 < limit) continue;
          if (s0 < limit) {
            lo = 2.0 * (limit - s0) / h - 1.0;
            clip_lo = true;
          }
        }
      }
      if (b != run_beam || e != previous + 1) {
        flush();
        run_beam = b;
      }
      previous = e;
      const ClosestPoint cp = curves.closest_point(e, p, lo, hi);
      if (!best.valid || cp.distance < best.distance)
        best = {cp.distance, curves.abscissa(e, cp.local),
                (clip_lo && cp.local <= lo) || (clip_hi && cp.local >= hi), true};
    }
    flush();
  }
}

/// The raw zones found from the test points of `beam` (Eq. 26-32).
std::vector<RawZone> zones_from_beam(const BeamCurves& curves, const ElementTree& tree, int beam,
                                     const DetectionParameters& prm) {
  const double length = curves.length(beam);
  const int n_tests = std::max(1, static_cast<int>(std::ceil(length / prm.test_point_spacing - 1e-9)));
  std::vector<Chain> open, done;
  std::vector<int> candidates;
  std::vector<Match> matches;
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(prm.proximity_distance);
  for (int n = 0; n <= n_tests; ++n) {
    const double s_n = length * n / n_tests;
    const Eigen::Vector3d p = curves.position(beam, s_n);
    candidates.clear();
    tree.query(Box3(p - reach, p + reach), candidates);
    matches.clear();
    closest_points(curves, beam, s_n, p, candidates, prm, matches);
    std::vector<bool> extended(open.size(), false);
    for (const Match& m : matches) {
      int best = -1;
      double best_jump = prm.matching_length;
      for (std::size_t k = 0; k < open.size(); ++k) {
        const Chain& c = open[k];
        if (extended[k] || c.beam != m.beam || c.later != m.later || c.last != n - 1) continue;
        const double jump = std::abs(m.s - c.match.back());
        if (jump <= best_jump) {
          best = static_cast<int>(k);
          best_jump = jump;
        }
      }
      if (best < 0) {
        open.push_back({m.beam, m.later, n, n, {}, {}});
        extended.push_back(true);
        best = static_cast<int>(open.size()) - 1;
      }
      Chain& c = open[static_cast<std::size_t>(best)];
      c.last = n;
      c.tests.push_back(s_n);
      c.match.push_back(m.s);
      extended[static_cast<std::size_t>(best)] = true;
    }
    for (std::size_t k = open.size(); k-- > 0;)
      if (open[k].last < n) {
        done.push_back(std::move(open[k]));
        open.erase(open.begin() + static_cast<std::ptrdiff_t>(k));
      }
  }
  for (Chain& c : open) done.push_back(std::move(c));

  std::vector<RawZone> zones;
  const double half = 0.5 * prm.matching_length;
  for (const Chain& c : done) {
    const double other_length = curves.length(c.beam);
    const double t0 = c.tests.front(), t1 = c.tests.back();
    const auto [lo_it, hi_it] = std::minmax_element(c.match.begin(), c.match.end());
    const double progression = c.match.back() - c.match.front();
    bool antiparallel;
    double evidence = 1.0;
    if (std::abs(progression) > 0.25 * (t1 - t0)) {
      antiparallel = progression < 0.0;
    } else {
      const std::size_t mid = c.tests.size() / 2;
      const Eigen::Vector3d t_i = curves.at(beam, c.tests[mid]).dr.normalized();
      const Eigen::Vector3d t_j = curves.at(c.beam, c.match[mid]).dr.normalized();
      antiparallel = t_i.dot(t_j) < 0.0;
      evidence = std::abs(t_i.dot(t_j));
    }
    RawZone z{beam,
              c.beam,
              clamp_to(t0 - half, length),
              clamp_to(t1 + half, length),
              clamp_to(*lo_it - half, other_length),
              clamp_to(*hi_it + half, other_length),
              antiparallel,
              evidence};
    // Canonical order: beam_i < beam_j; for self-contact, [a, b] on the later part.
    if (beam > c.beam || (beam == c.beam && c.later)) {
      std::swap(z.beam_i, z.beam_j);
      std::swap(z.a, z.lo);
      std::swap(z.b, z.hi);
    }
    zones.push_back(z);
  }
  return zones;
}

bool overlaps(const ProximityZone& x, const ProximityZone& y) {
  return x.beam_i == y.beam_i && x.beam_j == y.beam_j && x.a <= y.b && y.a <= x.b &&
         std::min(x.c, x.d) <= std::max(y.c, y.d) && std::min(y.c, y.d) <= std::max(x.c, x.d);
}

/// Below this |cos| of the angle between the axes (crossings steeper than 60 degrees) the orientation of a
/// zone is a matter of convention; a zone keeps the orientation of the previous zone it overlaps, so that a
/// crossing near 90 degrees does not flip its pairing from one detection to the next.
constexpr double kWeakOrientation = 0.5;

/// Merges the raw zones of one pair of beams whose intervals overlap on both beams; the result does not
/// depend on which beam's test points found which zone. Zones whose orientation is weakly decided take that
/// of an overlapping zone of `previous` (may be null).
std::vector<ProximityZone> merge(std::vector<RawZone> raw, const ContactGeometry* previous) {
  std::sort(raw.begin(), raw.end(), [](const RawZone& x, const RawZone& y) {
    return std::tie(x.beam_i, x.beam_j, x.a, x.b, x.lo, x.hi) <
           std::tie(y.beam_i, y.beam_j, y.a, y.b, y.lo, y.hi);
  });
  const std::size_t n = raw.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = i + 1; k < n && raw[k].beam_i == raw[i].beam_i && raw[k].beam_j == raw[i].beam_j;
         ++k)
      if (raw[k].a <= raw[i].b && raw[i].a <= raw[k].b && raw[k].lo <= raw[i].hi && raw[i].lo <= raw[k].hi)
        parent[find(k)] = find(i);

  std::vector<ProximityZone> zones;
  std::vector<double> orientation, evidence;
  std::vector<std::size_t> zone_of_root(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t root = find(i);
    const RawZone& z = raw[i];
    if (zone_of_root[root] == n) {
      zone_of_root[root] = zones.size();
      zones.push_back({z.beam_i, z.beam_j, z.a, z.b, z.lo, z.hi, 0, 0});
      orientation.push_back(0.0);
      evidence.push_back(0.0);
    }
    const std::size_t k = zone_of_root[root];
    ProximityZone& m = zones[k];
    m.a = std::min(m.a, z.a);
    m.b = std::max(m.b, z.b);
    m.c = std::min(m.c, z.lo);
    m.d = std::max(m.d, z.hi);
    orientation[k] += (z.antiparallel ? -1.0 : 1.0) * (z.b - z.a + z.hi - z.lo);
    evidence[k] = std::max(evidence[k], z.evidence);
  }
  for (std::size_t k = 0; k < zones.size(); ++k) {
    bool antiparallel = orientation[k] < 0.0;
    if (previous && evidence[k] < kWeakOrientation)
      for (const ProximityZone& p : previous->zones)
        if (overlaps(zones[k], p)) {
          antiparallel = p.c > p.d;
          break;
        }
    if (antiparallel) std::swap(zones[k].c, zones[k].d);
  }
  std::sort(zones.begin(), zones.end(), [](const ProximityZone& x, const ProximityZone& y) {
    return std::tie(x.beam_i, x.beam_j, x.a) < std::tie(y.beam_i, y.beam_j, y.a);
  });
  return zones;
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

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// The direction d between the section centres (Eq. 37) and the normal (Eq. 41-44), oriented from I towards
/// J, of the sections `gi` and `gj`; false if neither is defined (coincident centres of parallel axes).
bool section_normal(const SectionGeometry& gi, const SectionGeometry& gj, double length_scale,
                    Eigen::Vector3d& d, Eigen::Vector3d& normal, double& parallel_weight) {
  const Eigen::Vector3d centres = gj.r - gi.r;
  const Eigen::Vector3d t_i = gi.dr.normalized();
  Eigen::Vector3d t_j = gj.dr.normalized();
  if (t_i.dot(t_j) < 0.0) t_j = -t_j;  // antiparallel parts: compare like with like
  const Eigen::Vector3d cross = t_i.cross(t_j);
  const double sin_angle = cross.norm();
  if (centres.norm() > 1e-12 * length_scale) {
    d = centres.normalized();
  } else if (sin_angle > 0.0) {
    d = cross / sin_angle;  // the axes meet: the common normal is the only candidate
  } else {
    return false;
  }
  const double w = smoothstep((sin_angle - kSinParallelBelow) / (kSinCrossAbove - kSinParallelBelow));
  Eigen::Vector3d n_cross = Eigen::Vector3d::Zero();
  if (sin_angle > 0.0) n_cross = (cross.dot(d) < 0.0 ? -cross : cross) / sin_angle;
  const Eigen::Vector3d t_mean = (t_i + t_j).normalized();
  Eigen::Vector3d n_parallel = d - d.dot(t_mean) * t_mean;
  if (n_parallel.norm() > 0.0) n_parallel.normalize();
  normal = w * n_cross + (1.0 - w) * n_parallel;
  if (!(normal.norm() > 1e-12)) return false;
  normal.normalize();
  parallel_weight = 1.0 - w;
  return true;
}

/// The contact element at relative abscissa zeta of `zone` (Eq. 33-45); false if the plane normal to the
/// intermediate geometry misses one of the axes or the axes meet.
bool make_element(const BeamCurves& curves, const ProximityZone& zone, double zeta, ContactElement& out) {
  const int bi = zone.beam_i, bj = zone.beam_j;
  double s_i = zone.a + zeta * (zone.b - zone.a);
  double s_j = zone.c + zeta * (zone.d - zone.c);
  const SectionGeometry gi0 = curves.at(bi, s_i), gj0 = curves.at(bj, s_j);
  const Eigen::Vector3d x_int = 0.5 * (gi0.r + gj0.r);                                            // Eq. 33
  const Eigen::Vector3d t_int = 0.5 * ((zone.b - zone.a) * gi0.dr + (zone.d - zone.c) * gj0.dr);  // Eq. 34
  if (!(t_int.norm() > 0.0)) return false;
  if (!cut_axis(curves, bi, x_int, t_int, s_i) || !cut_axis(curves, bj, x_int, t_int, s_j)) return false;
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
std::vector<ContactElement> zone_elements(const BeamCurves& curves, const ProximityZone& zone, int count) {
  const double step = 1.0 / (count - 1);
  std::vector<ContactElement> uniform;
  std::size_t smallest = 0;
  for (int i = 0; i < count; ++i) {
    ContactElement e;
    if (!make_element(curves, zone, static_cast<double>(i) / (count - 1), e)) continue;
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
    if (make_element(curves, zone, std::min(1.0, anchor + i * step), e)) shifted.push_back(e);
  }
  return shifted;
}

}  // namespace

DetectionParameters resolve_parameters(const DetectionParameters& given, const model::Model& model,
                                       const std::vector<int>& beams) {
  double radius = 0.0;
  for (int b = 0; b < static_cast<int>(model.beams().size()); ++b)
    if (beams.empty() || std::find(beams.begin(), beams.end(), b) != beams.end())
      radius = std::max(radius, model.beam(b).radius());
  DetectionParameters p = given;
  if (p.proximity_distance <= 0.0) p.proximity_distance = 3.0 * radius;
  const double contact = 2.0 * radius;
  const double delta = p.proximity_distance;
  if (p.test_point_spacing <= 0.0)
    p.test_point_spacing = std::max(std::sqrt(std::max(delta * delta - contact * contact, 0.0)), 0.5 * delta);
  if (p.matching_length <= 0.0) p.matching_length = 2.0 * p.test_point_spacing;
  if (p.separation_distance <= 0.0) p.separation_distance = 4.0 * delta;
  if (p.matching_length < p.test_point_spacing)
    throw std::invalid_argument(fmt::format(
        "contact: matching_length {:.6g} mm is below test_point_spacing {:.6g} mm; successive matching "
        "intervals must "
        "overlap",
        p.matching_length, p.test_point_spacing));
  if (p.self_contact && p.separation_distance <= delta)
    throw std::invalid_argument(fmt::format(
        "contact: separation_distance {:.6g} mm is not above proximity_distance {:.6g} mm; neighbouring "
        "parts of a beam "
        "would be paired",
        p.separation_distance, delta));
  return p;
}

bool contact_element_at(const model::Model& model, const Eigen::VectorXd& x, const ProximityZone& zone,
                        double zeta, ContactElement& out) {
  return make_element(BeamCurves(model, x), zone, zeta, out);
}

bool update_normal(const model::Model& model, const Eigen::VectorXd& x, ContactElement& e, bool facing) {
  const BeamCurves curves(model, x);
  const SectionGeometry gi = curves.at_element(e.particle_i.element, e.particle_i.local);
  const SectionGeometry gj = curves.at_element(e.particle_j.element, e.particle_j.local);
  Eigen::Vector3d d;
  if (!section_normal(gi, gj, curves.length(e.particle_i.beam), d, e.normal, e.parallel_weight)) return false;
  if (facing) {
    facing_point(gi.g1, gi.g2, e.normal, curves.radius(e.particle_i.beam), e.particle_i.transverse);
    facing_point(gj.g1, gj.g2, -e.normal, curves.radius(e.particle_j.beam), e.particle_j.transverse);
  }
  const Eigen::Vector2d& a = e.particle_i.transverse;
  const Eigen::Vector2d& b = e.particle_j.transverse;
  e.position_i = gi.r + a.x() * gi.g1 + a.y() * gi.g2;
  e.position_j = gj.r + b.x() * gj.g1 + b.y() * gj.g2;
  e.gap = (e.position_j - e.position_i).dot(e.normal);
  return true;
}

/// Below this many beam elements detection runs on one thread: its parallel regions would last less than the
/// cost of waking the threads (on a busy machine, far more: the 64-element example spent 1 s instead of
/// 2.4 ms in detection while other processes held the cores).
constexpr std::size_t kParallelElements = 1000;

ContactGeometry detect(const model::Model& model, const Eigen::VectorXd& x,
                       const DetectionParameters& parameters, const std::vector<int>& beams,
                       const ContactGeometry* previous) {
  std::vector<int> active = beams;
  if (active.empty()) {
    active.resize(model.beams().size());
    std::iota(active.begin(), active.end(), 0);
  }
  std::sort(active.begin(), active.end());
  active.erase(std::unique(active.begin(), active.end()), active.end());
  const DetectionParameters prm = resolve_parameters(parameters, model, active);
  const BeamCurves curves(model, x);

  std::vector<int> elements;
  for (int b : active)
    for (int e = 0; e < model.beam(b).num_elements(); ++e) elements.push_back(curves.first_element(b) + e);
  const ElementTree tree(curves, elements);

  // Beam by beam and zone by zone in parallel; results are gathered in order, so they do not depend on the
  // number of threads.
  const auto num_active = static_cast<std::ptrdiff_t>(active.size());
  std::vector<std::vector<RawZone>> found(active.size());
#pragma omp parallel for schedule(dynamic) if (elements.size() >= kParallelElements)
  for (std::ptrdiff_t k = 0; k < num_active; ++k)
    found[static_cast<std::size_t>(k)] =
        zones_from_beam(curves, tree, active[static_cast<std::size_t>(k)], prm);
  std::vector<RawZone> raw;
  for (const std::vector<RawZone>& z : found) raw.insert(raw.end(), z.begin(), z.end());

  const std::vector<ProximityZone> zones = merge(std::move(raw), previous);
  const auto num_zones = static_cast<std::ptrdiff_t>(zones.size());
  std::vector<std::vector<ContactElement>> built(zones.size());
#pragma omp parallel for schedule(dynamic) if (elements.size() >= kParallelElements)
  for (std::ptrdiff_t k = 0; k < num_zones; ++k) {
    const ProximityZone& zone = zones[static_cast<std::size_t>(k)];
    const double spacing = prm.element_spacing > 0.0
                               ? prm.element_spacing
                               : 0.5 * std::min(model.beam(zone.beam_i).element_length(),
                                                model.beam(zone.beam_j).element_length());
    const int count = std::max(
        2, static_cast<int>(std::ceil(std::min(zone.b - zone.a, std::abs(zone.d - zone.c)) / spacing)));
    built[static_cast<std::size_t>(k)] = zone_elements(curves, zone, count);
  }

  ContactGeometry result;
  for (std::size_t k = 0; k < zones.size(); ++k) {
    if (built[k].empty()) continue;
    ProximityZone zone = zones[k];
    zone.first_element = static_cast<int>(result.elements.size());
    zone.num_elements = static_cast<int>(built[k].size());
    for (ContactElement& e : built[k]) {
      e.zone = static_cast<int>(result.zones.size());
      result.elements.push_back(e);
    }
    result.zones.push_back(zone);
  }
  return result;
}

}  // namespace nodus::contact
