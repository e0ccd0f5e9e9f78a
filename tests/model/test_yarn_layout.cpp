// The laid yarn's cross-section (model/yarn_layout.hpp) against its defining geometry: fibres of a roving
// touching their neighbours at exactly d = 2 R + c and never closer, the closest fibres of different rovings
// exactly d apart, three fibres an equilateral triangle, seven a hexagon around one, and the layout unchanged
// by the turn 2 pi / m that takes each roving to the next. References are closed forms of circle packings.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "nodus/model/yarn_layout.hpp"

namespace nodus::model {
namespace {

constexpr double kSpacing = 2.0 * 0.0188 + 0.01 * 0.0188;  // d = 2 R + c of the 3x9 yarn, c = 0.01 R [mm]
constexpr double kTol = 1e-12 * kSpacing;  // round-off of a few operations on lengths of order d

double min_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b, bool same) {
  double out = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = same ? i + 1 : 0; j < b.size(); ++j) out = std::min(out, (a[i] - b[j]).norm());
  }
  return out;
}

/// Whether the graph of pairs exactly d apart joins all points.
bool touching_graph_connected(const std::vector<Vec2>& points, double d) {
  std::vector<bool> seen(points.size(), false);
  std::vector<std::size_t> stack{0};
  seen[0] = true;
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (!seen[j] && std::abs((points[i] - points[j]).norm() - d) <= kTol) {
        seen[j] = true;
        stack.push_back(j);
      }
    }
  }
  for (bool s : seen)
    if (!s) return false;
  return true;
}

TEST(YarnLayout, RovingNeighboursExactlyOneSpacingApartAndNoneCloser) {
  for (RovingPacking packing : {RovingPacking::hexagonal, RovingPacking::ring}) {
    for (int n = 1; n <= (packing == RovingPacking::hexagonal ? 40 : 12); ++n) {
      const std::vector<Vec2> p = roving_pattern(packing, n, kSpacing);
      ASSERT_EQ(static_cast<int>(p.size()), n);
      Vec2 mean = Vec2::Zero();
      for (const Vec2& x : p) mean += x;
      EXPECT_LE((mean / n).norm(), kTol) << n;  // centroid at the roving centre
      if (n == 1) continue;
      EXPECT_NEAR(min_distance(p, p, true), kSpacing, kTol) << n;  // neighbours at d, no pair closer
      EXPECT_GE(min_distance(p, p, true), kSpacing - kTol) << n;
      // Every fibre touches a neighbour, and the touching fibres form one bundle.
      for (std::size_t i = 0; i < p.size(); ++i) {
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < p.size(); ++j)
          if (j != i) nearest = std::min(nearest, (p[i] - p[j]).norm());
        EXPECT_NEAR(nearest, kSpacing, kTol) << n << " fibre " << i;
      }
      EXPECT_TRUE(touching_graph_connected(p, kSpacing)) << n;
    }
  }
}

TEST(YarnLayout, SmallRovingsAreTheCompactShapes) {
  // One fibre at the centre.
  const std::vector<Vec2> one = roving_pattern(RovingPacking::hexagonal, 1, kSpacing);
  EXPECT_LE(one[0].norm(), kTol);
  // Three: an equilateral triangle of side d, its vertices d / sqrt(3) from the centroid.
  const std::vector<Vec2> three = roving_pattern(RovingPacking::hexagonal, 3, kSpacing);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR((three[i] - three[(i + 1) % 3]).norm(), kSpacing, kTol);
    EXPECT_NEAR(three[i].norm(), kSpacing / std::sqrt(3.0), kTol);
  }
  // Seven: a hexagon of side d around a fibre at the centre.
  const std::vector<Vec2> seven = roving_pattern(RovingPacking::hexagonal, 7, kSpacing);
  int centre = 0, ring = 0;
  for (const Vec2& x : seven) {
    if (x.norm() <= kTol) ++centre;
    if (std::abs(x.norm() - kSpacing) <= kTol) ++ring;
  }
  EXPECT_EQ(centre, 1);
  EXPECT_EQ(ring, 6);
  // A ring of n: all on the circle of radius d / (2 sin(pi / n)).
  for (const Vec2& x : roving_pattern(RovingPacking::ring, 5, kSpacing))
    EXPECT_NEAR(x.norm(), kSpacing / (2.0 * std::sin(std::numbers::pi / 5)), kTol);
}

TEST(YarnLayout, RovingsTouchAtExactlyOneSpacingAndAreTurnedCopies) {
  struct Case {
    RovingPacking packing;
    int m, n;
  };
  for (const Case& c : {Case{RovingPacking::hexagonal, 3, 1}, Case{RovingPacking::hexagonal, 3, 9},
                        Case{RovingPacking::hexagonal, 3, 25}, Case{RovingPacking::hexagonal, 2, 4},
                        Case{RovingPacking::hexagonal, 4, 7}, Case{RovingPacking::hexagonal, 6, 3},
                        Case{RovingPacking::ring, 3, 6}, Case{RovingPacking::hexagonal, 1, 9}}) {
    const YarnLayout layout = yarn_layout(c.packing, c.m, c.n, kSpacing);
    const auto& f = layout.fibres;
    ASSERT_EQ(static_cast<int>(f.size()), c.m);
    double between = std::numeric_limits<double>::infinity();
    for (int k = 0; k < c.m; ++k) {
      ASSERT_EQ(static_cast<int>(f[k].size()), c.n);
      if (c.n > 1) {
        EXPECT_GE(min_distance(f[k], f[k], true), kSpacing - kTol);
      }
      for (int l = k + 1; l < c.m; ++l) between = std::min(between, min_distance(f[k], f[l], false));
    }
    if (c.m == 1) {
      EXPECT_EQ(layout.roving_distance, 0.0);
    } else {
      EXPECT_NEAR(between, kSpacing, kTol) << c.m << "x" << c.n;  // touching, none closer
    }
    // The turn by 2 pi / m about the axis takes fibre j of roving k onto fibre j of roving k + 1.
    const double a = 2.0 * std::numbers::pi / c.m;
    for (int k = 0; k < c.m; ++k) {
      for (int j = 0; j < c.n; ++j) {
        const Vec2& x = f[k][j];
        const Vec2 turned(std::cos(a) * x.x() - std::sin(a) * x.y(),
                          std::sin(a) * x.x() + std::cos(a) * x.y());
        EXPECT_LE((turned - f[(k + 1) % c.m][j]).norm(), kTol) << c.m << "x" << c.n << " r" << k << " f" << j;
      }
    }
  }
}

TEST(YarnLayout, ThreeSingleFibresFormATriangle) {
  // 3x1: three touching circles, centres on a circle of radius d / sqrt(3).
  const YarnLayout layout = yarn_layout(RovingPacking::hexagonal, 3, 1, kSpacing);
  EXPECT_NEAR(layout.roving_distance, kSpacing / std::sqrt(3.0), kTol);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR((layout.fibres[k][0] - layout.fibres[(k + 1) % 3][0]).norm(), kSpacing, kTol);
}

TEST(YarnLayout, RefusesBadArguments) {
  EXPECT_THROW(roving_pattern(RovingPacking::hexagonal, 0, kSpacing), std::invalid_argument);
  EXPECT_THROW(roving_pattern(RovingPacking::hexagonal, 3, 0.0), std::invalid_argument);
  EXPECT_THROW(yarn_layout(RovingPacking::hexagonal, 0, 3, kSpacing), std::invalid_argument);
}

}  // namespace
}  // namespace nodus::model
