// The crossing guard (contact/crossing.hpp): moving segments against closed forms and against meetings built
// on purpose, and beams of a model passing through each other, or through themselves, between two states.

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "contact_test_support.hpp"
#include "nodus/contact/crossing.hpp"

namespace nodus::contact {
namespace {

using testing::beam_definition;
using testing::constant;
using testing::line;
using testing::place_beam;
using Segments = Eigen::Matrix<double, 3, 4>;  // columns p0, p1, q0, q1

Segments segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  Segments s;
  s << p0, p1, q0, q1;
  return s;
}

TEST(SegmentsMeet, OneDrivenThroughTheOtherMeetsWhereTheyCross) {
  // p along x at z = 0.5 moves down to z = -0.5 through q along y at z = 0: they meet half way, at the middle
  // of both.
  const Segments start = segments({-1, 0, 0.5}, {1, 0, 0.5}, {0, -1, 0}, {0, 1, 0});
  const Segments end = segments({-1, 0, -0.5}, {1, 0, -0.5}, {0, -1, 0}, {0, 1, 0});
  const auto m = segments_meet(start, end);
  ASSERT_TRUE(m);
  EXPECT_NEAR(m->instant, 0.5, 1e-12);
  EXPECT_NEAR(m->u, 0.5, 1e-12);
  EXPECT_NEAR(m->v, 0.5, 1e-12);
  // Off-centre and uneven: p's ends at heights 0.3 and 0.9 go to -0.7 and -0.1; over q at x = 0.5 (u = 0.75)
  // p's height is 0.75 - t, zero at t = 0.75.
  const Segments start2 = segments({-1, 0.2, 0.3}, {1, 0.2, 0.9}, {0.5, -1, 0}, {0.5, 1, 0});
  const Segments end2 = segments({-1, 0.2, -0.7}, {1, 0.2, -0.1}, {0.5, -1, 0}, {0.5, 1, 0});
  const auto m2 = segments_meet(start2, end2);
  ASSERT_TRUE(m2);
  EXPECT_NEAR(m2->instant, 0.75, 1e-12);
  EXPECT_NEAR(m2->u, 0.75, 1e-12);
  EXPECT_NEAR(m2->v, 0.6, 1e-12);
}

TEST(SegmentsMeet, PassingBeyondAnEndOrStoppingShortIsNoMeeting) {
  // p crosses the plane of q at y = 1.5, beyond q's end at y = 1.
  EXPECT_FALSE(segments_meet(segments({-1, 1.5, 0.5}, {1, 1.5, 0.5}, {0, -1, 0}, {0, 1, 0}),
                             segments({-1, 1.5, -0.5}, {1, 1.5, -0.5}, {0, -1, 0}, {0, 1, 0})));
  // p stops 1e-3 above q.
  EXPECT_FALSE(segments_meet(segments({-1, 0, 0.5}, {1, 0, 0.5}, {0, -1, 0}, {0, 1, 0}),
                             segments({-1, 0, 1e-3}, {1, 0, 1e-3}, {0, -1, 0}, {0, 1, 0})));
  // Both move along z together: always 0.5 apart.
  EXPECT_FALSE(segments_meet(segments({-1, 0, 0.5}, {1, 0, 0.5}, {0, -1, 0}, {0, 1, 0}),
                             segments({-1, 0, -1.5}, {1, 0, -1.5}, {0, -1, -2}, {0, 1, -2})));
}

TEST(SegmentsMeet, InOnePlaneTheyMeetIfTheyDoAtTheEnd) {
  // Coplanar throughout (z = 0): the cubic vanishes identically; p ends across q.
  const Segments start = segments({-1, 2, 0}, {1, 2, 0}, {0, -1, 0}, {0, 1, 0});
  const auto m = segments_meet(start, segments({-1, 0.5, 0}, {1, 0.5, 0}, {0, -1, 0}, {0, 1, 0}));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->instant, 1.0);
  EXPECT_NEAR(m->v, 0.75, 1e-12);
  EXPECT_FALSE(segments_meet(start, segments({-1, 1.5, 0}, {1, 1.5, 0}, {0, -1, 0}, {0, 1, 0})));
}

/// Random segments made to meet at instant t_meet, where p(u) = q(v): the guard finds a meeting no later,
/// and the points it reports coincide at the instant it reports.
TEST(SegmentsMeet, MeetingsBuiltOnPurposeAreFound) {
  std::mt19937 gen(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-1.0, 1.0);
  const auto random_vector = [&] { return Vec3(coordinate(gen), coordinate(gen), coordinate(gen)); };
  int later_found_earlier = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const double t_meet = 0.05 + 0.95 * unit(gen), u = unit(gen), v = unit(gen);
    const Vec3 x = random_vector(), dp = random_vector(), dq = random_vector();
    // At t_meet: p = x - u dp .. x + (1 - u) dp, q likewise along dq.
    const Segments at = segments(x - u * dp, x + (1 - u) * dp, x - v * dq, x + (1 - v) * dq);
    Segments start;
    for (int c = 0; c < 4; ++c) start.col(c) = random_vector();
    const Segments end = start + (at - start) / t_meet;
    const auto m = segments_meet(start, end);
    ASSERT_TRUE(m) << "trial " << trial;
    EXPECT_LE(m->instant, t_meet + 1e-9) << "trial " << trial;
    if (m->instant < t_meet - 1e-9) ++later_found_earlier;
    const Segments now = start + m->instant * (end - start);
    const Vec3 p = now.col(0) + m->u * (now.col(1) - now.col(0));
    const Vec3 q = now.col(2) + m->v * (now.col(3) - now.col(2));
    EXPECT_LT((p - q).norm(), 1e-9) << "trial " << trial;
  }
  // Some random motions meet twice: the first meeting is reported.
  EXPECT_LT(later_found_earlier, 250);
}

