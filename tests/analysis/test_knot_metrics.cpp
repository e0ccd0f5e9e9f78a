// Knot metrics (analysis/knot_metrics.hpp) against references the code did not produce: circles in a tilted
// plane (the fitted radius is the circle's, over a whole turn or a quarter of one), two straight tails at a
// known angle, midpoints on straight lines (the abscissa is the distance along them), zones with a known span
// in contact, the gaps of hand-placed intervals, a loop of known radius and length between two crossings,
// particles at a known distance from the axis; the contact table against the contact_final.csv text of the
// same geometry; and the whole analysis against tests/analysis/knot_metrics_reference.py (an independent
// numpy implementation: knot_report.py's before the metrics moved here) on the same numbers, when python3
// with numpy is there.

#include <gtest/gtest.h>

#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "nodus/analysis/knot_metrics.hpp"
#include "nodus/output/contact_table.hpp"

namespace nodus::analysis {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

/// A contact table of `n` elements: zone 0, beams 0 and 0, zeta k / n, particles at the origin, no gap, no
/// force, open.
ContactTable blank_table(int n) {
  ContactTable t;
  t.resize(static_cast<std::size_t>(n));
  t.zone.setZero();
  t.beam_i.setZero();
  t.beam_j.setZero();
  for (int k = 0; k < n; ++k) t.zeta[k] = static_cast<double>(k) / n;
  t.abscissa_i.setZero();
  t.abscissa_j.setZero();
  t.particle_i.setZero();
  t.particle_j.setZero();
  t.gap.setZero();
  t.normal_force.setZero();
  t.tangential_force.setZero();
  t.state.setZero();
  return t;
}

/// An orthonormal pair spanning a plane tilted against every coordinate plane.
std::pair<Vec3, Vec3> tilted_plane() {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  return {rotation.col(0), rotation.col(1)};
}

// ---------------------------------------------------------------------------------------------------------
// fit_circle

TEST(FitCircle, WholeCircleInATiltedPlaneGivesItsRadius) {
  const auto [e1, e2] = tilted_plane();
  const Vec3 centre(0.3, -2.0, 5.0);
  const double radius = 1.7;
  Points points(13, 3);
  for (int k = 0; k < 13; ++k) {
    const double theta = 0.1 + 2.0 * kPi * k / 13;
    points.row(k) = (centre + radius * (std::cos(theta) * e1 + std::sin(theta) * e2)).transpose();
  }
  EXPECT_NEAR(fit_circle(points), radius, 1e-12 * radius);
}

TEST(FitCircle, QuarterArcWithUnevenPointsGivesItsRadius) {
  const auto [e1, e2] = tilted_plane();
  const Vec3 centre(-40.0, 12.0, 7.5);
  const double radius = 0.35;
  const std::vector<double> fractions{0.0, 0.05, 0.2, 0.45, 0.5, 0.8, 1.0};  // of 90 degrees
  Points points(static_cast<Eigen::Index>(fractions.size()), 3);
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const double theta = 1.2 + 0.5 * kPi * fractions[k];
    points.row(static_cast<Eigen::Index>(k)) =
        (centre + radius * (std::cos(theta) * e1 + std::sin(theta) * e2)).transpose();
  }
  // A quarter arc 40 mm from the origin: the fit works on centred coordinates, and points on a circle
  // satisfy the Kasa equations exactly (zero residual), so the short arc loses nothing.
  EXPECT_NEAR(fit_circle(points), radius, 1e-12 * radius);
}

TEST(FitCircle, FewerThanThreePointsIsNaN) {
  Points two(2, 3);
  two << 0, 0, 0, 1, 0, 0;
  EXPECT_TRUE(std::isnan(fit_circle(two)));
}

// ---------------------------------------------------------------------------------------------------------
// centreline_at, tail_angle

/// Tail A runs straight into the knot along -u_a (c(s) = c_a + (4 - s) u_a for s <= 4), a bump of the knot
/// lies over s in (4, 6), tail B runs straight out of it along u_b (c(s) = c_b + (s - 6) u_b for s >= 6).
Centreline two_tails(const Vec3& u_a, const Vec3& u_b) {
  const Vec3 c_a(1.0, 2.0, 3.0), c_b(1.5, 2.2, 3.1);
  Centreline c;
  for (double s = 0.0; s <= 4.0; s += 0.5) {
    c.points.push_back(c_a + (4.0 - s) * u_a);
    c.arc_length.push_back(s);
  }
  for (double s : {4.5, 5.0, 5.5}) {
    c.points.push_back(Vec3(1.2, 2.5 + s, -3.0));  // the knot: anywhere
    c.arc_length.push_back(s);
  }
  for (double s = 6.0; s <= 10.0; s += 0.5) {
    c.points.push_back(c_b + (s - 6.0) * u_b);
    c.arc_length.push_back(s);
  }
  return c;
}

TEST(CentrelineAt, LinearBetweenNodesClampedAtTheEnds) {
  Centreline c;
  c.points = {Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(1, 2, 4)};
  c.arc_length = {1.0, 2.0, 4.0};
  Eigen::VectorXd s(5);
  s << 0.0, 1.25, 2.0, 3.5, 9.0;
  const Points p = centreline_at(c, s);
  EXPECT_EQ(p.row(0), Vec3(0, 0, 0).transpose());  // before the start: the first node
  EXPECT_NEAR((p.row(1) - Vec3(0.25, 0.5, 0).transpose()).norm(), 0.0, 1e-15);
  EXPECT_EQ(p.row(2), Vec3(1, 2, 0).transpose());  // on a node
  EXPECT_NEAR((p.row(3) - Vec3(1, 2, 3).transpose()).norm(), 0.0, 1e-15);
  EXPECT_EQ(p.row(4), Vec3(1, 2, 4).transpose());  // beyond the end: the last node
  Centreline one{{Vec3::Zero()}, {0.0}};
  EXPECT_THROW(centreline_at(one, s), std::invalid_argument);
}

