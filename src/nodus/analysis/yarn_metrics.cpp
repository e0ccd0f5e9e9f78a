#include "nodus/analysis/yarn_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "nodus/beam/shape_functions.hpp"

namespace nodus::analysis {
namespace {

using Vec3 = Eigen::Vector3d;

struct Sampled {
  std::vector<Vec3> points;
  std::vector<double> s;  ///< reference arc length of each point
  Vec3 low, high;         ///< bounding box of the points
};

Sampled sample(const model::Model& model, const Eigen::VectorXd& x, int b, int samples, double end_margin) {
  const beam::Beam& beam = model.beam(b);
  Sampled out;
  out.low = Vec3::Constant(std::numeric_limits<double>::infinity());
  out.high = -out.low;
  for (int e = 0; e < beam.num_elements(); ++e) {
    const Vec3 r0 = x.segment<3>(model.node_dof(beam.node(2 * e)));
    const Vec3 r1 = x.segment<3>(model.node_dof(beam.node(2 * e + 1)));
    const Vec3 r2 = x.segment<3>(model.node_dof(beam.node(2 * e + 2)));
    for (int k = 0; k <= samples; ++k) {
      if (k == samples && e + 1 < beam.num_elements()) break;  // the next element's first point
      const double xi = -1.0 + 2.0 * k / samples;
      const double s = beam.element_length() * (e + 0.5 * (xi + 1.0));
      if (s < end_margin || s > beam.length() - end_margin) continue;
      const beam::QuadraticShape n = beam::quadratic_shape(xi);
      const Vec3 p = n.value[0] * r0 + n.value[1] * r1 + n.value[2] * r2;
      out.points.push_back(p);
      out.s.push_back(s);
      out.low = out.low.cwiseMin(p);
      out.high = out.high.cwiseMax(p);
    }
  }
  return out;
}

}  // namespace

AxisGap smallest_axis_gap(const model::Model& model, const Eigen::VectorXd& x, int samples,
                          double end_margin) {
  AxisGap best;
  best.gap = std::numeric_limits<double>::infinity();
  const int beams = static_cast<int>(model.beams().size());
  std::vector<Sampled> sampled;
  for (int b = 0; b < beams; ++b) sampled.push_back(sample(model, x, b, std::max(samples, 1), end_margin));
  for (int i = 0; i < beams; ++i)
    for (int j = i + 1; j < beams; ++j) {
      const Sampled &a = sampled[static_cast<std::size_t>(i)], &b = sampled[static_cast<std::size_t>(j)];
      const double radii = model.beam(i).radius() + model.beam(j).radius();
      // The boxes' distance bounds the axes' from below: a pair that cannot beat the best so far is skipped.
      const Vec3 apart = (a.low - b.high).cwiseMax(b.low - a.high).cwiseMax(0.0);
      if (apart.norm() - radii >= best.gap) continue;
      for (std::size_t p = 0; p < a.points.size(); ++p)
        for (std::size_t q = 0; q < b.points.size(); ++q) {
          const double gap = (a.points[p] - b.points[q]).norm() - radii;
          if (gap < best.gap) best = {gap, i, j, a.s[p], b.s[q]};
        }
    }
  return best;
}

HelixFit fit_helix(const model::Model& model, const Eigen::VectorXd& x, int b, const Vec3& origin,
                   const Vec3& axis, double from, double to) {
  const beam::Beam& beam = model.beam(b);
  // A fixed frame normal to the axis for the angle.
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  HelixFit fit;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  std::vector<double> along, angle;
  double previous = 0.0;
  for (int n = 0; n < beam.num_nodes(); ++n) {
    const double s = beam.abscissa(n);
    if (s < from || s > to) continue;
    const Vec3 d = x.segment<3>(model.node_dof(beam.node(n))) - origin;
    const Vec3 radial = d - d.dot(axis) * axis;
    const double r = radial.norm();
    fit.radius += r;
    low = std::min(low, r);
    high = std::max(high, r);
    double a = std::atan2(radial.dot(e2), radial.dot(e1));
    if (!angle.empty()) a -= 2.0 * std::numbers::pi * std::round((a - previous) / (2.0 * std::numbers::pi));
    previous = a;
    along.push_back(d.dot(axis));
    angle.push_back(a);
  }
  fit.nodes = static_cast<int>(along.size());
  if (fit.nodes == 0) return fit;
  fit.radius /= fit.nodes;
  fit.radius_spread = high - low;
  if (fit.nodes >= 2) {
    const Eigen::Map<const Eigen::VectorXd> z(along.data(), fit.nodes), t(angle.data(), fit.nodes);
    const double zm = z.mean(), tm = t.mean();
    fit.rate = ((z.array() - zm) * (t.array() - tm)).sum() / (z.array() - zm).square().sum();
  }
  return fit;
}

double winding_about_centre(const model::Model& model, const Eigen::VectorXd& x, int b,
                            const std::vector<int>& beams, const Vec3& axis) {
  const beam::Beam& fibre = model.beam(b);
  for (int other : beams)
    if (model.beam(other).num_nodes() != fibre.num_nodes())
      throw std::invalid_argument("winding_about_centre: beams '" + fibre.name() + "' and '" +
                                  model.beam(other).name() + "' have different numbers of nodes");
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  double total = 0.0, previous = 0.0;
  for (int n = 0; n < fibre.num_nodes(); ++n) {
    Vec3 centre = Vec3::Zero();
    for (int other : beams) centre += x.segment<3>(model.node_dof(model.beam(other).node(n)));
    centre /= static_cast<double>(beams.size());
    const Vec3 offset = x.segment<3>(model.node_dof(fibre.node(n))) - centre;
    const double a = std::atan2(offset.dot(e2), offset.dot(e1));
    if (n > 0) total += std::remainder(a - previous, 2.0 * std::numbers::pi);  // the turn, in [-pi, pi]
    previous = a;
  }
  return total;
}

}  // namespace nodus::analysis
