// The yarn checks against closed forms: the gap between parallel and crossing axes, and the helix through
// nodes placed on one.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

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

/// Three fibres on helices of `turns` turns about the x axis over their length (one a third of a turn
/// ahead of the next), or straight if turns = 0.
Eigen::VectorXd plied(const model::Model& m, double turns, const Vec3& shift = Vec3::Zero()) {
  Eigen::VectorXd x = m.reference();
  for (int b = 0; b < 3; ++b) {
    const beam::Beam& fibre = m.beam(b);
    for (int n = 0; n < fibre.num_nodes(); ++n) {
      const double s = fibre.abscissa(n);
      const double angle = 2.0 * std::numbers::pi * (turns * s / fibre.length() + b / 3.0);
      x.segment<3>(m.node_dof(fibre.node(n))) =
          shift + Vec3(s, 0.07 * std::cos(angle), 0.07 * std::sin(angle));
    }
  }
  return x;
}

TEST(YarnMetrics, WindingOfPliesAboutTheirCentre) {
  model::Model m;
  for (const char* name : {"a", "b", "c"}) {
    beam::BeamDefinition d = straight(name, Vec3::Zero(), Vec3::UnitX(), 0.05);
    d.length = 6.0;
    d.elements = 100;  // 201 nodes: 5 degrees a node at 2.86 turns
    m.add_beam(d);
  }
  const std::vector<int> all{0, 1, 2};
  // 1030 degrees, the 3x1 knot's twist, either way; and about -x, the opposite sense.
  for (double degrees : {1030.0, -1030.0, 0.0, 90.0}) {
    const Eigen::VectorXd x = plied(m, degrees / 360.0, Vec3(1.0, -2.0, 0.5));
    for (int b = 0; b < 3; ++b)
      EXPECT_NEAR(winding_about_centre(m, x, b, all, Vec3::UnitX()), degrees * std::numbers::pi / 180.0,
                  1e-12)
          << degrees << " degrees, fibre " << b;
    EXPECT_NEAR(winding_about_centre(m, x, 0, all, -Vec3::UnitX()), -degrees * std::numbers::pi / 180.0,
                1e-12);
  }
  // Fibres of different node counts have no centre node by node.
  model::Model uneven;
  uneven.add_beam(straight("a", Vec3::Zero(), Vec3::UnitX(), 0.05));
  beam::BeamDefinition coarse = straight("b", Vec3(0, 0.1, 0), Vec3::UnitX(), 0.05);
  coarse.elements = 3;
  uneven.add_beam(coarse);
  EXPECT_THROW(winding_about_centre(uneven, uneven.reference(), 0, {0, 1}, Vec3::UnitX()),
               std::invalid_argument);
}

}  // namespace
}  // namespace nodus::analysis