TEST(TailAngle, StraightTailsGiveTheAngleBetweenThem) {
  const auto [e1, e2] = tilted_plane();
  const double alpha = 37.0;  // deg, between -u_a (into the knot, reversed: the chord of tail A) and u_b
  const double a = alpha * kPi / 180.0;
  const Vec3 u_a = e1, u_b = std::cos(a) * e1 + std::sin(a) * e2;
  const Centreline c = two_tails(u_a, u_b);
  EXPECT_NEAR(tail_angle(c, 4.0, 6.0), alpha, 1e-10);
  // Knot ends between nodes, and chords clamped at the rod ends (1 mm and 0.5 mm long): the same angle.
  EXPECT_NEAR(tail_angle(c, 3.75, 6.25), alpha, 1e-10);
  EXPECT_NEAR(tail_angle(c, 1.0, 9.5), alpha, 1e-10);
  EXPECT_NEAR(tail_angle(c, 4.0, 6.0, 0.3), alpha, 1e-10);
  // Tails pulled apart: 180 degrees. acos is steep at -1: a rounding error eps of the cosine moves the angle
  // by sqrt(2 eps) rad, 1e-6 deg for eps = 1e-16.
  EXPECT_NEAR(tail_angle(two_tails(u_a, -u_a), 4.0, 6.0), 180.0, 1e-6);
}

TEST(TailAngle, ChordOfZeroLengthIsNaN) {
  const Centreline c = two_tails(Vec3::UnitX(), Vec3::UnitY());
  EXPECT_TRUE(std::isnan(tail_angle(c, 0.0, 6.0)));   // s_a at the rod's start
  EXPECT_TRUE(std::isnan(tail_angle(c, 4.0, 10.0)));  // s_b at the rod's end
  EXPECT_TRUE(std::isnan(tail_angle(c, -1.0, 6.0)));  // before the start: clamped, no chord
}

// ---------------------------------------------------------------------------------------------------------
// midpoints, intermediate_abscissa, intermediate_length, element_spacing, knot_extent

/// Zone 0: midpoints at p0 + t d, t = 0, 1, 3; zone 1: at q0 + t e, t = 0, 2, 2.5; particles on either
/// side of each midpoint at an arbitrary offset. Forces: zone 0 (0, 0.5, 0.2), zone 1 (0.1, 0.3, 0).
ContactTable straight_zones() {
  ContactTable t = blank_table(6);
  const Vec3 p0(1, 1, 1), d = Vec3(1, -2, 2) / 3.0, q0(-4, 0, 2), e = Vec3(0, 0.6, 0.8);
  const std::vector<Vec3> mids{p0, p0 + d, p0 + 3 * d, q0, q0 + 2 * e, q0 + 2.5 * e};
  const std::vector<Vec3> offsets{Vec3(0.1, 0, 0),     Vec3(0, 0.2, 0.1), Vec3(-0.1, 0.05, 0.3),
                                  Vec3(0.2, 0.2, 0.2), Vec3(0, 0, -0.1),  Vec3(0.3, -0.1, 0)};
  const std::vector<double> normal{0.0, 0.5, 0.2, 0.1, 0.3, 0.0};
  for (int k = 0; k < 6; ++k) {
    t.zone[k] = k < 3 ? 0 : 1;
    t.particle_i.row(k) = (mids[k] + offsets[k]).transpose();
    t.particle_j.row(k) = (mids[k] - offsets[k]).transpose();
    t.normal_force[k] = normal[k];
    t.abscissa_i[k] = 10.0 + k;
    t.abscissa_j[k] = 30.0 - 2.0 * k;
  }
  return t;
}

TEST(IntermediateGeometry, MidpointsOnStraightLinesHaveTheirDistancesAsAbscissa) {
  const ContactTable t = straight_zones();
  const Points mid = midpoints(t);
  const Vec3 p0(1, 1, 1), d = Vec3(1, -2, 2) / 3.0;
  EXPECT_NEAR((mid.row(2) - (p0 + 3 * d).transpose()).norm(), 0.0, 1e-14);
  const Eigen::VectorXd a = intermediate_abscissa(t);
  // Zone 1 starts where zone 0 ends (3 mm), then 2 and 0.5 mm along e.
  const std::vector<double> expected{0.0, 1.0, 3.0, 3.0, 5.0, 5.5};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(a[k], expected[static_cast<std::size_t>(k)], 1e-14) << k;
  // In contact: zone 0 elements at 1 and 3 (span 2), zone 1 at 3 and 5 (span 2).
  EXPECT_NEAR(intermediate_length(t, a), 4.0, 1e-14);
}

TEST(IntermediateGeometry, ZoneWithOneOrNoElementInContactAddsNothing) {
  ContactTable t = straight_zones();
  t.normal_force << 0.0, 0.0, 0.0, 0.0, 0.7, 0.0;
  EXPECT_EQ(intermediate_length(t, intermediate_abscissa(t)), 0.0);
  t.normal_force << 0.0, 0.2, 0.0, 0.0, 0.7, 0.1;  // zone 0: one element; zone 1: from 5 to 5.5
  EXPECT_NEAR(intermediate_length(t, intermediate_abscissa(t)), 0.5, 1e-14);
}

