// The pieces under the detection: closest points on a curved element against dense sampling, element boxes
// that contain their curves, and the BVH query against a brute-force scan.

#include <random>

#include <gtest/gtest.h>

#include "contact_test_support.hpp"
#include "nodus/contact/beam_curve.hpp"
#include "nodus/contact/broad_phase.hpp"

namespace nodus::contact {
namespace {

/// A model of `beams` beams of `elements` elements each with nodes at random positions in a 10 mm cube.
struct RandomAssembly {
  model::Model model;
  Eigen::VectorXd x;
  RandomAssembly(int beams, int elements, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> coordinate(0.0, 10.0), step(-0.4, 0.4);
    for (int b = 0; b < beams; ++b) model.add_beam(testing::beam_definition(4.0, 0.1, elements));
    x = model.reference();
    for (int b = 0; b < beams; ++b) {
      Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
      for (int i = 0; i < model.beam(b).num_nodes(); ++i) {
        p += Vec3(step(rng), step(rng), step(rng));
        x.segment<3>(beam::kNodeDofs * model.beam(b).node(i)) = p;
      }
    }
  }
};

TEST(BeamCurves, ClosestPointIsTheMinimumOverTheElement) {
  const RandomAssembly a(3, 20, 7);
  const BeamCurves curves(a.model, a.x);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(0.0, 10.0), bound(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int element = trial % a.model.num_elements();
    const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
    double lo = bound(rng), hi = bound(rng);
    if (lo > hi) std::swap(lo, hi);
    const ClosestPoint cp = curves.closest_point(element, p, lo, hi);
    ASSERT_GE(cp.local, lo);
    ASSERT_LE(cp.local, hi);
    EXPECT_NEAR(cp.distance, (curves.at_element(element, cp.local).r - p).norm(), 1e-12);
    // Dense sampling (4001 points) never finds a closer point than the computed one.
    double sampled = cp.distance;
    for (int k = 0; k <= 4000; ++k)
      sampled = std::min(sampled, (curves.at_element(element, lo + (hi - lo) * k / 4000.0).r - p).norm());
    EXPECT_GE(sampled, cp.distance - 1e-12);
  }
}

TEST(BeamCurves, AbscissaAndSectionsFollowTheMesh) {
  model::Model m;
  m.add_beam(testing::beam_definition(3.0, 0.1, 6));
  m.add_beam(testing::beam_definition(2.0, 0.1, 4));
  const BeamCurves curves(m, m.reference());
  EXPECT_EQ(curves.first_element(1), 6);
  EXPECT_EQ(curves.element_beam(7), 1);
  EXPECT_DOUBLE_EQ(curves.abscissa(7, 0.0), 0.75);  // second element of beam 1 (length 0.5), its middle
  const SectionGeometry g = curves.at(1, 0.75);
  EXPECT_EQ(g.element, 7);
  EXPECT_NEAR(g.local, 0.0, 1e-15);
  // Reference: straight along x from the origin, unit tangent, unit directors.
  EXPECT_NEAR((g.r - Vec3(0.75, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((g.dr - Vec3::UnitX()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(g.g1.norm(), 1.0, 1e-15);
  // Clamped to the beam.
  EXPECT_NEAR((curves.position(1, -1.0) - Vec3::Zero()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((curves.position(1, 9.0) - Vec3(2.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(BroadPhase, ElementBoxesContainTheirCurves) {
  const RandomAssembly a(4, 25, 3);
  const BeamCurves curves(a.model, a.x);
  for (int e = 0; e < a.model.num_elements(); ++e) {
    const Box3 box = element_box(curves, e);
    for (int k = 0; k <= 100; ++k) {
      const Vec3 r = curves.at_element(e, -1.0 + k / 50.0).r;
      EXPECT_TRUE(box.exteriorDistance(r) < 1e-12) << "element " << e;
    }
  }
}

TEST(BroadPhase, QueryFindsExactlyTheElementsWhoseBoxesMeet) {
  const RandomAssembly a(30, 40, 5);
  const BeamCurves curves(a.model, a.x);
  std::vector<int> all(static_cast<std::size_t>(a.model.num_elements()));
  for (std::size_t e = 0; e < all.size(); ++e) all[e] = static_cast<int>(e);
  const ElementTree tree(curves, all);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coordinate(-2.0, 12.0), size(0.0, 1.5);
  std::size_t total = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 c(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vec3 half = Vec3::Constant(size(rng));
    const Box3 query(c - half, c + half);
    std::vector<int> found;
    tree.query(query, found);
    std::sort(found.begin(), found.end());
    std::vector<int> expected;
    for (int e : all)
      if (element_box(curves, e).intersects(query)) expected.push_back(e);
    EXPECT_EQ(found, expected);
    total += expected.size();
  }
  EXPECT_GT(total, 500u);  // the queries do meet elements
}

}  // namespace
}  // namespace nodus::contact
