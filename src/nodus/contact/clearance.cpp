#include "nodus/contact/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"

namespace nodus::contact {

Clearance min_clearance(const model::Model& model, const Eigen::VectorXd& x, const std::vector<int>& beams,
                        double separation, double reach, int samples, bool parallel) {
  std::vector<int> active = beams;
  if (active.empty()) {
    active.resize(model.beams().size());
    std::iota(active.begin(), active.end(), 0);
  }
  const BeamCurves curves(model, x);
  std::vector<int> elements;
  for (int b : active)
    for (int e = 0; e < model.beam(b).num_elements(); ++e) elements.push_back(curves.first_element(b) + e);
  const ElementTree tree(curves, elements);
  const Eigen::Vector3d box = Eigen::Vector3d::Constant(reach);
  const int n = std::max(samples, 2);

  const auto count = static_cast<std::ptrdiff_t>(elements.size());
  std::vector<Clearance> best(elements.size(), Clearance{std::numeric_limits<double>::infinity()});
#pragma omp parallel for schedule(dynamic, 16) if (parallel)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const int e = elements[static_cast<std::size_t>(k)];
    const int beam = curves.element_beam(e);
    Clearance& found = best[static_cast<std::size_t>(k)];
    std::vector<int> candidates;
    for (int i = 0; i < n; ++i) {
      const double local = -1.0 + 2.0 * i / (n - 1);
      const double s = curves.abscissa(e, local);
      const SectionGeometry section = curves.at_element(e, local);
      const Eigen::Vector3d& p = section.r;
      candidates.clear();
      tree.query(Box3(p - box, p + box), candidates);
      for (int f : candidates) {
        const int other = curves.element_beam(f);
        if (other < beam || (other == beam && f <= e)) continue;  // each pair of elements from one side
        double lo = -1.0, hi = 1.0;
        if (other == beam) {  // only the parts more than `separation` beyond s
          const double s0 = curves.abscissa(f, -1.0), s1 = curves.abscissa(f, 1.0);
          if (s1 < s + separation) continue;
          if (s0 < s + separation) lo = 2.0 * (s + separation - s0) / (s1 - s0) - 1.0;
        }
        const ClosestPoint cp = curves.closest_point(f, p, lo, hi);
        if (cp.distance > reach) continue;
        double value = -curves.radius(beam) - curves.radius(other);  // axes through each other
        if (cp.distance > 0.0) {
          const SectionGeometry facing = curves.at_element(f, cp.local);
          const Eigen::Vector3d d = (facing.r - p) / cp.distance;
          value = cp.distance - section_reach(section, d, curves.radius(beam)) -
                  section_reach(facing, d, curves.radius(other));
        }
        if (value < found.value) found = {value, beam, other, s, curves.abscissa(f, cp.local)};
      }
    }
  }
  Clearance result{std::numeric_limits<double>::infinity()};
  for (const Clearance& c : best)
    if (c.value < result.value) result = c;
  return result;
}

}  // namespace nodus::contact