TEST(ElementSpacing, MedianOfSuccessiveAbscissaDifferencesWithinZones) {
  ContactTable t = blank_table(7);
  t.zone << 0, 0, 0, 1, 1, 2, 2;
  t.abscissa_i << 0.0, 0.25, 0.5, 10.0, 9.0, 20.0, 20.5;  // differences 0.25, 0.25 | 1 | 0.5
  EXPECT_DOUBLE_EQ(element_spacing(t), 0.375);            // median of four: (0.25 + 0.5) / 2
  t.abscissa_i[6] = 19.0;                                 // differences 0.25, 0.25, 1, 1
  EXPECT_DOUBLE_EQ(element_spacing(t), 0.625);
  t.zone << 0, 0, 0, 1, 1, 2, 3;  // differences 0.25, 0.25, 1
  EXPECT_DOUBLE_EQ(element_spacing(t), 0.25);
  t.abscissa_i << 0.0, 0.01, 0.02, 10.0, 10.01, 20.0, 30.0;
  EXPECT_DOUBLE_EQ(element_spacing(t), 0.05);           // below MIN_SPACING
  EXPECT_NEAR(element_spacing(t, 0.001), 0.01, 1e-12);  // with a smaller minimum: the median itself
  t.zone << 0, 1, 2, 3, 4, 5, 6;                        // no two elements in a zone
  EXPECT_DOUBLE_EQ(element_spacing(t), 0.05);
  EXPECT_DOUBLE_EQ(element_spacing(blank_table(0)), 0.05);
}

TEST(KnotExtent, RangeOfTheAbscissasOfElementsInContact) {
  const ContactTable t = straight_zones();  // in contact: k = 1, 2, 3, 4
  const Interval extent = knot_extent(t);
  EXPECT_EQ(extent.lo, 11.0);  // abscissa_i of k = 1
  EXPECT_EQ(extent.hi, 28.0);  // abscissa_j of k = 1
  ContactTable none = straight_zones();
  none.normal_force.setZero();
  EXPECT_TRUE(std::isnan(knot_extent(none).lo));
  EXPECT_TRUE(std::isnan(knot_extent(none).hi));
}

// ---------------------------------------------------------------------------------------------------------
// longest_uncovered

void expect_interval(const std::optional<Interval>& got, double lo, double hi) {
  ASSERT_TRUE(got.has_value());
  EXPECT_DOUBLE_EQ(got->lo, lo);
  EXPECT_DOUBLE_EQ(got->hi, hi);
}

TEST(LongestUncovered, EdgeCases) {
  expect_interval(longest_uncovered({}, 0.5, 1.0, 5.0), 1.0, 5.0);  // no centres: all of it
  std::vector<double> all;
  for (int c = 0; c <= 10; ++c) all.push_back(c);
  EXPECT_FALSE(longest_uncovered(all, 0.5, 0.0, 10.0).has_value());  // covered, intervals touching
  std::vector<double> late, early;
  for (int c = 3; c <= 10; ++c) late.push_back(c);
  for (int c = 0; c <= 6; ++c) early.push_back(c);
  expect_interval(longest_uncovered(late, 0.5, 0.0, 10.0), 0.0, 2.5);    // gap at the start
  expect_interval(longest_uncovered(early, 0.5, 0.0, 10.0), 6.5, 10.0);  // gap at the end
  // Unsorted centres, gaps (1.5, 4.5) and (6.5, 9.1): the longer.
  expect_interval(longest_uncovered({10.0, 5.0, 0.0, 9.6, 6.0, 1.0}, 0.5, 0.0, 10.0), 1.5, 4.5);
  // Gaps (0, 2.5), (3.5, 4.5), (5.5, 8) of lengths 2.5, 1, 2.5: the first of the longest.
  expect_interval(longest_uncovered({5.0, 3.0}, 0.5, 0.0, 8.0), 0.0, 2.5);
  // A centre beyond hi: the gap before it is cut at hi.
  expect_interval(longest_uncovered({5.0}, 0.5, 0.0, 2.0), 0.0, 2.0);
  // Overlapping intervals leave no gap between them.
  expect_interval(longest_uncovered({2.0, 2.6, 3.1}, 0.5, 0.0, 4.0), 0.0, 1.5);
}

// ---------------------------------------------------------------------------------------------------------
// A loop between two crossings: loop_geometry, rod_radius, analyse_knot

/// Tail A along +x up to the origin (s in [0, 5]), a circle of radius R = 1.5 in the plane z = 0 tangent to
/// the x axis at the origin (s in [5, 5 + 2 pi R], 48 nodes), tail B from the origin along
/// (cos 30 deg, -sin 30 deg, 0) (5 mm). The reference arc length is the length along this curve.
constexpr double kLoopRadius = 1.5;
constexpr double kLoopStart = 5.0;
const double kLoopEnd = kLoopStart + 2.0 * kPi * kLoopRadius;

Vec3 loop_curve(double s) {
  if (s <= kLoopStart) return Vec3(s - kLoopStart, 0.0, 0.0);
  if (s >= kLoopEnd) {
    const double b = 30.0 * kPi / 180.0;
    return (s - kLoopEnd) * Vec3(std::cos(b), -std::sin(b), 0.0);
  }
  const double phi = (s - kLoopStart) / kLoopRadius;
  return Vec3(kLoopRadius * std::sin(phi), kLoopRadius * (1.0 - std::cos(phi)), 0.0);
}

Centreline loop_centreline() {
  Centreline c;
  for (int k = 0; k <= 10; ++k) c.arc_length.push_back(0.5 * k);
  for (int k = 1; k < 48; ++k) c.arc_length.push_back(kLoopStart + (kLoopEnd - kLoopStart) * k / 48);
  for (int k = 0; k <= 10; ++k) c.arc_length.push_back(kLoopEnd + 0.5 * k);
  for (double s : c.arc_length) c.points.push_back(loop_curve(s));
  return c;
}

