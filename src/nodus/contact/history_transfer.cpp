#include "nodus/contact/history_transfer.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

namespace nodus::contact {
namespace {

/// Reversible displacements stored at the particles' abscissas on each beam, per pair of beams and side
/// (Sect. 5.2.3): key (beam_i, beam_j, side), values (abscissa, g_rev) sorted by abscissa.
using HistoryKey = std::tuple<int, int, int>;
using History = std::map<HistoryKey, std::vector<std::pair<double, Eigen::Vector3d>>>;

/// Linear interpolation between the stored neighbours of s; nothing outside the stored range.
std::optional<Eigen::Vector3d> interpolate(const std::vector<std::pair<double, Eigen::Vector3d>>& points,
                                           double s) {
  if (points.empty() || s < points.front().first || s > points.back().first) return std::nullopt;
  const auto upper =
      std::lower_bound(points.begin(), points.end(), s, [](const auto& p, double v) { return p.first < v; });
  if (upper == points.begin()) return upper->second;
  const auto lower = std::prev(upper);
  const double span = upper->first - lower->first;
  if (!(span > 0.0)) return lower->second;
  const double w = (s - lower->first) / span;
  return (1.0 - w) * lower->second + w * upper->second;
}

double overlap(double a0, double a1, double b0, double b1) {
  return std::max(
      0.0, std::min(std::max(a0, a1), std::max(b0, b1)) - std::max(std::min(a0, a1), std::min(b0, b1)));
}

}  // namespace

std::vector<double> transfer_penalties(const ContactGeometry& old, const std::vector<double>& old_penalty,
                                       const ContactGeometry& next, double default_penalty) {
  // Penalty of a new zone: that of the old zone of the same pair of beams that overlaps it most.
  std::vector<double> penalty(next.zones.size(), default_penalty);
  for (std::size_t z = 0; z < next.zones.size(); ++z) {
    const ProximityZone& n = next.zones[z];
    double best = 0.0;
    for (std::size_t o = 0; o < old.zones.size(); ++o) {
      const ProximityZone& p = old.zones[o];
      if (p.beam_i != n.beam_i || p.beam_j != n.beam_j) continue;
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
                                                 const ContactGeometry& next) {
  // History: committed g_rev stored on both particles' abscissas; a new element takes the mean of the values
  // interpolated at its two particles.
  History history;
  for (std::size_t k = 0; k < old.elements.size(); ++k) {
    const ContactElement& e = old.elements[k];
    const ProximityZone& z = old.zones[static_cast<std::size_t>(e.zone)];
    history[{z.beam_i, z.beam_j, 0}].emplace_back(e.particle_i.abscissa, old_reversible[k]);
    history[{z.beam_i, z.beam_j, 1}].emplace_back(e.particle_j.abscissa, old_reversible[k]);
  }
  for (auto& [key, points] : history)
    std::sort(points.begin(), points.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Eigen::Vector3d> reversible(next.elements.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < next.elements.size(); ++k) {
    const ContactElement& e = next.elements[k];
    const ProximityZone& z = next.zones[static_cast<std::size_t>(e.zone)];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (int side = 0; side < 2; ++side) {
      const auto it = history.find({z.beam_i, z.beam_j, side});
      if (it == history.end()) continue;
      const auto value = interpolate(it->second, side == 0 ? e.particle_i.abscissa : e.particle_j.abscissa);
      if (value) {
        sum += *value;
        ++count;
      }
    }
    if (count > 0) reversible[k] = sum / count;
  }
  return reversible;
}

}  // namespace nodus::contact
