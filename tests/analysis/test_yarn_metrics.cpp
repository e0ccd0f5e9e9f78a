// The yarn checks against closed forms: the gap between parallel and crossing axes, and the helix through
// nodes placed on one.
#include <cmath>

#include <gtest/gtest.h>

#include "nodus/analysis/yarn_metrics.hpp"

namespace nodus::analysis {
namespace {

using Vec3 = Eigen::Vector3d;

beam::BeamDefinition straight(const std::string& name, const Vec3& start, const Vec3& direction,
                              double radius) {
  beam::BeamDefinition d;
  d.name = name;
  d.length = 2.0;
  d.radius = radius;
  d.elements = 4;
  d.start = start;
  d.direction = direction;
  d.director1 = direction.unitOrthogonal();
  d.material = {4000.0, 0.3};
  return d;
}

TEST(YarnMetrics, GapBetweenParallelAndCrossingAxes) {
  model::Model m;
  m.add_beam(straight("a", Vec3(0, 0, 0), Vec3::UnitX(), 0.05));
  m.add_beam(straight("b", Vec3(0, 0.13, 0), Vec3::UnitX(), 0.06));
  // c crosses a above it, at a's arc length 1.0 (a node), 0.2 above its axis.
  m.add_beam(straight("c", Vec3(1.0, -1.0, 0.2), Vec3::UnitY(), 0.04));
  const AxisGap g = smallest_axis_gap(m, m.reference());
  EXPECT_NEAR(g.gap, 0.13 - 0.11, 1e-14);
  EXPECT_EQ(g.beam_i, 0);
  EXPECT_EQ(g.beam_j, 1);
  // Without b: a and c, 0.2 - 0.09 apart where they cross.
  model::Model two;
  two.add_beam(straight("a", Vec3(0, 0, 0), Vec3::UnitX(), 0.05));
  two.add_beam(straight("c", Vec3(1.0, -1.0, 0.2), Vec3::UnitY(), 0.04));
  const AxisGap crossing = smallest_axis_gap(two, two.reference());
  EXPECT_NEAR(crossing.gap, 0.2 - 0.09, 1e-14);
  EXPECT_NEAR(crossing.s_i, 1.0, 1e-14);
  EXPECT_NEAR(crossing.s_j, 1.0, 1e-14);
}

TEST(YarnMetrics, HelixThroughItsNodes) {
  model::Model m;
  m.add_beam(straight("h", Vec3::Zero(), Vec3::UnitZ(), 0.05));
  const double radius = 0.07, rate = 2.5;  // rad/mm
  Eigen::VectorXd x = m.reference();
  for (int n = 0; n < m.num_nodes(); ++n) {
    const double z = 0.5 * n * 0.5;  // nodes every h/2 = 0.25 mm
    x.segment<3>(m.node_dof(n)) = Vec3(radius * std::cos(rate * z), radius * std::sin(rate * z), z);
  }
  const HelixFit fit = fit_helix(m, x, 0, Vec3::Zero(), Vec3::UnitZ(), 0.5, 1.5);
  EXPECT_EQ(fit.nodes, 5);
  EXPECT_NEAR(fit.radius, radius, 1e-15);
  EXPECT_LT(fit.radius_spread, 1e-15);
  EXPECT_NEAR(fit.rate, rate, 1e-12);
}

}  // namespace
}  // namespace nodus::analysis