/// Seven elements in contact where the tails cross at the origin: abscissa_i from kLoopStart - 0.375 up in
/// steps of 0.125 mm (binary fractions: the element spacing is 0.125 mm exactly), abscissa_j from
/// kLoopEnd + 0.375 down; particles 0.1 mm below and above the axis.
ContactTable crossing_contact() {
  ContactTable t = blank_table(7);
  for (int k = 0; k < 7; ++k) {
    t.abscissa_i[k] = kLoopStart - 0.375 + 0.125 * k;
    t.abscissa_j[k] = kLoopEnd + 0.375 - 0.125 * k;
    t.particle_i.row(k) = (loop_curve(t.abscissa_i[k]) - 0.1 * Vec3::UnitZ()).transpose();
    t.particle_j.row(k) = (loop_curve(t.abscissa_j[k]) + 0.1 * Vec3::UnitZ()).transpose();
    t.normal_force[k] = 0.1 + 0.01 * k;
    t.tangential_force[k] = 0.02 * k;
    t.gap[k] = -0.001 * k;
    t.state[k] = 1;
  }
  return t;
}

TEST(LoopGeometry, LoopBetweenTwoCrossingsHasTheCircleRadiusAndLength) {
  const Centreline c = loop_centreline();
  const ContactTable t = crossing_contact();
  const double s_a = kLoopStart - 0.375, s_b = kLoopEnd + 0.375;
  // Half the spacing, 0.0625 mm, around each touched abscissa: the loop is
  // (kLoopStart + 0.4375, kLoopEnd - 0.4375).
  const LoopGeometry loop = loop_geometry(c, t, s_a, s_b);
  EXPECT_NEAR(loop.length, kLoopEnd - kLoopStart - 0.875, 1e-12);
  EXPECT_NEAR(loop.radius, kLoopRadius, 1e-12);
  KnotMetricsOptions demanding;
  demanding.min_loop_nodes = 100;  // more than the loop's 43 nodes
  EXPECT_TRUE(std::isnan(loop_geometry(c, t, s_a, s_b, demanding).radius));
  EXPECT_NEAR(loop_geometry(c, t, s_a, s_b, demanding).length, loop.length, 0.0);
  // Elements covering all of [s_a, s_b] (intervals exactly touching): no loop.
  const LoopGeometry none = loop_geometry(c, t, kLoopStart - 0.375, kLoopStart + 0.375);
  EXPECT_TRUE(std::isnan(none.length));
  EXPECT_TRUE(std::isnan(none.radius));
}

/// A straight rod along x (nodes every 0.5 mm, s = x) and `n` particles at distance r from its axis, at
/// abscissas between the nodes and angles around the axis.
std::pair<Centreline, ContactTable> particles_around_a_rod(int n, double r) {
  Centreline c;
  for (int k = 0; k <= 20; ++k) {
    c.arc_length.push_back(0.5 * k);
    c.points.push_back(Vec3(0.5 * k, 0.0, 0.0));
  }
  ContactTable t = blank_table(n);
  for (int k = 0; k < n; ++k) {
    const double s = 0.3 + 0.7 * k, theta = 0.9 * k;
    t.abscissa_i[k] = s;
    t.particle_i.row(k) = Vec3(s, r * std::cos(theta), r * std::sin(theta)).transpose();
  }
  return {c, t};
}

TEST(RodRadius, MedianDistanceOfTheParticlesFromTheAxis) {
  const auto [c1, t1] = particles_around_a_rod(7, 0.1);
  const auto [c2, t2] = particles_around_a_rod(5, 0.3);
  EXPECT_NEAR(rod_radius({c1}, {t1}), 0.1, 1e-15);
  // Two states: 7 particles at 0.1, 5 at 0.3; the median is the mean of the middle two, 0.1 and 0.1.
  EXPECT_NEAR(rod_radius({c1, c2}, {t1, t2}), 0.1, 1e-15);
  // 7 at 0.1, 7 at 0.3: the mean of 0.1 and 0.3.
  const auto [c3, t3] = particles_around_a_rod(7, 0.3);
  EXPECT_NEAR(rod_radius({c1, c3}, {t1, t3}), 0.2, 1e-15);
  EXPECT_EQ(rod_radius({c1}, {blank_table(0)}), kDefaultRodRadius);
  EXPECT_EQ(rod_radius({}, {}), kDefaultRodRadius);
  EXPECT_THROW(rod_radius({c1}, {}), std::invalid_argument);
}

TEST(AnalyseKnot, LoopBetweenTwoCrossings) {
  const KnotMetrics m = analyse_knot(loop_centreline(), crossing_contact());
  EXPECT_EQ(m.zones, 1);
  EXPECT_EQ(m.contact_elements, 7);
  EXPECT_EQ(m.elements_in_contact, 7);
  EXPECT_DOUBLE_EQ(m.s_a, kLoopStart - 0.375);
  EXPECT_DOUBLE_EQ(m.s_b, kLoopEnd + 0.375);
  // Tail A's chord points along -x, tail B's along (cos 30, -sin 30, 0): 150 degrees apart.
  EXPECT_NEAR(m.tail_angle, 150.0, 1e-10);
  EXPECT_NEAR(m.loop_radius, kLoopRadius, 1e-12);
  EXPECT_NEAR(m.loop_length, kLoopEnd - kLoopStart - 0.875, 1e-12);
  EXPECT_NEAR(m.max_normal, 0.16, 1e-15);
  EXPECT_NEAR(m.total_normal, 7 * 0.1 + 0.01 * 21, 1e-14);
  EXPECT_NEAR(m.max_tangential, 0.12, 1e-15);
  EXPECT_NEAR(m.total_tangential, 0.02 * 21, 1e-14);
  EXPECT_NEAR(m.max_penetration, 0.006, 1e-15);
  // Midpoints: (c(s_i) + c(s_j)) / 2, both near the origin; all seven in contact.
  ASSERT_EQ(m.reactions.abscissa.size(), 7);
  EXPECT_EQ(m.reactions.abscissa[0], 0.0);
  EXPECT_NEAR(m.intermediate_length, m.reactions.abscissa[6], 1e-15);
}

