// Topology checks of a centreline against references the code did not produce: knots built from their
// textbook parametrisations (trefoil, figure-eight, torus knots T(p, q)), whose Alexander polynomials are
// known in closed form (Rolfsen's table; T(p, q): (t^pq - 1)(t - 1) / ((t^p - 1)(t^q - 1))), invariance
// under rigid motion, scale, mirror image and sampling; self-distances of curves with closed-form answers
// (skew lines, a hairpin, a circle, a helix).
//
// Opening a closed knot into an open one without changing its type: cut it at a point K(t0) where a plane
// supports it (the knot lies on one side and touches the plane there only), and attach straight tails to the
// two cut ends inside that plane, in opposite directions +-e (e normal to the tangent at K(t0), so the tails
// run on two parallel lines). The tails and any closure far away then lie in the empty half-space, where
// they are isotopic to the short chord across the cut: the open curve is the closed knot.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "nodus/analysis/knot.hpp"

namespace nodus::analysis {
namespace {

using Vec3 = Eigen::Vector3d;
using Curve = std::vector<Vec3>;
using Polynomial = std::vector<std::int64_t>;
constexpr double kPi = std::numbers::pi;

/// A closed knot K(t), t in [0, 2 pi], its derivative, and a parameter t0 where the plane through K(t0)
/// with unit normal `normal` supports it (the knot lies on the side of `normal`, touching only at K(t0)).
struct ClosedKnot {
  std::function<Vec3(double)> position;
  std::function<Vec3(double)> derivative;
  double t0 = 0.0;
  Vec3 normal = Vec3::UnitX();
};

/// The trefoil (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t); y >= -3 with equality at t = pi only.
ClosedKnot trefoil() {
  return {[](double t) {
            return Vec3(std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t),
                        -std::sin(3 * t));
          },
          [](double t) {
            return Vec3(std::cos(t) + 4 * std::cos(2 * t), -std::sin(t) + 4 * std::sin(2 * t),
                        -3 * std::cos(3 * t));
          },
          kPi, Vec3::UnitY()};
}

/// The figure-eight knot ((2 + cos 2t) cos 3t, (2 + cos 2t) sin 3t, sin 4t); x <= 3, equal at t = 0 only.
ClosedKnot figure_eight() {
  return {[](double t) {
            return Vec3((2 + std::cos(2 * t)) * std::cos(3 * t), (2 + std::cos(2 * t)) * std::sin(3 * t),
                        std::sin(4 * t));
          },
          [](double t) {
            const double r = 2 + std::cos(2 * t), dr = -2 * std::sin(2 * t);
            return Vec3(dr * std::cos(3 * t) - 3 * r * std::sin(3 * t),
                        dr * std::sin(3 * t) + 3 * r * std::cos(3 * t), 4 * std::cos(4 * t));
          },
          0.0, -Vec3::UnitX()};
}

/// The torus knot T(p, q) ((2 + cos qt) cos pt, (2 + cos qt) sin pt, -sin qt): p turns about the z axis,
/// q about the core circle; x <= 3, equal only where cos qt = cos pt = 1, at t = 0 for coprime p, q.
ClosedKnot torus_knot(int p, int q) {
  return {[p, q](double t) {
            const double r = 2 + std::cos(q * t);
            return Vec3(r * std::cos(p * t), r * std::sin(p * t), -std::sin(q * t));
          },
          [p, q](double t) {
            const double r = 2 + std::cos(q * t), dr = -q * std::sin(q * t);
            return Vec3(dr * std::cos(p * t) - p * r * std::sin(p * t),
                        dr * std::sin(p * t) + p * r * std::cos(p * t), -q * std::cos(q * t));
          },
          0.0, -Vec3::UnitX()};
}

/// Unit direction of the tails: in the supporting plane, normal to the tangent at the cut.
Vec3 tail_direction(const ClosedKnot& k) {
  return k.normal.cross(k.derivative(k.t0)).normalized();
}

/// The knot cut open: `samples` points from K(t0 + delta) to K(t0 + 2 pi - delta), delta half a step.
Curve knot_arc(const ClosedKnot& k, int samples) {
  const double delta = kPi / samples;
  Curve arc;
  for (int i = 0; i < samples; ++i)
    arc.push_back(k.position(k.t0 + delta + (2 * kPi - 2 * delta) * i / (samples - 1)));
  return arc;
}

/// Appends a straight run from `from` (excluded) to `to` (included) in `steps` steps; by value, as `from` is
/// often curve.back().
void append_line(Curve& curve, Vec3 from, Vec3 to, int steps) {
  for (int i = 1; i <= steps; ++i) curve.push_back(from + (to - from) * static_cast<double>(i) / steps);
}

/// The open knot: `tail_samples` points on a straight tail of length `tail` leading into the first cut end
/// A along -e (from A + tail e), the arc from A to the other cut end B, and `tail_samples` points on a tail
/// leaving B along -e (to B - tail e): samples + 2 tail_samples points.
Curve open_knot(const ClosedKnot& k, int samples, int tail_samples, double tail) {
  const Curve arc = knot_arc(k, samples);
  const Vec3 e = tail_direction(k);
  Curve curve;
  for (int i = 0; i < tail_samples; ++i)
    curve.push_back(arc.front() + tail * (1.0 - double(i) / tail_samples) * e);
  curve.insert(curve.end(), arc.begin(), arc.end());
  append_line(curve, arc.back(), arc.back() - tail * e, tail_samples);
  return curve;
}

Curve transformed(const Curve& curve, const Eigen::Matrix3d& linear, const Vec3& shift) {
  Curve out;
  for (const Vec3& p : curve) out.push_back(linear * p + shift);
  return out;
}

Eigen::Matrix3d random_rotation(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// Integer polynomials, t^0 first, for the torus-knot formula.
Polynomial multiply(const Polynomial& a, const Polynomial& b) {
  Polynomial c(a.size() + b.size() - 1, 0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

/// a / b for a monic b dividing a.
Polynomial divide(Polynomial a, const Polynomial& b) {
  Polynomial q(a.size() - b.size() + 1, 0);
  for (std::size_t k = q.size(); k-- > 0;) {
    q[k] = a[k + b.size() - 1];
    for (std::size_t j = 0; j < b.size(); ++j) a[k + j] -= q[k] * b[j];
  }
  for (std::int64_t v : a) EXPECT_EQ(v, 0) << "inexact division";
  return q;
}

Polynomial t_power_minus_one(int n) {
  Polynomial p(static_cast<std::size_t>(n) + 1, 0);
  p.front() = -1;
  p.back() = 1;
  return p;
}

/// Delta of T(p, q) = (t^pq - 1)(t - 1) / ((t^p - 1)(t^q - 1)).
Polynomial torus_alexander(int p, int q) {
  return divide(multiply(t_power_minus_one(p * q), t_power_minus_one(1)),
                multiply(t_power_minus_one(p), t_power_minus_one(q)));
}

const Polynomial kTrefoil{1, -1, 1};
const Polynomial kFigureEight{1, -3, 1};

// --- Alexander polynomial ---------------------------------------------------------------------------------

TEST(KnotInvariant, UnknottedCurves) {
  Curve straight;
  for (int i = 0; i <= 100; ++i) straight.push_back(Vec3(0.3, -0.2, 0.1) * i);
  Curve arc;  // 300 degrees of a circle of radius 2
  for (int i = 0; i <= 200; ++i) {
    const double a = 5.0 / 3.0 * kPi * i / 200;
    arc.push_back(Vec3(2 * std::cos(a), 2 * std::sin(a), 0));
  }
  Curve helix;  // four loose turns: radius 1, pitch 0.5
  for (int i = 0; i <= 400; ++i) {
    const double a = 8 * kPi * i / 400;
    helix.push_back(Vec3(std::cos(a), std::sin(a), 0.5 * a / (2 * kPi)));
  }
  for (const Curve* c : {&straight, &arc, &helix}) {
    const KnotInvariant k = knot_invariant(*c);
    EXPECT_TRUE(k.is_unknot()) << k.to_string();
    EXPECT_FALSE(k.is_trefoil());
    EXPECT_EQ(k.determinant(), 1);
    EXPECT_EQ(k.to_string(), "1");
  }
  // Seen nearly along its axis the helix shows many crossings; Delta stays 1.
  const KnotInvariant along_axis = knot_invariant(helix, Vec3(0.05, 0.03, 1.0));
  EXPECT_GE(along_axis.crossings, 6);
  EXPECT_TRUE(along_axis.is_unknot()) << along_axis.to_string();
  // A two-point curve is a segment.
  EXPECT_TRUE(knot_invariant(Curve{Vec3(0, 0, 0), Vec3(1, 2, 3)}).is_unknot());
}

TEST(KnotInvariant, TorusKnotsOfTypeOneAreUnknots) {
  // T(3, 1) and T(1, 3) look knotted (the former winds three times about the axis) but are trivial.
  for (auto [p, q] : {std::pair{3, 1}, std::pair{1, 3}, std::pair{4, 1}}) {
    const KnotInvariant k = knot_invariant(open_knot(torus_knot(p, q), 400, 20, 20.0));
    EXPECT_TRUE(k.is_unknot()) << "T(" << p << ", " << q << "): " << k.to_string();
  }
}

TEST(KnotInvariant, SpikesThatRetraceThemselvesAreIgnored) {
  // A beam element folded back on itself leaves a spike p, q, p in the node polyline, at an end or inside. A
  // spike bounds a triangle of zero area, so the knot type is that of the curve without it; left in, the
  // spike at the end makes every projection degenerate (its closure runs back along it).
  Curve curve = open_knot(trefoil(), 400, 50, 30.0);
  const Vec3 end = curve.back(), before = curve[curve.size() - 2];
  curve.push_back(end + 0.5 * (end - before));  // out along the curve ...
  curve.push_back(end + 1e-9 * Vec3::UnitX());  // ... and back onto the end, to 1e-9
  const std::size_t middle = curve.size() / 2;
  const Vec3 m = curve[middle];
  curve.insert(curve.begin() + static_cast<std::ptrdiff_t>(middle) + 1, {m + Vec3(0.0, 0.0, 0.5), m});
  const KnotInvariant k = knot_invariant(curve);
  EXPECT_TRUE(k.is_trefoil()) << k.to_string();
}

TEST(KnotInvariant, OpenOverhandKnotIsATrefoil) {
  const Curve curve = open_knot(trefoil(), 400, 50, 30.0);
  const KnotInvariant k = knot_invariant(curve);
  EXPECT_EQ(k.coefficients, kTrefoil);
  EXPECT_TRUE(k.is_trefoil());
  EXPECT_FALSE(k.is_unknot());
  EXPECT_EQ(k.to_string(), "1 - t + t^2");
  EXPECT_EQ(k.determinant(), 3);
  EXPECT_GE(k.crossings, 3);  // the crossing number of the trefoil
  EXPECT_NEAR(k.direction.norm(), 1.0, 1e-12);

  // Its mirror image: Alexander cannot tell the handedness.
  const KnotInvariant mirror =
      knot_invariant(transformed(curve, Eigen::Vector3d(1, 1, -1).asDiagonal(), Vec3::Zero()));
  EXPECT_EQ(mirror.coefficients, kTrefoil);
}

TEST(KnotInvariant, TrefoilUnderRigidMotionScaleAndProjectionDirection) {
  const Curve curve = open_knot(trefoil(), 300, 30, 30.0);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Curve moved = transformed(curve, random_rotation(seed), Vec3(seed * 3.0, -7.0, 2.5));
    EXPECT_EQ(knot_invariant(moved).coefficients, kTrefoil) << "rotation " << seed;
  }
  // Millimetres to metres and far from the origin: the tolerances are relative.
  EXPECT_EQ(knot_invariant(transformed(curve, 1e-3 * Eigen::Matrix3d::Identity(), Vec3(1e3, -2e3, 5e2)))
                .coefficients,
            kTrefoil);
  // Projections chosen by hand, each with its own diagram.
  for (const Vec3& d : {Vec3(0.3, 0.5, 0.8), Vec3(-0.7, 0.2, 0.4), Vec3(0.1, -0.9, 0.35),
                        Vec3(0.62, 0.05, -0.21), Vec3(0.2, 1.0, 0.1), Vec3(0.05, 0.07, 1.0)}) {
    const KnotInvariant k = knot_invariant(curve, d);
    EXPECT_EQ(k.coefficients, kTrefoil) << d.transpose();
    EXPECT_GE(k.crossings, 3);
    EXPECT_NEAR(k.direction.dot(d.normalized()), 1.0, 1e-12);
  }
}

TEST(KnotInvariant, TrefoilFineAndCoarseSampling) {
  const Curve coarse = open_knot(trefoil(), 60, 20, 20.0);  // 99 points
  ASSERT_LE(coarse.size(), 110u);
  EXPECT_EQ(knot_invariant(coarse).coefficients, kTrefoil);
  const Curve fine = open_knot(trefoil(), 5000, 500, 30.0);
  EXPECT_EQ(knot_invariant(fine).coefficients, kTrefoil);
}

TEST(KnotInvariant, RodSizedTrefoil) {
  // 601 nodes of a rod about 20 mm long: a 0.4 mm-scale trefoil (11.6 mm of rod) between 4.2 mm tails.
  const Curve curve =
      transformed(open_knot(trefoil(), 401, 100, 10.5), 0.4 * Eigen::Matrix3d::Identity(), Vec3::Zero());
  ASSERT_EQ(curve.size(), 601u);
  auto start = std::chrono::steady_clock::now();
  const KnotInvariant k = knot_invariant(curve);
  const double knot_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(k.is_trefoil()) << k.to_string();

  // Its self-distance beyond 1 mm along the rod lies between two brute-force bounds: the closest vertices
  // >= 1 mm apart along it (feasible points: an upper bound) and the closest boxes of two segments holding
  // such a pair of points (a lower bound).
  std::vector<double> s{0.0};
  for (std::size_t i = 1; i < curve.size(); ++i) s.push_back(s.back() + (curve[i] - curve[i - 1]).norm());
  const double S = 1.0;
  start = std::chrono::steady_clock::now();
  const SelfDistance d = min_self_distance(curve, s, S);
  const double distance_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  double upper = std::numeric_limits<double>::infinity(), lower = upper;
  for (std::size_t i = 0; i < curve.size(); ++i)
    for (std::size_t j = i + 1; j < curve.size(); ++j)
      if (s[j] - s[i] >= S) upper = std::min(upper, (curve[j] - curve[i]).norm());
  for (std::size_t i = 0; i + 1 < curve.size(); ++i)
    for (std::size_t j = i; j + 1 < curve.size(); ++j)
      if (s[j + 1] - s[i] >= S) {
        const Eigen::AlignedBox3d bi = Eigen::AlignedBox3d(curve[i]).extend(curve[i + 1]);
        const Eigen::AlignedBox3d bj = Eigen::AlignedBox3d(curve[j]).extend(curve[j + 1]);
        lower = std::min(lower, std::sqrt(bi.squaredExteriorDistance(bj)));
      }
  EXPECT_LE(d.distance, upper + 1e-12);
  EXPECT_GE(d.distance, lower - 1e-12);
  EXPECT_GE(d.s2 - d.s1, S - 1e-9);
  RecordProperty("knot_invariant_601_nodes_ms", std::to_string(knot_ms));
  RecordProperty("min_self_distance_601_nodes_ms", std::to_string(distance_ms));
  std::printf("601 nodes: knot_invariant %.2f ms (%d crossings), min_self_distance %.2f ms (%.4f mm)\n",
              knot_ms, k.crossings, distance_ms, d.distance);
}

TEST(KnotInvariant, FigureEight) {
  const Curve curve = open_knot(figure_eight(), 500, 30, 30.0);
  const KnotInvariant k = knot_invariant(curve);
  EXPECT_EQ(k.coefficients, kFigureEight);
  EXPECT_EQ(k.to_string(), "1 - 3t + t^2");
  EXPECT_EQ(k.determinant(), 5);
  EXPECT_FALSE(k.is_trefoil());
  EXPECT_EQ(knot_invariant(transformed(curve, random_rotation(11), Vec3(1, 2, 3))).coefficients,
            kFigureEight);
  EXPECT_EQ(
      knot_invariant(transformed(curve, Eigen::Vector3d(-1, 1, 1).asDiagonal(), Vec3::Zero())).coefficients,
      kFigureEight);
}

TEST(KnotInvariant, TorusKnots) {
  // Sanity of the reference formula against Rolfsen's table.
  EXPECT_EQ(torus_alexander(2, 3), kTrefoil);
  EXPECT_EQ(torus_alexander(2, 5), (Polynomial{1, -1, 1, -1, 1}));
  EXPECT_EQ(torus_alexander(3, 4), (Polynomial{1, -1, 0, 1, 0, -1, 1}));  // 8_19
  // Up to degree 20 (T(5, 6): 25 to 56 crossings depending on the projection).
  for (auto [p, q] : {std::pair{2, 3}, std::pair{3, 2}, std::pair{2, 5}, std::pair{2, 7}, std::pair{3, 4},
                      std::pair{3, 5}, std::pair{4, 5}, std::pair{5, 6}}) {
    const KnotInvariant k = knot_invariant(open_knot(torus_knot(p, q), 150 * (p + q), 20, 20.0));
    EXPECT_EQ(k.coefficients, torus_alexander(p, q)) << "T(" << p << ", " << q << "): " << k.to_string();
  }
  const KnotInvariant cinquefoil = knot_invariant(open_knot(torus_knot(2, 5), 800, 20, 20.0));
  EXPECT_EQ(cinquefoil.to_string(), "1 - t + t^2 - t^3 + t^4");
  EXPECT_EQ(cinquefoil.determinant(), 5);
}

TEST(KnotInvariant, EveryProjectionOfATorusKnotAgrees) {
  // 8_19 = T(3, 4) seen from 20 random directions: different diagrams, one polynomial.
  const Curve curve = open_knot(torus_knot(3, 4), 700, 20, 20.0);
  std::mt19937 rng(7);
  std::normal_distribution<double> n;
  for (int k = 0; k < 20; ++k) {
    const Vec3 d(n(rng), n(rng), n(rng));
    const KnotInvariant knot = knot_invariant(curve, d);
    EXPECT_EQ(knot.coefficients, torus_alexander(3, 4))
        << d.transpose() << ", " << knot.crossings << " crossings";
    EXPECT_GE(knot.crossings, 8);  // the crossing number of 8_19
  }
}

TEST(KnotInvariant, GrannyKnotIsTheProductOfTwoTrefoils) {
  // Two trefoils tied one after the other on one rod: the connected sum, Delta = (1 - t + t^2)^2. The second
  // is the first moved along -e; the connector runs in the supporting plane, which both knots only touch.
  const ClosedKnot k = trefoil();
  const Vec3 e = tail_direction(k);
  const Curve arc = knot_arc(k, 400);
  Curve curve{arc.front() + 30.0 * e};
  append_line(curve, curve.back(), arc.front(), 30);
  curve.insert(curve.end(), arc.begin() + 1, arc.end());
  const Vec3 shift = -12.0 * e;
  append_line(curve, arc.back(), arc.front() + shift, 20);
  for (std::size_t i = 1; i < arc.size(); ++i) curve.push_back(arc[i] + shift);
  append_line(curve, curve.back(), curve.back() - 30.0 * e, 30);
  const KnotInvariant granny = knot_invariant(curve);
  EXPECT_EQ(granny.coefficients, multiply(kTrefoil, kTrefoil));
  EXPECT_EQ(granny.to_string(), "1 - 2t + 3t^2 - 2t^3 + t^4");
  EXPECT_EQ(granny.determinant(), 9);
}

TEST(KnotInvariant, ClosedInputIsUsedAsIs) {
  // A closed trefoil (last vertex repeating the first) needs no closure.
  const ClosedKnot k = trefoil();
  Curve closed;
  for (int i = 0; i <= 300; ++i) closed.push_back(k.position(2 * kPi * i / 300));
  EXPECT_TRUE(knot_invariant(closed).is_trefoil());
}

TEST(KnotInvariant, DegenerateInputs) {
  EXPECT_THROW(knot_invariant(Curve{}), std::invalid_argument);
  EXPECT_THROW(knot_invariant(Curve{Vec3(1, 2, 3), Vec3(1, 2, 3)}), std::invalid_argument);
  EXPECT_THROW(knot_invariant(Curve{Vec3(0, 0, 0), Vec3(1, 0, 0)}, Vec3::Zero()), std::invalid_argument);
  // A curve through itself: a figure "8" in a plane, its two lobes crossing at the origin.
  Curve eight;
  for (int i = 0; i <= 200; ++i) {
    const double a = 2 * kPi * i / 200 + 0.1;
    eight.push_back(Vec3(std::sin(a), std::sin(a) * std::cos(a), 0));
  }
  EXPECT_THROW(knot_invariant(eight), std::runtime_error);
  // Seen along its tails, the open trefoil's tails are points: that projection is degenerate.
  EXPECT_THROW(knot_invariant(open_knot(trefoil(), 100, 10, 10.0), tail_direction(trefoil())),
               std::runtime_error);
}

TEST(KnotInvariant, ToStringAndDeterminant) {
  KnotInvariant k;
  EXPECT_EQ(k.to_string(), "1");
  k.coefficients = {2, -5, 2};  // 6_1
  EXPECT_EQ(k.to_string(), "2 - 5t + 2t^2");
  EXPECT_EQ(k.determinant(), 9);
  k.coefficients = {1, -3, 3, -3, 1};  // 6_2
  EXPECT_EQ(k.to_string(), "1 - 3t + 3t^2 - 3t^3 + t^4");
  EXPECT_EQ(k.determinant(), 11);
}

// --- Self-distance ----------------------------------------------------------------------------------------

/// Arc lengths of the polyline itself (exact for straight pieces).
std::vector<double> chord_lengths(const Curve& c) {
  std::vector<double> s{0.0};
  for (std::size_t i = 1; i < c.size(); ++i) s.push_back(s.back() + (c[i] - c[i - 1]).norm());
  return s;
}

TEST(MinSelfDistance, SkewLinesJoinedFarAway) {
  // Line 1 along x at z = 0, line 2 along y at z = h, joined at their far ends. The closest points are the
  // two origins, which are no nodes (40 nodes per line). Near the corners the connector makes 45 degrees
  // with the lines: points >= S apart there are >= 2 (S / 2) sin(22.5 deg) = 0.38 S = 3.1 apart.
  const double L = 10.0, h = 0.7, S = 8.0;
  Curve c{Vec3(-L, 0, 0)};
  append_line(c, c.back(), Vec3(L, 0, 0), 39);
  append_line(c, c.back(), Vec3(0, -L, h), 29);
  append_line(c, c.back(), Vec3(0, L, h), 39);
  const std::vector<double> s = chord_lengths(c);
  const SelfDistance d = min_self_distance(c, s, S);
  EXPECT_NEAR(d.distance, h, 1e-12);
  const double connector = std::sqrt(2 * L * L + h * h);
  EXPECT_NEAR(d.s1, L, 1e-9);
  EXPECT_NEAR(d.s2, 2 * L + connector + L, 1e-9);
}

TEST(MinSelfDistance, Hairpin) {
  // Two parallel legs g apart (length 5) joined by a half circle of diameter g. With S above half the U's
  // length the only pairs left face each other across the gap.
  const double g = 0.5, leg = 5.0, S = 3 * g;
  Curve c;
  std::vector<double> s;
  for (int i = 0; i <= 50; ++i) {
    c.emplace_back(leg * i / 50, 0, 0);
    s.push_back(leg * i / 50);
  }
  for (int i = 1; i <= 20; ++i) {
    const double a = kPi * i / 20;
    c.emplace_back(leg + 0.5 * g * std::sin(a), 0.5 * g - 0.5 * g * std::cos(a), 0);
    s.push_back(leg + 0.5 * g * a);
  }
  for (int i = 1; i <= 50; ++i) {
    c.emplace_back(leg - leg * i / 50, g, 0);
    s.push_back(leg + kPi * 0.5 * g + leg * i / 50);
  }
  const SelfDistance d = min_self_distance(c, s, S);
  EXPECT_NEAR(d.distance, g, 1e-12);
  EXPECT_GE(d.s2 - d.s1, S - 1e-12);
  EXPECT_LE(d.s1, leg);                          // on the first leg
  EXPECT_GE(d.s2, leg + kPi * 0.5 * g - 1e-12);  // on the second
  // Lower the separation below the U and the U's own chords come out: the chord of the half circle for
  // S = g / 2 is 2 (g / 2) sin(S / g) (up to the polygon's sagitta).
  EXPECT_NEAR(min_self_distance(c, s, 0.5 * g).distance, g * std::sin(0.5), 1e-3);
}

TEST(MinSelfDistance, CircleArcChord) {
  // 270 degrees of a circle of radius r: points s apart along it are 2 r sin(s / 2r) apart, increasing in s
  // up to pi r, and the ends are sqrt(2) r apart; with S = r the minimum is the chord of S.
  const double r = 2.0, S = r;
  Curve c;
  std::vector<double> s;
  for (int i = 0; i <= 1500; ++i) {
    const double a = 1.5 * kPi * i / 1500;
    c.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    s.push_back(r * a);
  }
  const SelfDistance d = min_self_distance(c, s, S);
  EXPECT_NEAR(d.distance, 2 * r * std::sin(S / (2 * r)), 1e-5);  // sagitta r (dphi)^2 / 8 = 2.5e-6
  EXPECT_NEAR(d.s2 - d.s1, S, 1e-9);
}

TEST(MinSelfDistance, HelixSuccessiveTurns) {
  // Helix of radius a, rise c per radian: points phi apart (in angle) are D(phi) apart,
  // D^2 = 2 a^2 (1 - cos phi) + c^2 phi^2. Beyond half a turn the minimum is near one turn, just below the
  // pitch 2 pi c, where a^2 sin phi + c^2 phi = 0 (solved here by Newton's method).
  const double a = 1.0, pitch = 0.3, c = pitch / (2 * kPi), speed = std::sqrt(a * a + c * c);
  double phi = 2 * kPi;
  for (int it = 0; it < 50; ++it)
    phi -= (a * a * std::sin(phi) + c * c * phi) / (a * a * std::cos(phi) + c * c);
  const double reference = std::sqrt(2 * a * a * (1 - std::cos(phi)) + c * c * phi * phi);
  ASSERT_LT(reference, pitch - 2e-4);  // a real difference to the pitch, well above the tolerance below
  Curve curve;
  std::vector<double> s;
  for (int i = 0; i <= 3000; ++i) {
    const double t = 6 * kPi * i / 3000;
    curve.emplace_back(a * std::cos(t), a * std::sin(t), c * t);
    s.push_back(speed * t);
  }
  const SelfDistance d = min_self_distance(curve, s, kPi * speed);
  EXPECT_NEAR(d.distance, reference, 2e-5);
  EXPECT_NEAR((d.s2 - d.s1) / speed, phi, 0.02);
  // Run backwards: the same distance.
  Curve reversed(curve.rbegin(), curve.rend());
  std::vector<double> s_reversed;
  for (auto it = s.rbegin(); it != s.rend(); ++it) s_reversed.push_back(s.back() - *it);
  EXPECT_NEAR(min_self_distance(reversed, s_reversed, kPi * speed).distance, d.distance, 1e-12);
}

TEST(MinSelfDistance, StraightLineAndLimits) {
  Curve c;
  std::vector<double> s;
  for (int i = 0; i <= 10; ++i) {
    c.emplace_back(i, 0, 0);
    s.push_back(i);
  }
  // On a straight line, points S apart along it are S apart.
  const SelfDistance d = min_self_distance(c, s, 2.5);
  EXPECT_NEAR(d.distance, 2.5, 1e-12);
  EXPECT_NEAR(d.s2 - d.s1, 2.5, 1e-12);
  EXPECT_NEAR(min_self_distance(c, s, 0.3).distance, 0.3, 1e-12);  // within one segment
  EXPECT_EQ(min_self_distance(c, s, 0.0).distance, 0.0);
  EXPECT_TRUE(std::isinf(min_self_distance(c, s, 20.0).distance));
  EXPECT_THROW(min_self_distance(c, std::vector<double>(3, 0.0), 1.0), std::invalid_argument);
  s[4] = s[3];
  EXPECT_THROW(min_self_distance(c, s, 1.0), std::invalid_argument);
}

// --- Distance between two fibres; the mean centreline of a yarn ------------------------------------------

TEST(MinDistanceBetween, SkewLines) {
  // Line 1 along x at z = 0, line 2 along y at z = h; the closest points are the origins, which are no
  // vertices (5 and 7 segments).
  const double L = 3.0, h = 0.4;
  Curve a{Vec3(-L, 0, 0)}, b{Vec3(0, -L, h)};
  append_line(a, a.back(), Vec3(L, 0, 0), 5);
  append_line(b, b.back(), Vec3(0, L, h), 7);
  const CurveDistance d = min_distance_between(a, chord_lengths(a), b, chord_lengths(b));
  EXPECT_NEAR(d.distance, h, 1e-14);
  EXPECT_NEAR(d.s1, L, 1e-12);
  EXPECT_NEAR(d.s2, L, 1e-12);
  const CurveDistance swapped = min_distance_between(b, chord_lengths(b), a, chord_lengths(a));
  EXPECT_EQ(swapped.distance, d.distance);
  EXPECT_NEAR(swapped.s1, L, 1e-12);
}

TEST(MinDistanceBetween, TwoHelicesOfAThreePlyYarn) {
  // Fibres k = 0, 1 of a 3-ply yarn: helices (c t, a cos(t + phi_k), a sin(t + phi_k)), phi_k = 2 pi k / 3.
  // Points t1 on fibre 0 and t2 on fibre 1 are D apart, D^2 = c^2 d^2 + 2 a^2 (1 - cos(d - 2 pi / 3)) with
  // d = t1 - t2: at d = 0 the distance sqrt(3) a across the section, and a little less at the d where
  // c^2 d + a^2 sin(d - 2 pi / 3) = 0 (Newton's method).
  const double a = 0.065, c = 2.0 / (2 * kPi), phi = 2 * kPi / 3, speed = std::sqrt(a * a + c * c);
  double d = 0.0;
  for (int it = 0; it < 50; ++it)
    d -= (c * c * d + a * a * std::sin(d - phi)) / (c * c + a * a * std::cos(d - phi));
  const double reference = std::sqrt(c * c * d * d + 2 * a * a * (1 - std::cos(d - phi)));
  ASSERT_LT(reference, std::sqrt(3.0) * a - 1e-4);  // a real difference, well above the tolerance below
  const auto helix = [&](double phase) {
    Curve curve;
    std::vector<double> s;
    for (int i = 0; i <= 3000; ++i) {
      const double t = 6 * kPi * i / 3000;
      curve.emplace_back(c * t, a * std::cos(t + phase), a * std::sin(t + phase));
      s.push_back(speed * t);
    }
    return std::pair{curve, s};
  };
  const auto [c0, s0] = helix(0.0);
  const auto [c1, s1] = helix(phi);
  const CurveDistance found = min_distance_between(c0, s0, c1, s1);
  // The node polylines cut inside the helices by at most kappa ds^2 / 8 = 2e-7 mm.
  EXPECT_NEAR(found.distance, reference, 1e-6);
  EXPECT_NEAR((found.s1 - found.s2) / speed, d, 0.01);
}

TEST(MeanCurve, ThreeFibresAroundATrefoil) {
  // Three fibres at 120 degrees about the trefoil K, r away in its normal planes: each fibre is a trefoil
  // too, and their mean is K (the three offsets sum to zero).
  const ClosedKnot knot = trefoil();
  const Vec3 axis = Vec3(0.3, 0.5, 0.8).normalized();  // never along K' (checked)
  const double r = 0.1;
  const int n = 600;
  std::vector<Curve> fibres(3);
  Curve centre;
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * kPi * i / n;
    const Vec3 tangent = knot.derivative(t).normalized();
    ASSERT_GT(tangent.cross(axis).norm(), 0.1);
    const Vec3 u = tangent.cross(axis).normalized(), v = tangent.cross(u);
    centre.push_back(knot.position(t));
    for (int k = 0; k < 3; ++k) {
      const double angle = 2 * kPi * k / 3 + 3 * t;  // the fibres also wind about K
      fibres[static_cast<std::size_t>(k)].push_back(knot.position(t) +
                                                    r * (std::cos(angle) * u + std::sin(angle) * v));
    }
  }
  const Curve mean = mean_curve(fibres);
  ASSERT_EQ(mean.size(), centre.size());
  for (std::size_t i = 0; i < mean.size(); ++i) EXPECT_LT((mean[i] - centre[i]).norm(), 1e-14) << i;
  EXPECT_TRUE(knot_invariant(mean).is_trefoil());
  for (const Curve& fibre : fibres) EXPECT_TRUE(knot_invariant(fibre).is_trefoil());
  EXPECT_THROW(mean_curve({}), std::invalid_argument);
  EXPECT_THROW(mean_curve({centre, Curve(centre.begin(), centre.end() - 1)}), std::invalid_argument);
}

// --- Beam centreline --------------------------------------------------------------------------------------

TEST(BeamCentreline, NodesOfOneBeamInOrder) {
  model::Model m;
  beam::BeamDefinition a;
  a.name = "a";
  a.length = 20.0;
  a.radius = 0.1;
  a.elements = 4;
  a.material = {4000.0, 0.3};
  beam::BeamDefinition b = a;
  b.name = "b";
  b.length = 6.0;
  b.elements = 3;
  b.start = Vec3(1, 2, 3);
  b.direction = Vec3::UnitY();
  b.director1 = Vec3::UnitZ();
  m.add_beam(a);
  m.add_beam(b);
  // Beam b bent into a helix in the state, directors left as they are.
  Eigen::VectorXd x = m.reference();
  const beam::Beam& beam_b = m.beam(1);
  for (int i = 0; i < beam_b.num_nodes(); ++i) {
    const double t = beam_b.abscissa(i);
    x.segment<3>(beam::kNodeDofs * beam_b.node(i)) = Vec3(std::cos(t), std::sin(t), 0.1 * t);
  }
  const Centreline ca = beam_centreline(m, x, 0);
  ASSERT_EQ(ca.points.size(), 9u);
  ASSERT_EQ(ca.arc_length.size(), 9u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR((ca.points[i] - Vec3(2.5 * i, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(ca.arc_length[i], 2.5 * i);
  }
  const Centreline cb = beam_centreline(m, x, 1);
  ASSERT_EQ(cb.points.size(), 7u);
  for (int i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(cb.arc_length[i], 1.0 * i);
    EXPECT_NEAR((cb.points[i] - Vec3(std::cos(1.0 * i), std::sin(1.0 * i), 0.1 * i)).norm(), 0.0, 1e-12);
  }
  EXPECT_TRUE(knot_invariant(cb.points).is_unknot());
  EXPECT_NEAR(min_self_distance(ca.points, ca.arc_length, 5.0).distance, 5.0, 1e-12);  // straight
  EXPECT_THROW(beam_centreline(m, Eigen::VectorXd::Zero(5), 0), std::invalid_argument);
  EXPECT_THROW(beam_centreline(m, x, 2), std::out_of_range);
  EXPECT_THROW(beam_centreline(m, x, 0, 0), std::invalid_argument);

  // Subdivided: the quadratic interpolation of each element. Nodes on the parabola y = s^2 / 20, z = 0
  // along beam a (x = s): every interpolated point lies on it too, since the interpolation is exact for
  // quadratics, at arc lengths 20 / (4 * 5) apart.
  for (int i = 0; i < m.beam(0).num_nodes(); ++i) {
    const double s = m.beam(0).abscissa(i);
    x.segment<3>(beam::kNodeDofs * m.beam(0).node(i)) = Vec3(s, s * s / 20.0, 0.0);
  }
  const Centreline fine = beam_centreline(m, x, 0, 5);
  ASSERT_EQ(fine.points.size(), 21u);
  for (std::size_t k = 0; k < fine.points.size(); ++k) {
    const double s = 1.0 * static_cast<double>(k);
    EXPECT_NEAR(fine.arc_length[k], s, 1e-12);
    EXPECT_NEAR((fine.points[k] - Vec3(s, s * s / 20.0, 0.0)).norm(), 0.0, 1e-12) << k;
  }
}

}  // namespace
}  // namespace nodus::analysis
