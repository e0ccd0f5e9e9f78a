#include "nodus/contact/proximity_zone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

namespace nodus::contact {
namespace {

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
  std::vector<std::pair<double, double>> pairs;  ///< the chain's (s on I, s on J): the zone's pairing
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
              evidence,
              {}};
    // Canonical order: beam_i < beam_j; for self-contact, [a, b] on the later part.
    const bool swap = beam > c.beam || (beam == c.beam && c.later);
    for (std::size_t k = 0; k < c.tests.size(); ++k)
      z.pairs.push_back(swap ? std::pair{c.match[k], c.tests[k]} : std::pair{c.tests[k], c.match[k]});
    if (swap) {
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

/// Whether two raw zones of one pair of beams pair the same parts: some matched pair of one lies within
/// `reach` of one of the other on both beams. Their boxes may overlap without it: two fibres of a yarn are
/// paired side by side all along it, and where the yarn's knot crosses itself one fibre's later part crosses
/// the other's earlier part, inside that box but far from its pairing.
bool same_pairing(const RawZone& x, const RawZone& y, double reach) {
  for (const auto& [s, u] : x.pairs)
    for (const auto& [t, v] : y.pairs)
      if (std::abs(s - t) <= reach && std::abs(u - v) <= reach) return true;
  return false;
}

/// Merges the raw zones of one pair of beams whose intervals overlap on both beams and which pair the same
/// parts (same_pairing within l_p); the result does not depend on which beam's test points found which zone.
/// Zones whose orientation is weakly decided take that of an overlapping zone of `previous` (may be null).
std::vector<ProximityZone> merge(std::vector<RawZone> raw, double matching_length,
                                 const std::vector<ProximityZone>* previous) {
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
      if (raw[k].a <= raw[i].b && raw[i].a <= raw[k].b && raw[k].lo <= raw[i].hi && raw[i].lo <= raw[k].hi &&
          same_pairing(raw[i], raw[k], matching_length))
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
    if (previous && evidence[k] < kWeakOrientation) {
      // The overlapping previous zone whose pairing passes nearest to this zone's centre.
      const ProximityZone& z = zones[k];
      double nearest = std::numeric_limits<double>::infinity();
      for (const ProximityZone& p : *previous)
        if (overlaps(z, p))
          if (const double d = pairing_distance(p, 0.5 * (z.a + z.b), 0.5 * (z.c + z.d)); d < nearest) {
            nearest = d;
            antiparallel = p.c > p.d;
          }
    }
    if (antiparallel) std::swap(zones[k].c, zones[k].d);
  }
  std::sort(zones.begin(), zones.end(), [](const ProximityZone& x, const ProximityZone& y) {
    return std::tie(x.beam_i, x.beam_j, x.a) < std::tie(y.beam_i, y.beam_j, y.a);
  });
  return zones;
}

}  // namespace

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d along = b - a;
  const double length2 = along.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(along) / length2, 0.0, 1.0) : 0.0;
  return (p - a - t * along).norm();
}

double pairing_distance(const ProximityZone& zone, double s_i, double s_j) {
  return segment_distance({s_i, s_j}, {zone.a, zone.c}, {zone.b, zone.d});
}

std::vector<ProximityZone> find_zones(const BeamCurves& curves, const ElementTree& tree,
                                      const std::vector<int>& beams, const DetectionParameters& prm,
                                      const std::vector<ProximityZone>* previous, bool parallel) {
  // Beam by beam in parallel; results are gathered in order, so they do not depend on the number of threads.
  const auto num_beams = static_cast<std::ptrdiff_t>(beams.size());
  std::vector<std::vector<RawZone>> found(beams.size());
#pragma omp parallel for schedule(dynamic) if (parallel)
  for (std::ptrdiff_t k = 0; k < num_beams; ++k)
    found[static_cast<std::size_t>(k)] =
        zones_from_beam(curves, tree, beams[static_cast<std::size_t>(k)], prm);
  std::vector<RawZone> raw;
  for (const std::vector<RawZone>& z : found) raw.insert(raw.end(), z.begin(), z.end());
  return merge(std::move(raw), prm.matching_length, previous);
}

}  // namespace nodus::contact