TEST(AnalyseKnot, DoesNotDependOnTheOrderOfTheElements) {
  const Centreline c = loop_centreline();
  ContactTable t = straight_zones();
  for (int k = 0; k < 6; ++k) t.zeta[k] = 0.1 * (k % 3);
  const KnotMetrics sorted = analyse_knot(c, t);
  const std::vector<int> shuffle{4, 0, 5, 2, 3, 1};
  ContactTable shuffled = t;
  for (int k = 0; k < 6; ++k) {
    const int from = shuffle[static_cast<std::size_t>(k)];
    shuffled.zone[k] = t.zone[from];
    shuffled.zeta[k] = t.zeta[from];
    shuffled.abscissa_i[k] = t.abscissa_i[from];
    shuffled.abscissa_j[k] = t.abscissa_j[from];
    shuffled.particle_i.row(k) = t.particle_i.row(from);
    shuffled.particle_j.row(k) = t.particle_j.row(from);
    shuffled.normal_force[k] = t.normal_force[from];
  }
  const KnotMetrics m = analyse_knot(c, shuffled);
  EXPECT_EQ(m.intermediate_length, sorted.intermediate_length);
  EXPECT_NEAR(m.intermediate_length, 4.0, 1e-14);  // as in MidpointsOnStraightLines...
  EXPECT_EQ(m.s_a, sorted.s_a);
  EXPECT_EQ(m.s_b, sorted.s_b);
  EXPECT_EQ(m.reactions.abscissa, sorted.reactions.abscissa);
  for (int k = 0; k < 6; ++k)
    EXPECT_EQ(shuffle[m.reactions.element[static_cast<std::size_t>(k)]], k);  // back to the table given
}

TEST(AnalyseKnot, NoElementInContactGivesNaN) {
  const Centreline c = loop_centreline();
  ContactTable open = crossing_contact();
  open.normal_force.setZero();
  const KnotMetrics m = analyse_knot(c, open);
  EXPECT_EQ(m.contact_elements, 7);
  EXPECT_EQ(m.elements_in_contact, 0);
  EXPECT_EQ(m.intermediate_length, 0.0);
  EXPECT_EQ(m.max_normal, 0.0);
  for (double v : {m.s_a, m.s_b, m.tail_angle, m.loop_radius, m.loop_length}) EXPECT_TRUE(std::isnan(v));
  EXPECT_NEAR(m.max_penetration, 0.006, 1e-15);

  const KnotMetrics empty = analyse_knot(c, blank_table(0));
  EXPECT_EQ(empty.zones, 0);
  EXPECT_EQ(empty.contact_elements, 0);
  EXPECT_EQ(empty.max_normal, 0.0);
  EXPECT_EQ(empty.total_normal, 0.0);
  EXPECT_EQ(empty.max_tangential, 0.0);
  for (double v : {empty.s_a, empty.tail_angle, empty.loop_radius, empty.max_penetration})
    EXPECT_TRUE(std::isnan(v));

  Centreline short_rod{{Vec3::Zero()}, {0.0}};
  EXPECT_THROW(analyse_knot(short_rod, open), std::invalid_argument);
  ContactTable ragged = open;
  ragged.gap.resize(3);
  EXPECT_THROW(analyse_knot(c, ragged), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------
// The contact table from a contact geometry, against contact_final.csv of the same geometry

/// Two zones (beams 0-1 with two elements, 0-2 with one).
contact::ContactGeometry hand_geometry() {
  contact::ContactGeometry g;
  g.zones.resize(2);
  g.zones[0].beam_i = 0;
  g.zones[0].beam_j = 1;
  g.zones[0].first_element = 0;
  g.zones[0].num_elements = 2;
  g.zones[1].beam_i = 0;
  g.zones[1].beam_j = 2;
  g.zones[1].first_element = 2;
  g.zones[1].num_elements = 1;
  for (int k = 0; k < 3; ++k) {
    contact::ContactElement e;
    e.zone = k < 2 ? 0 : 1;
    e.zeta = 0.25 + 0.5 * (k % 2);
    e.particle_i.abscissa = 1.0 + 0.123456789012 * k;
    e.particle_j.abscissa = 7.0 - 0.3 * k;
    e.particle_i.transverse = Eigen::Vector2d(0.1, 0.0);
    e.particle_j.transverse = Eigen::Vector2d(0.0, -0.1);
    e.position_i = Vec3(0.5 * k, 1.0 / 3.0, -2.0);
    e.position_j = Vec3(0.5 * k, 1.0 / 3.0, -1.81 - 0.001 * k);
    e.normal = Vec3::UnitZ();
    e.gap = -0.01 + 0.011 * k;
    g.elements.push_back(e);
  }
  return g;
}

std::vector<simulation::ContactState> hand_states() {
  std::vector<simulation::ContactState> s(3);
  s[0].normal_reaction = 0.25;
  s[0].tangential = Vec3(0.03, -0.04, 0.0);
  s[0].slip = true;
  s[1].normal_reaction = 1.0 / 7.0;
  s[1].tangential = Vec3(0.0, 0.01, 0.0);
  return s;  // s[2] open
}

/// The rows of a CSV text as {column: values} (every column read as a number, NaN where it is not one).
std::map<std::string, std::vector<std::string>> parse_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  std::map<std::string, std::vector<std::string>> columns;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (const std::string& name : header) {
      std::string cell;
      std::getline(row, cell, ',');
      columns[name].push_back(cell);
    }
  }
  return columns;
}

