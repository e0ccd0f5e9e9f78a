#include "nodus/contact/history_transfer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

namespace nodus::contact {
namespace {

/// Reversible displacements stored at the particles' abscissas on each beam, per pair of beams and side
/// (Sect. 5.2.3): key (beam_i, beam_j, side), values sorted by abscissa.
using HistoryKey = std::tuple<int, int, int>;
struct Stored {
  double abscissa = 0.0;  ///< on the key's side
  int zone = 0;           ///< the old element's zone
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
};
using History = std::map<HistoryKey, std::vector<Stored>>;

/// Linear interpolation at s between the nearest stored neighbours on either side that are not in a zone of
/// `excluded`; nothing outside their range.
std::optional<Eigen::Vector3d> interpolate(const std::vector<Stored>& points, double s,
                                           const std::vector<int>& excluded) {
  const auto kept = [&](const Stored& p) {
    return std::find(excluded.begin(), excluded.end(), p.zone) == excluded.end();
  };
  const auto split = std::lower_bound(points.begin(), points.end(), s,
                                      [](const Stored& p, double v) { return p.abscissa < v; });
  const auto upper = std::find_if(split, points.end(), kept);
  if (upper == points.end()) return std::nullopt;
  if (upper->abscissa == s) return upper->value;
  const auto lower = std::find_if(std::make_reverse_iterator(split), points.rend(), kept);
  if (lower == points.rend()) return std::nullopt;
  const double span = upper->abscissa - lower->abscissa;
  if (!(span > 0.0)) return lower->value;
  const double w = (s - lower->abscissa) / span;
  return (1.0 - w) * lower->value + w * upper->value;
}

/// The distance in the plane of abscissas from `p` to the polyline of `points` [mm].
double distance_to(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p) {
  if (points.size() == 1) return (p - points.front()).norm();
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    d = std::min(d, segment_distance(p, points[k], points[k + 1]));
  return d;
}

double overlap(double a0, double a1, double b0, double b1) {
  return std::max(
      0.0, std::min(std::max(a0, a1), std::max(b0, b1)) - std::max(std::min(a0, a1), std::min(b0, b1)));
}

}  // namespace

std::vector<double> transfer_penalties(const ContactGeometry& old, const std::vector<double>& old_penalty,
                                       const ContactGeometry& next, double default_penalty, double reach) {
  // Penalty of a new zone: that of the old zone of the same pair of beams that overlaps it most, among those
  // whose pairing passes near the new zone's centre.
  std::vector<double> penalty(next.zones.size(), default_penalty);
  for (std::size_t z = 0; z < next.zones.size(); ++z) {
    const ProximityZone& n = next.zones[z];
    const double tolerance = reach + 0.5 * std::max(n.b - n.a, std::abs(n.d - n.c));
    double best = 0.0;
    for (std::size_t o = 0; o < old.zones.size(); ++o) {
      const ProximityZone& p = old.zones[o];
      if (p.beam_i != n.beam_i || p.beam_j != n.beam_j ||
          pairing_distance(p, 0.5 * (n.a + n.b), 0.5 * (n.c + n.d)) > tolerance)
        continue;
      const double common = overlap(n.a, n.b, p.a, p.b) * overlap(n.c, n.d, p.c, p.d);
      if (common > best) {
        best = common;
        penalty[z] = old_penalty[o];
      }
    }
  }
  return penalty;
}

std::vector<Eigen::Vector3d> transfer_reversible(const ContactGeometry& old,
                                                 const std::vector<Eigen::Vector3d>& old_reversible,
                                                 const ContactGeometry& next, double reach) {
  // History: committed g_rev stored on both particles' abscissas; a new element takes the mean of the values
  // interpolated at its two particles. An old zone whose elements straddle the new element's abscissa on one
  // side but pair it with parts of the other beam farther than `reach` from the new element's particle (a
  // crossing within another pairing of the same beams, as two fibres of a yarn side by side and crossed in
  // its knot) is left out of that side's interpolation.
  History history;
  std::vector<std::vector<Eigen::Vector2d>> pairing(old.zones.size());
  std::vector<std::array<double, 4>> range(
      old.zones.size(), {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()});
  for (std::size_t k = 0; k < old.elements.size(); ++k) {
    const ContactElement& e = old.elements[k];
    const ProximityZone& z = old.zones[static_cast<std::size_t>(e.zone)];
    const double s_i = e.particle_i.abscissa, s_j = e.particle_j.abscissa;
    history[{z.beam_i, z.beam_j, 0}].push_back({s_i, e.zone, old_reversible[k]});
    history[{z.beam_i, z.beam_j, 1}].push_back({s_j, e.zone, old_reversible[k]});
    pairing[static_cast<std::size_t>(e.zone)].emplace_back(s_i, s_j);
    auto& r = range[static_cast<std::size_t>(e.zone)];
    r = {std::min(r[0], s_i), std::max(r[1], s_i), std::min(r[2], s_j), std::max(r[3], s_j)};
  }
  std::map<std::pair<int, int>, std::vector<int>> zones_of_pair;  // old zones of each pair of beams
  for (std::size_t o = 0; o < old.zones.size(); ++o)
    zones_of_pair[{old.zones[o].beam_i, old.zones[o].beam_j}].push_back(static_cast<int>(o));
  for (auto& [key, points] : history)
    std::stable_sort(points.begin(), points.end(),
                     [](const Stored& x, const Stored& y) { return x.abscissa < y.abscissa; });
  std::vector<Eigen::Vector3d> reversible(next.elements.size(), Eigen::Vector3d::Zero());
  std::vector<int> excluded;
  for (std::size_t k = 0; k < next.elements.size(); ++k) {
    const ContactElement& e = next.elements[k];
    const ProximityZone& z = next.zones[static_cast<std::size_t>(e.zone)];
    const Eigen::Vector2d at(e.particle_i.abscissa, e.particle_j.abscissa);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (int side = 0; side < 2; ++side) {
      const auto it = history.find({z.beam_i, z.beam_j, side});
      if (it == history.end()) continue;
      excluded.clear();
      for (int o : zones_of_pair[{z.beam_i, z.beam_j}]) {
        const auto& r = range[static_cast<std::size_t>(o)];
        if (r[2 * side] < at[side] && at[side] < r[2 * side + 1] &&
            distance_to(pairing[static_cast<std::size_t>(o)], at) > reach)
          excluded.push_back(o);
      }
      if (const auto value = interpolate(it->second, at[side], excluded)) {
        sum += *value;
        ++count;
      }
    }
    if (count > 0) reversible[k] = sum / count;
  }
  return reversible;
}

}  // namespace nodus::contact