/// Random segments kept on either side of the plane z = 0 (p above 0.01, q below -0.01) never meet.
TEST(SegmentsMeet, SegmentsKeptApartNeverMeet) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), height(0.01, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    Segments start, end;
    for (int c = 0; c < 4; ++c) {
      const double sign = c < 2 ? 1.0 : -1.0;
      start.col(c) = Vec3(coordinate(gen), coordinate(gen), sign * height(gen));
      end.col(c) = Vec3(coordinate(gen), coordinate(gen), sign * height(gen));
    }
    EXPECT_FALSE(segments_meet(start, end)) << "trial " << trial;
  }
}

/// Beam I along x; beam J along y at height z0 in the first state and z1 in the second, crossing above the
/// middle of I at J's abscissa 1.3 (not a node).
std::optional<Crossing> beams_moved(double z0, double z1) {
  model::Model m;
  m.add_beam(beam_definition(4.0, 0.1, 20));
  m.add_beam(beam_definition(3.0, 0.1, 15));
  Eigen::VectorXd x0 = m.reference(), x1 = m.reference();
  place_beam(m, x0, 0, line(Vec3(-2.0, 0.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  place_beam(m, x1, 0, line(Vec3(-2.0, 0.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  place_beam(m, x0, 1, line(Vec3(0.1, -1.3, z0), Vec3::UnitY()), constant(Vec3::UnitX()));
  place_beam(m, x1, 1, line(Vec3(0.1, -1.3, z1), Vec3::UnitY()), constant(Vec3::UnitX()));
  return find_crossing(m, x0, x1, {}, 1.2);
}

TEST(FindCrossing, ABeamDrivenThroughAnotherIsCaught) {
  const auto c = beams_moved(0.3, -0.1);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->beam_i, 0);
  EXPECT_EQ(c->beam_j, 1);
  EXPECT_NEAR(c->instant, 0.75, 1e-12);
  EXPECT_NEAR(c->s_i, 2.1, 1e-12);
  EXPECT_NEAR(c->s_j, 1.3, 1e-12);
  // Coming down onto it, or lifted away from below, is no crossing.
  EXPECT_FALSE(beams_moved(0.3, 0.19));
  EXPECT_FALSE(beams_moved(-0.3, -1.0));
}

/// Most of a figure eight, r(t) = (sin t, sin t cos t, z), t = t0 + 1.7 pi s / L, crossing itself at the
/// origin at t = 0 and t = pi: its second lobe (t > pi / 2) is lifted from z = h0 to h1 over the first.
constexpr double kLength = 8.0, kT0 = -0.5 * std::numbers::pi + 0.3, kSpan = 1.7 * std::numbers::pi;
std::optional<Crossing> figure_eight_moved(double h0, double h1, double separation) {
  model::Model m;
  m.add_beam(beam_definition(kLength, 0.02, 150));
  Eigen::VectorXd x0 = m.reference(), x1 = m.reference();
  const auto eight = [](double h) {
    return [h](double s) {
      const double t = kT0 + kSpan * s / kLength;
      return Vec3(std::sin(t), std::sin(t) * std::cos(t), t > 0.5 * std::numbers::pi ? h : 0.0);
    };
  };
  place_beam(m, x0, 0, eight(h0), constant(Vec3::UnitZ()));
  place_beam(m, x1, 0, eight(h1), constant(Vec3::UnitZ()));
  return find_crossing(m, x0, x1, {}, separation);
}

TEST(FindCrossing, ABeamThroughItselfIsCaughtBeyondTheSeparation) {
  const auto c = figure_eight_moved(0.2, -0.2, 1.2);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->beam_i, 0);
  EXPECT_EQ(c->beam_j, 0);
  EXPECT_NEAR(c->instant, 0.5, 1e-9);
  // The crossing points: t = 0 and pi, within an element's length (the chords stand for the curve).
  const double h = kLength / 150;
  EXPECT_NEAR(c->s_i, (0.0 - kT0) * kLength / kSpan, h);
  EXPECT_NEAR(c->s_j, (std::numbers::pi - kT0) * kLength / kSpan, h);
  EXPECT_FALSE(figure_eight_moved(0.2, 0.1, 1.2));
  EXPECT_FALSE(figure_eight_moved(-0.2, -0.1, 1.2));
  // With a separation longer than the beam, no part of it is paired with another.
  EXPECT_FALSE(figure_eight_moved(0.2, -0.2, 10.0));
}

}  // namespace
}  // namespace nodus::contact