TEST(ContactTable, AgreesWithTheContactCsvOfTheSameGeometry) {
  const contact::ContactGeometry g = hand_geometry();
  const std::vector<simulation::ContactState> states = hand_states();
  const ContactTable t = contact_table(g, &states);
  ASSERT_EQ(t.size(), 3U);
  auto csv = parse_csv(output::contact_final_csv(g, {"rod", "tool_a", "tool_b"}, &states));
  ASSERT_EQ(csv["zone"].size(), 3U);
  const auto number = [&](const std::string& column, int k) {
    return std::stod(csv[column][static_cast<std::size_t>(k)]);
  };
  const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(t.zone[k], static_cast<int>(number("zone", k)));
    EXPECT_EQ(csv["beam_j"][static_cast<std::size_t>(k)], k < 2 ? "tool_a" : "tool_b");
    EXPECT_EQ(t.beam_j[k], k < 2 ? 1 : 2);
    EXPECT_EQ(t.beam_i[k], 0);
    EXPECT_TRUE(close(t.zeta[k], number("zeta", k)));
    EXPECT_TRUE(close(t.abscissa_i[k], number("abscissa_i", k)));
    EXPECT_TRUE(close(t.abscissa_j[k], number("abscissa_j", k)));
    const char* axes[] = {"x", "y", "z"};
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(close(t.particle_i(k, c), number(std::string(axes[c]) + "_i", k)));
      EXPECT_TRUE(close(t.particle_j(k, c), number(std::string(axes[c]) + "_j", k)));
    }
    EXPECT_TRUE(close(t.gap[k], number("gap", k)));
    EXPECT_TRUE(close(t.normal_force[k], number("normal_force", k)));
    EXPECT_TRUE(close(t.tangential_force[k], number("tangential_force", k)));
    EXPECT_EQ(std::string(output::status_name(static_cast<output::ContactStatus>(t.state[k]))),
              csv["state"][static_cast<std::size_t>(k)]);
  }
  // Against the inputs themselves: |T| of (0.03, -0.04, 0) is 0.05; slip, stick, open.
  EXPECT_DOUBLE_EQ(t.tangential_force[0], 0.05);
  EXPECT_EQ(t.state[0], 2);
  EXPECT_EQ(t.state[1], 1);
  EXPECT_EQ(t.state[2], 0);
  EXPECT_EQ(t.particle_j(2, 2), -1.812);
}

