#include "nodus/contact/detection_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace nodus::contact {

DetectionParameters resolve_parameters(const DetectionParameters& given, const model::Model& model,
                                       const std::vector<int>& beams) {
  double radius = 0.0;
  for (int b = 0; b < static_cast<int>(model.beams().size()); ++b)
    if (beams.empty() || std::find(beams.begin(), beams.end(), b) != beams.end())
      radius = std::max(radius, model.beam(b).radius());
  return resolve_parameters(given, radius);
}

DetectionParameters resolve_parameters(const DetectionParameters& given, double radius) {
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

}  // namespace nodus::contact
