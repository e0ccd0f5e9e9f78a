#include "nodus/contact/detection.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"

namespace nodus::contact {
namespace {

/// Below this many beam elements detection runs on one thread: its parallel regions would last less than the
/// cost of waking the threads (on a busy machine, far more: the 64-element example spent 1 s instead of
/// 2.4 ms in detection while other processes held the cores).
constexpr std::size_t kParallelElements = 1000;

}  // namespace

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
  const bool parallel = elements.size() >= kParallelElements;
  const std::vector<ProximityZone> zones =
      find_zones(curves, tree, active, prm, previous ? &previous->zones : nullptr, parallel);
  const auto num_zones = static_cast<std::ptrdiff_t>(zones.size());
  std::vector<std::vector<ContactElement>> built(zones.size());
#pragma omp parallel for schedule(dynamic) if (parallel)
  for (std::ptrdiff_t k = 0; k < num_zones; ++k) {
    const ProximityZone& zone = zones[static_cast<std::size_t>(k)];
    const double spacing = prm.element_spacing > 0.0
                               ? prm.element_spacing
                               : 0.5 * std::min(model.beam(zone.beam_i).element_length(),
                                                model.beam(zone.beam_j).element_length());
    const int count = std::max(
        2, static_cast<int>(std::ceil(std::min(zone.b - zone.a, std::abs(zone.d - zone.c)) / spacing)));
    built[static_cast<std::size_t>(k)] =
        zone_elements(curves, zone, count, prm.pairing, prm.separation_distance - prm.matching_length);
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