TEST(ContactTable, WithoutStatesHasNoForces) {
  const ContactTable t = contact_table(hand_geometry());
  ASSERT_EQ(t.size(), 3U);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(std::isnan(t.normal_force[k]));
    EXPECT_TRUE(std::isnan(t.tangential_force[k]));
    EXPECT_EQ(t.state[k], kNoStatus);
  }
  const std::vector<simulation::ContactState> two(2);
  EXPECT_THROW(contact_table(hand_geometry(), &two), std::invalid_argument);
  contact::ContactGeometry bad = hand_geometry();
  bad.elements[2].zone = 5;
  EXPECT_THROW(contact_table(bad), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------
// Against knot_metrics_reference.py (knot_report.py's numpy metrics before they moved here) on the same
// numbers

namespace fs = std::filesystem;

/// The Python interpreter: Debian's (which scripts/setup.sh equips with numpy and matplotlib), else the
/// first python3 on the PATH.
std::string python() {
  return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

/// Runs `command` through the shell; its stdout, and its exit status in `status`.
std::string run_command(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) {
    status = -1;
    return out;
  }
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int raw = ::pclose(pipe);
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

/// A double as text that reads back to the same double.
std::string exact(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// What the Python computes, as lines `KEY v1 v2 ...` (repr of each float).
constexpr const char* kPythonProgram = R"(import importlib.util, sys
from pathlib import Path
import numpy as np
spec = importlib.util.spec_from_file_location("knot_metrics_reference", sys.argv[1])
kr = importlib.util.module_from_spec(spec)
spec.loader.exec_module(kr)
folder = Path(sys.argv[2])
state = kr.load_state(folder, "tightened", None)
row, reactions, extent = kr.analyse(state)
def out(key, values):
    print("@" + key, *[repr(float(v)) for v in np.atleast_1d(values)])
for key in ["zones", "contact_elements", "elements_in_contact", "intermediate_length_mm", "max_normal_N",
            "total_normal_N", "max_tangential_N", "total_tangential_N", "tail_angle_deg", "loop_radius_mm",
            "loop_length_mm", "max_penetration_mm"]:
    out(key, row[key])
out("extent", extent)
for key in ["zone", "zeta", "abscissa_mm", "s_i", "s_j", "x", "y", "z", "normal_N", "tangential_N"]:
    out("reactions_" + key, reactions[key])
out("rod_radius", kr.rod_radius([state]))
out("element_spacing", kr.element_spacing(state.contact))
probe = np.array([-1.0, 0.3, 4.77, 12.5, 99.0])
out("centreline", kr.centreline(state.nodes, probe).ravel())
out("tail_angle", kr.tail_angle(state.nodes, 3.3, 14.2))
nodes = np.column_stack([state.nodes[c] for c in ("x", "y", "z")])
out("fit_circle", kr.fit_circle(nodes[12:30]))
out("fit_circle_all", kr.fit_circle(nodes))
)";

/// The loop of loop_centreline with nodes moved by up to 0.05 mm (seeded), and two zones of contact
/// elements (forces, gaps, positions perturbed alike, some elements open), in shuffled order.
struct Dataset {
  Centreline centreline;
  ContactTable contact;
};

Dataset noisy_dataset() {
  std::mt19937 random(20240611);
  std::uniform_real_distribution<double> noise(-0.05, 0.05), unit(0.0, 1.0);
  Dataset d;
  d.centreline = loop_centreline();
  for (Vec3& p : d.centreline.points) p += Vec3(noise(random), noise(random), noise(random));
  const int n = 17;
  ContactTable t = blank_table(n);
  for (int k = 0; k < n; ++k) {
    const bool second = k >= 9;  // zone 0: the crossing; zone 1: a few elements inside the loop
    const int m = second ? k - 9 : k;
    t.zone[k] = second ? 3 : 0;
    t.beam_j[k] = second ? 1 : 0;
    t.zeta[k] = (m + 0.5) / (second ? 8.0 : 9.0);
    t.abscissa_i[k] = second ? 8.0 + 0.13 * m + noise(random) : kLoopStart - 0.4 + 0.1 * m + noise(random);
    t.abscissa_j[k] = second ? 3.0 - 0.11 * m : kLoopEnd + 0.4 - 0.1 * m + noise(random);
    const Vec3 xi = loop_curve(t.abscissa_i[k]) + Vec3(noise(random), noise(random), -0.1);
    const Vec3 xj = loop_curve(t.abscissa_j[k]) + Vec3(noise(random), noise(random), 0.1);
    t.particle_i.row(k) = xi.transpose();
    t.particle_j.row(k) = xj.transpose();
    t.gap[k] = 0.002 * noise(random);
    const bool open = k == 0 || k == 8 || k == 12 || unit(random) < 0.15;
    t.normal_force[k] = open ? 0.0 : unit(random);
    t.tangential_force[k] = open ? 0.0 : 0.3 * unit(random);
    t.state[k] = open ? 0 : 1 + (k % 2);
  }
  // Shuffled: both implementations sort by (zone, zeta) first.
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) order[static_cast<std::size_t>(k)] = (7 * k + 3) % n;
  d.contact = blank_table(n);
  for (int k = 0; k < n; ++k) {
    const int from = order[static_cast<std::size_t>(k)];
    d.contact.zone[k] = t.zone[from];
    d.contact.beam_j[k] = t.beam_j[from];
    d.contact.zeta[k] = t.zeta[from];
    d.contact.abscissa_i[k] = t.abscissa_i[from];
    d.contact.abscissa_j[k] = t.abscissa_j[from];
    d.contact.particle_i.row(k) = t.particle_i.row(from);
    d.contact.particle_j.row(k) = t.particle_j.row(from);
    d.contact.gap[k] = t.gap[from];
    d.contact.normal_force[k] = t.normal_force[from];
    d.contact.tangential_force[k] = t.tangential_force[from];
    d.contact.state[k] = t.state[from];
  }
  return d;
}

/// Writes the dataset as knot_report.py reads a run folder: final_nodes.csv, contact_final.csv, and a
/// steps.csv without rows.
void write_run_folder(const Dataset& d, const fs::path& folder) {
  std::ofstream nodes(folder / "final_nodes.csv");
  nodes << "beam,node,s,x,y,z\n";
  for (std::size_t k = 0; k < d.centreline.points.size(); ++k) {
    const Vec3& p = d.centreline.points[k];
    nodes << "rod," << k << ',' << exact(d.centreline.arc_length[k]) << ',' << exact(p.x()) << ','
          << exact(p.y()) << ',' << exact(p.z()) << '\n';
  }
  std::ofstream contact(folder / "contact_final.csv");
  contact << "zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,x_i,y_i,z_i,x_j,y_j,z_j,gap,normal_force,"
             "tangential_force,state\n";
  const ContactTable& t = d.contact;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    contact << t.zone[i] << ",rod," << (t.beam_j[i] == 0 ? "rod" : "tool") << ',' << exact(t.zeta[i]) << ','
            << exact(t.abscissa_i[i]) << ',' << exact(t.abscissa_j[i]);
    for (int c = 0; c < 3; ++c) contact << ',' << exact(t.particle_i(i, c));
    for (int c = 0; c < 3; ++c) contact << ',' << exact(t.particle_j(i, c));
    contact << ',' << exact(t.gap[i]) << ',' << exact(t.normal_force[i]) << ','
            << exact(t.tangential_force[i]) << ','
            << output::status_name(static_cast<output::ContactStatus>(t.state[i])) << '\n';
  }
  std::ofstream(folder / "steps.csv") << "step,load_time\n";
}

/// Parses the `@KEY v1 v2 ...` lines of the Python program.
std::map<std::string, std::vector<double>> parse_python(const std::string& text) {
  std::map<std::string, std::vector<double>> values;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] != '@') continue;
    std::istringstream words(line.substr(1));
    std::string key, word;
    words >> key;
    std::vector<double>& v = values[key];
    while (words >> word) v.push_back(std::strtod(word.c_str(), nullptr));
  }
  return values;
}

/// Relative agreement |a - b| <= tol max(|a|, |b|); NaN agrees with NaN only.
::testing::AssertionResult agree(const std::string& what, double cpp, double py, double tol = 1e-12) {
  if (std::isnan(cpp) || std::isnan(py)) {
    if (std::isnan(cpp) && std::isnan(py)) return ::testing::AssertionSuccess();
  } else if (std::abs(cpp - py) <= tol * std::max(std::abs(cpp), std::abs(py))) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << what << ": C++ " << exact(cpp) << ", Python " << exact(py);
}

