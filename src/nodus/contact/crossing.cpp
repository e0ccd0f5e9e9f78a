#include "nodus/contact/crossing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include <Eigen/Geometry>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"

namespace nodus::contact {
namespace {

/// Closest points of segments p0 + u (p1 - p0) and q0 + v (q1 - q0), u, v in [0, 1].
struct SegmentDistance {
  double u = 0.0, v = 0.0, distance = 0.0;
};

SegmentDistance segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                 const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double tiny = 1e-300;
  double u = 0.0, v = 0.0;
  if (a <= tiny && e <= tiny) {
    // two points
  } else if (a <= tiny) {
    v = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= tiny) {
      u = std::clamp(-c / a, 0.0, 1.0);
    } else {
      // Minimise |r + u d1 - v d2|^2 over the square: the lines' closest points, clamped to u in [0, 1]; v
      // then follows u, and if v leaves [0, 1], u is the closest point to that end of q.
      const double b = d1.dot(d2), denominator = a * e - b * b;
      u = denominator > 1e-14 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      v = (b * u + f) / e;
      if (v < 0.0) {
        v = 0.0;
        u = std::clamp(-c / a, 0.0, 1.0);
      } else if (v > 1.0) {
        v = 1.0;
        u = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {u, v, ((p0 + u * d1) - (q0 + v * d2)).norm()};
}

/// The roots in (0, 1] of c[0] + c[1] t + c[2] t^2 + c[3] t^3 at which it changes sign or vanishes,
/// ascending: bisection on the intervals between its critical points, on each of which it is monotone.
std::vector<double> cubic_roots(const std::array<double, 4>& c) {
  const auto f = [&](double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); };
  std::vector<double> breaks{0.0, 1.0};
  // Critical points: 3 c3 t^2 + 2 c2 t + c1 = 0.
  const double qa = 3.0 * c[3], qb = 2.0 * c[2], qc = c[1];
  const double scale = std::abs(qa) + std::abs(qb) + std::abs(qc);
  if (scale > 0.0) {
    if (std::abs(qa) <= 1e-14 * scale) {
      if (qb != 0.0) breaks.push_back(-qc / qb);
    } else {
      const double discriminant = qb * qb - 4.0 * qa * qc;
      if (discriminant >= 0.0) {
        // The root of larger magnitude first, the other from the product of the roots (no cancellation).
        const double q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
        breaks.push_back(q / qa);
        if (q != 0.0) breaks.push_back(qc / q);
      }
    }
  }
  std::erase_if(breaks, [](double t) { return !(t >= 0.0 && t <= 1.0); });
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> roots;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    double lo = breaks[k], hi = breaks[k + 1];
    double f_lo = f(lo);
    const double f_hi = f(hi);
    if (f_hi == 0.0) {
      if (hi > 0.0) roots.push_back(hi);
      continue;
    }
    if (!(f_lo * f_hi < 0.0)) continue;
    while (hi - lo > 1e-14) {
      const double mid = 0.5 * (lo + hi), f_mid = f(mid);
      if (f_mid == 0.0) {
        lo = hi = mid;
        break;
      }
      if ((f_mid < 0.0) == (f_lo < 0.0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    roots.push_back(0.5 * (lo + hi));
  }
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  return roots;
}

/// The segments meet at instant t if they are closer than this (round-off of the root and of the lengths).
/// find_crossing widens each segment's box by its part of it.
double meeting_tolerance(const Eigen::Matrix<double, 3, 4>& at) {
  return 1e-7 * ((at.col(1) - at.col(0)).norm() + (at.col(3) - at.col(2)).norm());
}

}  // namespace

std::optional<SegmentMeeting> segments_meet(const Eigen::Matrix<double, 3, 4>& start,
                                            const Eigen::Matrix<double, 3, 4>& end) {
  const Eigen::Matrix<double, 3, 4> motion = end - start;
  // det[p1 - p0, q1 - q0, q0 - p0] at instant t, each vector linear in t: A0 + t a, B0 + t b, C0 + t c.
  const Eigen::Vector3d A0 = start.col(1) - start.col(0), a = motion.col(1) - motion.col(0);
  const Eigen::Vector3d B0 = start.col(3) - start.col(2), b = motion.col(3) - motion.col(2);
  const Eigen::Vector3d C0 = start.col(2) - start.col(0), c = motion.col(2) - motion.col(0);
  const std::array<double, 4> coefficients{
      A0.dot(B0.cross(C0)),
      a.dot(B0.cross(C0)) + A0.dot(b.cross(C0)) + A0.dot(B0.cross(c)),
      a.dot(b.cross(C0)) + a.dot(B0.cross(c)) + A0.dot(b.cross(c)),
      a.dot(b.cross(c)),
  };
  const auto meet_at = [&](double t) -> std::optional<SegmentMeeting> {
    const Eigen::Matrix<double, 3, 4> at = start + t * motion;
    const SegmentDistance d = segment_distance(at.col(0), at.col(1), at.col(2), at.col(3));
    if (d.distance <= meeting_tolerance(at)) return SegmentMeeting{t, d.u, d.v};
    return std::nullopt;
  };
  for (double t : cubic_roots(coefficients))
    if (const auto m = meet_at(t)) return m;
  // Segments coplanar throughout (the cubic vanishes identically, as for beams in one plane) or parallel:
  // no instant stands out; they meet if they do at the end.
  return meet_at(1.0);
}

std::optional<Crossing> find_crossing(const model::Model& model, const Eigen::VectorXd& x0,
                                      const Eigen::VectorXd& x1, const std::vector<int>& beams,
                                      double separation, bool parallel) {
  std::vector<int> active = beams;
  if (active.empty()) {
    active.resize(model.beams().size());
    std::iota(active.begin(), active.end(), 0);
  }
  const BeamCurves before(model, x0), after(model, x1);
  // Two segments per element: nodes 0-1 and 1-2 of its axis.
  struct Segment {
    int beam = 0;
    double s0 = 0.0, s1 = 0.0;          ///< reference arc lengths of its ends
    Eigen::Matrix<double, 3, 2> start;  ///< its ends in x0
    Eigen::Matrix<double, 3, 2> end;    ///< in x1
  };
  std::vector<Segment> segments;
  std::vector<Box3> boxes;
  for (int b : active)
    for (int k = 0; k < model.beam(b).num_elements(); ++k) {
      const int e = before.first_element(b) + k;
      const Eigen::Matrix3d n0 = before.element_axis(e), n1 = after.element_axis(e);
      for (int half = 0; half < 2; ++half) {
        Segment g;
        g.beam = b;
        g.s0 = before.abscissa(e, half - 1.0);
        g.s1 = before.abscissa(e, half);
        g.start = n0.middleCols<2>(half);
        g.end = n1.middleCols<2>(half);
        Box3 box(g.start.col(0));
        box.extend(g.start.col(1));
        box.extend(g.end.col(0));
        box.extend(g.end.col(1));
        // Widened by the meeting tolerance: segments that end within it of each other meet, and their boxes
        // may be that far apart (a segment in the plane z = 0, another ending at z = 1e-13 above it).
        const double reach =
            1e-7 * std::max((g.start.col(1) - g.start.col(0)).norm(), (g.end.col(1) - g.end.col(0)).norm());
        box.min().array() -= reach;
        box.max().array() += reach;
        segments.push_back(g);
        boxes.push_back(box);
      }
    }
  std::vector<int> ids(segments.size());
  std::iota(ids.begin(), ids.end(), 0);
  const ElementTree tree(ids, boxes);

  const auto count = static_cast<std::ptrdiff_t>(segments.size());
  std::vector<std::optional<Crossing>> found(segments.size());
#pragma omp parallel for schedule(dynamic, 64) if (parallel)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const Segment& p = segments[static_cast<std::size_t>(i)];
    std::vector<int> candidates;
    tree.query(boxes[static_cast<std::size_t>(i)], candidates);
    std::sort(candidates.begin(), candidates.end());
    for (int j : candidates) {
      if (j <= i) continue;  // each pair once
      const Segment& q = segments[static_cast<std::size_t>(j)];
      // Along one beam, only parts more than `separation` apart (segments are listed along it).
      if (q.beam == p.beam && q.s0 - p.s1 < separation) continue;
      Eigen::Matrix<double, 3, 4> start, end;
      start << p.start, q.start;
      end << p.end, q.end;
      const std::optional<SegmentMeeting> m = segments_meet(start, end);
      if (!m) continue;
      std::optional<Crossing>& best = found[static_cast<std::size_t>(i)];
      if (!best || m->instant < best->instant)
        best = Crossing{m->instant, p.beam, q.beam, p.s0 + m->u * (p.s1 - p.s0), q.s0 + m->v * (q.s1 - q.s0)};
    }
  }
  std::optional<Crossing> first;
  for (const std::optional<Crossing>& c : found)
    if (c && (!first || c->instant < first->instant)) first = c;
  return first;
}

}  // namespace nodus::contact