TEST(KnotMetricsPythonReference, SameNumbersOnASyntheticKnot) {
  int status = 0;
  run_command(python() + " -c 'import numpy' > /dev/null 2>&1", status);
  if (status != 0) GTEST_SKIP() << python() << " lacks numpy (scripts/setup.sh installs it)";

  char folder_template[] = "/tmp/nodus_knot_metrics_XXXXXX";
  ASSERT_NE(::mkdtemp(folder_template), nullptr);
  const fs::path folder(folder_template);
  const Dataset d = noisy_dataset();
  write_run_folder(d, folder);
  std::ofstream(folder / "program.py") << kPythonProgram;
  const std::string script = std::string(NODUS_SOURCE_DIR) + "/tests/analysis/knot_metrics_reference.py";
  const std::string output =
      run_command("MPLCONFIGDIR='" + folder.string() + "' " + python() + " '" +
                      (folder / "program.py").string() + "' '" + script + "' '" + folder.string() + "' 2>&1",
                  status);
  fs::remove_all(folder);
  ASSERT_EQ(status, 0) << output;
  auto py = parse_python(output);

  const KnotMetrics m = analyse_knot(d.centreline, d.contact);
  const auto scalar = [&](const std::string& key) {
    return py[key].size() == 1 ? py[key][0] : std::numeric_limits<double>::infinity();
  };
  EXPECT_EQ(m.zones, scalar("zones"));
  EXPECT_EQ(m.contact_elements, scalar("contact_elements"));
  EXPECT_EQ(m.elements_in_contact, scalar("elements_in_contact"));
  EXPECT_TRUE(agree("intermediate_length", m.intermediate_length, scalar("intermediate_length_mm")));
  EXPECT_TRUE(agree("max_normal", m.max_normal, scalar("max_normal_N")));
  EXPECT_TRUE(agree("total_normal", m.total_normal, scalar("total_normal_N")));
  EXPECT_TRUE(agree("max_tangential", m.max_tangential, scalar("max_tangential_N")));
  EXPECT_TRUE(agree("total_tangential", m.total_tangential, scalar("total_tangential_N")));
  EXPECT_TRUE(agree("tail_angle", m.tail_angle, scalar("tail_angle_deg")));
  EXPECT_TRUE(agree("loop_radius", m.loop_radius, scalar("loop_radius_mm")));
  EXPECT_TRUE(agree("loop_length", m.loop_length, scalar("loop_length_mm")));
  EXPECT_TRUE(agree("max_penetration", m.max_penetration, scalar("max_penetration_mm")));
  ASSERT_EQ(py["extent"].size(), 2U);
  EXPECT_TRUE(agree("s_a", m.s_a, py["extent"][0]));
  EXPECT_TRUE(agree("s_b", m.s_b, py["extent"][1]));
  // The loop exists and is fitted: the comparison is not between two NaN.
  EXPECT_FALSE(std::isnan(m.loop_radius));
  EXPECT_GT(m.intermediate_length, 0.0);

  const ReactionsTable& r = m.reactions;
  const auto column = [&](const std::string& key, const Eigen::VectorXd& cpp) {
    const std::vector<double>& v = py["reactions_" + key];
    ASSERT_EQ(v.size(), static_cast<std::size_t>(cpp.size())) << key;
    for (std::size_t k = 0; k < v.size(); ++k)
      EXPECT_TRUE(agree(key + "[" + std::to_string(k) + "]", cpp[static_cast<Eigen::Index>(k)], v[k]));
  };
  column("zone", r.zone.cast<double>());
  column("zeta", r.zeta);
  // The first abscissa of the first zone is 0 in both: relative agreement is exact agreement there.
  column("abscissa_mm", r.abscissa);
  column("s_i", r.s_i);
  column("s_j", r.s_j);
  column("x", r.midpoint.col(0));
  column("y", r.midpoint.col(1));
  column("z", r.midpoint.col(2));
  column("normal_N", r.normal);
  column("tangential_N", r.tangential);

  EXPECT_TRUE(agree("rod_radius", rod_radius({d.centreline}, {d.contact}), scalar("rod_radius")));
  EXPECT_TRUE(agree("element_spacing", element_spacing(sorted_by_zone_and_zeta(d.contact)),
                    scalar("element_spacing")));
  Eigen::VectorXd probe(5);
  probe << -1.0, 0.3, 4.77, 12.5, 99.0;
  const Points at = centreline_at(d.centreline, probe);
  ASSERT_EQ(py["centreline"].size(), 15U);
  for (int k = 0; k < 5; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(agree("centreline", at(k, c), py["centreline"][static_cast<std::size_t>(3 * k + c)]));
  EXPECT_TRUE(agree("tail_angle(3.3, 14.2)", tail_angle(d.centreline, 3.3, 14.2), scalar("tail_angle")));
  Points nodes(static_cast<Eigen::Index>(d.centreline.points.size()), 3);
  for (std::size_t k = 0; k < d.centreline.points.size(); ++k)
    nodes.row(static_cast<Eigen::Index>(k)) = d.centreline.points[k].transpose();
  EXPECT_TRUE(agree("fit_circle(nodes 12..29)", fit_circle(nodes.middleRows(12, 18)), scalar("fit_circle")));
  EXPECT_TRUE(agree("fit_circle(all nodes)", fit_circle(nodes), scalar("fit_circle_all")));
}

}  // namespace
}  // namespace nodus::analysis
