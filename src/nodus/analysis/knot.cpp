#include "nodus/analysis/knot.hpp"

#include "nodus/beam/shape_functions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <Eigen/Geometry>

namespace nodus::analysis {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
__extension__ typedef unsigned __int128 Uint128;
__extension__ typedef __int128 Int128;

/// Tolerance of the projection, relative to the curve's bounding radius.
constexpr double kRelativeTolerance = 1e-10;
/// Radius of the sphere the closure runs on, in bounding radii.
constexpr double kClosureRadius = 4.0;
/// Largest angle between two successive closure vertices on that sphere [rad].
constexpr double kClosureStep = 10.0 * std::numbers::pi / 180.0;
/// Number of candidate projection directions.
constexpr int kDirections = 24;

// ---------------------------------------------------------------------------------------------------------
// The closed polygon.

struct Ball {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// The curve prepared for projection: consecutive repeated vertices removed.
struct PreparedCurve {
  std::vector<Vec3> points;
  Ball ball;             ///< centre: length-weighted centroid; radius: largest vertex distance from it
  bool closed = false;   ///< the last input vertex repeated the first (dropped from `points`)
  double tolerance = 0;  ///< kRelativeTolerance * ball.radius [mm]
};

PreparedCurve prepare(const std::vector<Vec3>& curve) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : curve) box.extend(p);
  const double merge = curve.empty() ? 0.0 : kRelativeTolerance * box.diagonal().norm();
  PreparedCurve out;
  for (const Vec3& p : curve)
    if (out.points.empty() || (p - out.points.back()).norm() > merge) out.points.push_back(p);
  // A spike that retraces itself (p[i+2] back on p[i], to 1e-6 of its length) bounds a triangle of (nearly)
  // zero area, which no other strand can pass: removing p[i+1] and p[i+2] changes nothing to the knot. A beam
  // element folded back on itself leaves such spikes (docs/model.md); left in, they make every projection
  // degenerate.
  for (std::size_t i = 0; i + 2 < out.points.size();) {
    const double arm = (out.points[i + 1] - out.points[i]).norm();
    if ((out.points[i + 2] - out.points[i]).norm() <= std::max(merge, 1e-6 * arm)) {
      out.points.erase(out.points.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                       out.points.begin() + static_cast<std::ptrdiff_t>(i) + 3);
      if (i > 0) --i;
    } else {
      ++i;
    }
  }
  if (out.points.size() < 2) throw std::invalid_argument("knot_invariant: fewer than two distinct vertices");
  if (out.points.size() > 3 && (out.points.back() - out.points.front()).norm() <= merge) {
    out.points.pop_back();
    out.closed = true;
  }
  double length = 0.0;
  Vec3 moment = Vec3::Zero();
  for (std::size_t i = 0; i + 1 < out.points.size(); ++i) {
    const double l = (out.points[i + 1] - out.points[i]).norm();
    length += l;
    moment += 0.5 * l * (out.points[i] + out.points[i + 1]);
  }
  out.ball.centre = moment / length;
  for (const Vec3& p : out.points) out.ball.radius = std::max(out.ball.radius, (p - out.ball.centre).norm());
  out.tolerance = kRelativeTolerance * out.ball.radius;
  return out;
}

/// Unit direction in which the curve leaves through its end vertex `end`: away from the centre, or along the
/// end tangent when the end lies (nearly) at the centre.
Vec3 outward(const Vec3& end, const Vec3& neighbour, const Ball& ball) {
  const Vec3 radial = end - ball.centre;
  if (radial.norm() > 1e-3 * ball.radius) return radial.normalized();
  return (end - neighbour).normalized();
}

/// Appends the points of the arc of the sphere (centre, rho) from unit direction a, turning by theta about
/// the unit axis n (n orthogonal to a): a excluded, the far end included, steps of at most kClosureStep.
void append_arc(const Vec3& a, const Vec3& n, double theta, const Vec3& centre, double rho,
                std::vector<Vec3>& out) {
  const int steps = static_cast<int>(std::ceil(std::abs(theta) / kClosureStep));
  const Vec3 w = n.cross(a);
  for (int k = 1; k <= steps; ++k) {
    const double phi = theta * k / steps;
    out.push_back(centre + rho * (std::cos(phi) * a + std::sin(phi) * w));
  }
}

/// Appends the meridian from unit `from` to unit `to`, its normalised projection on the equator (the great
/// circle normal to the projection direction); nothing if `from` lies on the equator.
void append_meridian(const Vec3& from, const Vec3& to, const Vec3& centre, double rho,
                     std::vector<Vec3>& out) {
  const Vec3 n = from.cross(to);
  const double s = n.norm();
  if (s < 1e-14) return;  // already there (from . to > 0 on a meridian)
  append_arc(from, n / s, std::atan2(s, from.dot(to)), centre, rho, out);
}

/// The closed polygon: the curve, then the closure for projection direction d (unit) in the order
/// end -> far point -> meridian -> equator -> meridian -> far point of the start. Empty if an end leaves
/// along d (its meridian is undefined).
std::vector<Vec3> close_far_away(const PreparedCurve& curve, const Vec3& d) {
  const std::vector<Vec3>& p = curve.points;
  if (curve.closed) return p;
  const Vec3& c = curve.ball.centre;
  const double rho = kClosureRadius * curve.ball.radius;
  const Vec3 u_start = outward(p.front(), p[1], curve.ball);
  const Vec3 u_end = outward(p.back(), p[p.size() - 2], curve.ball);
  const Vec3 e_start = u_start - u_start.dot(d) * d;
  const Vec3 e_end = u_end - u_end.dot(d) * d;
  if (e_start.norm() < 1e-6 || e_end.norm() < 1e-6) return {};
  const Vec3 a = e_end.normalized(), b = e_start.normalized();
  std::vector<Vec3> closed = p;
  closed.push_back(c + rho * u_end);
  append_meridian(u_end, a, c, rho, closed);
  append_arc(a, d, std::atan2(a.cross(b).dot(d), a.dot(b)), c, rho, closed);
  append_meridian(b, u_start, c, rho, closed);
  return closed;
}

// ---------------------------------------------------------------------------------------------------------
// Crossings of the projection.

/// A crossing of the projected closed polygon; positions along the polygon are segment index + parameter.
struct Crossing {
  double over = 0.0;   ///< position of the over-strand (the one further along the projection direction)
  double under = 0.0;  ///< position of the under-strand
  int sign = 0;        ///< +1 or -1: sign of (over direction x under direction) . d
};

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

/// The crossings of `polygon` (closed) projected along unit d; empty optional if the projection is
/// degenerate at tolerance `tol` [mm].
std::optional<std::vector<Crossing>> find_crossings(const std::vector<Vec3>& polygon, const Vec3& d,
                                                    const Vec3& origin, double tol) {
  const int m = static_cast<int>(polygon.size());
  const Vec3 e1 = d.unitOrthogonal();
  const Vec3 e2 = d.cross(e1);  // (e1, e2, d) right-handed
  std::vector<Vec2> q(polygon.size());
  std::vector<double> h(polygon.size());
  for (int k = 0; k < m; ++k) {
    const Vec3 r = polygon[k] - origin;
    q[k] = Vec2(r.dot(e1), r.dot(e2));
    h[k] = r.dot(d);
  }
  const auto next = [m](int k) { return k + 1 == m ? 0 : k + 1; };
  std::vector<Eigen::AlignedBox2d> boxes(polygon.size());
  for (int k = 0; k < m; ++k) {
    if ((q[next(k)] - q[k]).norm() < tol) return std::nullopt;  // segment seen end-on
    boxes[k] = Eigen::AlignedBox2d(q[k]).extend(q[next(k)]);
  }
  std::vector<int> order(polygon.size());
  for (int k = 0; k < m; ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return boxes[a].min().x() < boxes[b].min().x(); });

  std::vector<Crossing> crossings;
  for (int ia = 0; ia < m; ++ia) {
    const int i = order[ia];
    for (int ja = ia + 1; ja < m; ++ja) {
      const int j = order[ja];
      if (boxes[j].min().x() > boxes[i].max().x() + tol) break;
      if (boxes[j].min().y() > boxes[i].max().y() + tol || boxes[i].min().y() > boxes[j].max().y() + tol)
        continue;
      if (next(i) == j || next(j) == i) continue;  // neighbours share a vertex
      const Vec2 &p0 = q[i], &p1 = q[next(i)], &q0 = q[j], &q1 = q[next(j)];
      if (std::min({distance_to_segment(p0, q0, q1), distance_to_segment(p1, q0, q1),
                    distance_to_segment(q0, p0, p1), distance_to_segment(q1, p0, p1)}) < tol)
        return std::nullopt;  // a vertex on (or next to) another segment
      const Vec2 r = p1 - p0, s = q1 - q0;
      const double o1 = cross(r, q0 - p0), o2 = cross(r, q1 - p0);
      const double o3 = cross(s, p0 - q0), o4 = cross(s, p1 - q0);
      if ((o1 > 0.0) == (o2 > 0.0) || (o3 > 0.0) == (o4 > 0.0)) continue;
      const double a = o3 / (o3 - o4), b = o1 / (o1 - o2);  // parameters along i and j
      const double hi = h[i] + a * (h[next(i)] - h[i]), hj = h[j] + b * (h[next(j)] - h[j]);
      if (std::abs(hi - hj) < tol) return std::nullopt;  // the strands (nearly) meet in space
      const bool i_over = hi > hj;
      const double sign = i_over ? cross(r, s) : cross(s, r);
      crossings.push_back({i_over ? i + a : j + b, i_over ? j + b : i + a, sign > 0.0 ? 1 : -1});
    }
  }
  // Two crossings at one point of a segment would leave their order along it undefined.
  std::vector<double> positions;
  for (const Crossing& c : crossings) {
    positions.push_back(c.over);
    positions.push_back(c.under);
  }
  std::sort(positions.begin(), positions.end());
  for (std::size_t k = 1; k < positions.size(); ++k) {
    const int segment = static_cast<int>(positions[k - 1]);
    if (static_cast<int>(positions[k]) == segment &&
        (positions[k] - positions[k - 1]) * (q[next(segment)] - q[segment]).norm() < tol)
      return std::nullopt;
  }
  return crossings;
}

// ---------------------------------------------------------------------------------------------------------
// Exact Alexander polynomial: determinants over Z_p at integer points, interpolation, Chinese remainders.

using Residue = std::uint64_t;

/// Primes just below 2^62: products of two residues fit into 128 bits, p1 p2 > 2^123.
constexpr std::array<Residue, 3> kPrimes{4611686018427387847ULL, 4611686018427387817ULL,
                                         4611686018427387787ULL};

Residue mul_mod(Residue a, Residue b, Residue p) {
  return static_cast<Residue>(Uint128(a) * b % p);
}
Residue sub_mod(Residue a, Residue b, Residue p) {
  return a >= b ? a - b : a + (p - b);
}
Residue to_mod(std::int64_t v, Residue p) {
  const Residue r = static_cast<Residue>(v < 0 ? -v : v) % p;
  return v < 0 && r != 0 ? p - r : r;
}
Residue pow_mod(Residue a, Residue e, Residue p) {
  Residue result = 1;
  for (; e > 0; e >>= 1, a = mul_mod(a, a, p))
    if (e & 1) result = mul_mod(result, a, p);
  return result;
}
/// Inverse of a != 0 modulo the prime p (Fermat).
Residue inv_mod(Residue a, Residue p) {
  return pow_mod(a, p - 2, p);
}

/// Determinant of the size x size matrix `a` (row-major) over Z_p, by Gaussian elimination.
Residue det_mod(std::vector<Residue> a, int size, Residue p) {
  Residue det = 1;
  for (int k = 0; k < size; ++k) {
    int pivot = k;
    while (pivot < size && a[pivot * size + k] == 0) ++pivot;
    if (pivot == size) return 0;
    if (pivot != k) {
      for (int c = 0; c < size; ++c) std::swap(a[pivot * size + c], a[k * size + c]);
      det = sub_mod(0, det, p);
    }
    det = mul_mod(det, a[k * size + k], p);
    const Residue inv = inv_mod(a[k * size + k], p);
    for (int r = k + 1; r < size; ++r) {
      const Residue f = mul_mod(a[r * size + k], inv, p);
      if (f == 0) continue;
      for (int c = k; c < size; ++c)
        a[r * size + c] = sub_mod(a[r * size + c], mul_mod(f, a[k * size + c], p), p);
    }
  }
  return det;
}

/// Linear polynomial c0 + c1 t.
using Linear = std::array<std::int64_t, 2>;

/// Coefficients over Z_p of the polynomial of degree < size(x) through (x_k, y_k) (Newton's form).
std::vector<Residue> interpolate_mod(const std::vector<Residue>& x, std::vector<Residue> y, Residue p) {
  const std::size_t n = x.size();
  for (std::size_t j = 1; j < n; ++j)
    for (std::size_t k = n - 1; k >= j; --k)
      y[k] = mul_mod(sub_mod(y[k], y[k - 1], p), inv_mod(sub_mod(x[k], x[k - j], p), p), p);
  std::vector<Residue> poly(n, 0);
  for (std::size_t k = n; k-- > 0;) {  // poly = poly (t - x_k) + y_k
    for (std::size_t c = n - 1; c > 0; --c) poly[c] = sub_mod(poly[c - 1], mul_mod(poly[c], x[k], p), p);
    poly[0] = sub_mod(y[k], mul_mod(poly[0], x[k], p), p);
  }
  return poly;
}

/// Coefficients (t^0 first) of the determinant of the size x size matrix of linear polynomials `a`, modulo p.
std::vector<Residue> det_polynomial_mod(const std::vector<Linear>& a, int size, Residue p) {
  const int points = size + 1;  // degree <= size
  std::vector<Residue> x(points), y(points);
  std::vector<Residue> values(a.size());
  for (int k = 0; k < points; ++k) {
    x[k] = static_cast<Residue>(k + 2);
    for (std::size_t e = 0; e < a.size(); ++e)
      values[e] = (to_mod(a[e][0], p) + mul_mod(to_mod(a[e][1], p), x[k], p)) % p;
    y[k] = det_mod(values, size, p);
  }
  return interpolate_mod(x, y, p);
}

/// The determinant of a matrix of linear polynomials with integer coefficients, exactly. Each coefficient is
/// at most the product of the rows' L1 norms of coefficients in magnitude, here at most 4^size: up to
/// size 61 (< 2^122 < p1 p2 / 2) the first two primes determine it; the third must agree (a check of the
/// arithmetic there, the safeguard beyond).
std::vector<std::int64_t> det_polynomial(const std::vector<Linear>& a, int size) {
  std::array<std::vector<Residue>, 3> r;
  for (std::size_t k = 0; k < kPrimes.size(); ++k) r[k] = det_polynomial_mod(a, size, kPrimes[k]);
  const Residue p1 = kPrimes[0], p2 = kPrimes[1], p3 = kPrimes[2];
  const Residue p1_inv = inv_mod(p1 % p2, p2);
  const Uint128 product = Uint128(p1) * p2;
  std::vector<std::int64_t> coefficients(r[0].size());
  for (std::size_t c = 0; c < coefficients.size(); ++c) {
    const Residue k = mul_mod(sub_mod(r[1][c] % p2, r[0][c] % p2, p2), p1_inv, p2);
    const Uint128 x = Uint128(r[0][c]) + Uint128(p1) * k;  // in [0, p1 p2)
    const Int128 v = x > product / 2 ? -Int128(product - x) : Int128(x);
    const bool fits =
        v <= std::numeric_limits<std::int64_t>::max() && v >= -std::numeric_limits<std::int64_t>::max();
    if (!fits || to_mod(static_cast<std::int64_t>(v), p3) != r[2][c])
      throw std::runtime_error("knot_invariant: Alexander polynomial coefficient out of range");
    coefficients[c] = static_cast<std::int64_t>(v);
  }
  return coefficients;
}

/// The Alexander polynomial of the diagram, normalised; empty optional if the result is not that of a knot
/// (|Delta(1)| != 1 or not palindromic: an undetected degeneracy of the projection).
std::optional<std::vector<std::int64_t>> alexander_polynomial(const std::vector<Crossing>& crossings) {
  const int n = static_cast<int>(crossings.size());
  if (n <= 1) return std::vector<std::int64_t>{1};
  // Arcs run from one under-passage to the next: arc j leaves under-passage j (in the order along the curve).
  struct Event {
    double position;
    int crossing;
    bool under;
  };
  std::vector<Event> events;
  for (int c = 0; c < n; ++c) {
    events.push_back({crossings[c].over, c, false});
    events.push_back({crossings[c].under, c, true});
  }
  std::sort(events.begin(), events.end(),
            [](const Event& a, const Event& b) { return a.position < b.position; });
  std::vector<int> under_rank(n), over_arc(n);
  int seen = 0;
  for (const Event& e : events) {
    if (e.under)
      under_rank[e.crossing] = seen++;
    else
      over_arc[e.crossing] = (seen + n - 1) % n;  // before the first under-passage: the last arc
  }
  // Fox derivatives of the Wirtinger relation x_b = x_o^-e x_a x_o^e (a in, b out, o over, e the sign), with
  // every generator mapped to t and the row multiplied by a unit: e = +1: (t - 1, 1, -t), e = -1:
  // (1 - t, t, -1) at (o, a, b). Delete the last row and column.
  const int size = n - 1;
  std::vector<Linear> matrix(static_cast<std::size_t>(size * size), Linear{0, 0});
  for (int c = 0; c < size; ++c) {
    const int b = under_rank[c], a = (b + n - 1) % n, o = over_arc[c];
    const bool positive = crossings[c].sign > 0;
    std::array<Linear, 3> entries = positive
                                        ? std::array<Linear, 3>{Linear{-1, 1}, Linear{1, 0}, Linear{0, -1}}
                                        : std::array<Linear, 3>{Linear{1, -1}, Linear{0, 1}, Linear{-1, 0}};
    const std::array<int, 3> columns{o, a, b};
    for (int k = 0; k < 3; ++k) {
      if (columns[k] == size) continue;
      Linear& m = matrix[static_cast<std::size_t>(c * size + columns[k])];
      m[0] += entries[k][0];
      m[1] += entries[k][1];
    }
  }
  std::vector<std::int64_t> delta = det_polynomial(matrix, size);

  // Normalise: lowest power t^0, lowest coefficient positive.
  while (!delta.empty() && delta.back() == 0) delta.pop_back();
  if (delta.empty()) return std::nullopt;
  const auto first = std::find_if(delta.begin(), delta.end(), [](std::int64_t v) { return v != 0; });
  delta.erase(delta.begin(), first);
  if (delta.front() < 0)
    for (std::int64_t& v : delta) v = -v;
  Int128 at_one = 0;
  for (std::int64_t v : delta) at_one += v;
  if (at_one != 1 && at_one != -1) return std::nullopt;
  if (!std::equal(delta.begin(), delta.end(), delta.rbegin())) return std::nullopt;
  return delta;
}

/// 24 directions spread over a hemisphere (Fibonacci lattice, offset so that none is a coordinate axis).
std::vector<Vec3> candidate_directions() {
  std::vector<Vec3> directions;
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < kDirections; ++k) {
    const double z = 1.0 - (k + 0.5) / kDirections;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = k * golden_angle + 0.3;
    directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return directions;
}

/// The crossings of the curve closed for direction d, if the projection along d is not degenerate.
std::optional<std::vector<Crossing>> project(const PreparedCurve& curve, const Vec3& d) {
  const std::vector<Vec3> polygon = close_far_away(curve, d);
  if (polygon.size() < 3) return std::nullopt;
  return find_crossings(polygon, d, curve.ball.centre, curve.tolerance);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------

std::int64_t KnotInvariant::determinant() const {
  Int128 value = 0;
  for (std::size_t k = 0; k < coefficients.size(); ++k)
    value += (k % 2 == 0 ? 1 : -1) * Int128(coefficients[k]);
  return static_cast<std::int64_t>(value < 0 ? -value : value);
}

std::string KnotInvariant::to_string() const {
  std::string out;
  for (std::size_t k = 0; k < coefficients.size(); ++k) {
    const std::int64_t c = coefficients[k];
    if (c == 0) continue;
    const std::uint64_t magnitude = c < 0 ? 0 - static_cast<std::uint64_t>(c) : static_cast<std::uint64_t>(c);
    if (out.empty())
      out += c < 0 ? "-" : "";
    else
      out += c < 0 ? " - " : " + ";
    if (k == 0 || magnitude != 1) out += std::to_string(magnitude);
    if (k >= 1) out += "t";
    if (k >= 2) out += "^" + std::to_string(k);
  }
  return out.empty() ? "0" : out;
}

bool KnotInvariant::is_unknot() const {
  return coefficients == std::vector<std::int64_t>{1};
}

bool KnotInvariant::is_trefoil() const {
  return coefficients == std::vector<std::int64_t>{1, -1, 1};
}

KnotInvariant knot_invariant(const std::vector<Eigen::Vector3d>& open_curve) {
  const PreparedCurve curve = prepare(open_curve);
  struct Candidate {
    Vec3 direction;
    std::vector<Crossing> crossings;
  };
  std::vector<Candidate> candidates;
  for (const Vec3& d : candidate_directions())
    if (auto crossings = project(curve, d)) candidates.push_back({d, std::move(*crossings)});
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.crossings.size() < b.crossings.size();
  });
  for (const Candidate& c : candidates)
    if (auto delta = alexander_polynomial(c.crossings))
      return {std::move(*delta), static_cast<int>(c.crossings.size()), c.direction};
  throw std::runtime_error("knot_invariant: every projection is degenerate (does the curve touch itself?)");
}

KnotInvariant knot_invariant(const std::vector<Eigen::Vector3d>& open_curve,
                             const Eigen::Vector3d& direction) {
  if (!(direction.norm() > 0.0)) throw std::invalid_argument("knot_invariant: zero projection direction");
  const PreparedCurve curve = prepare(open_curve);
  const Vec3 d = direction.normalized();
  if (auto crossings = project(curve, d))
    if (auto delta = alexander_polynomial(*crossings))
      return {std::move(*delta), static_cast<int>(crossings->size()), d};
  throw std::runtime_error("knot_invariant: the projection along the given direction is degenerate");
}

// ---------------------------------------------------------------------------------------------------------

namespace {

/// Closest points of segments p0 + a (p1 - p0) and q0 + b (q1 - q0), a, b in [0, 1]
/// [Ericson, Real-Time Collision Detection, 2005, Sect. 5.1.9].
std::array<double, 2> closest_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kPoint = std::numeric_limits<double>::min();  // a segment of length zero
  if (a <= kPoint && e <= kPoint) return {0.0, 0.0};
  if (a <= kPoint) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= kPoint) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2);
  const double denominator = a * e - b * b;  // >= 0, zero when parallel
  double s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

/// The bounding box of each segment of the polyline `curve`.
std::vector<Eigen::AlignedBox3d> segment_boxes(const std::vector<Eigen::Vector3d>& curve) {
  std::vector<Eigen::AlignedBox3d> boxes(curve.size() < 2 ? 0 : curve.size() - 1);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    boxes[i] = Eigen::AlignedBox3d(curve[i]).extend(curve[i + 1]);
  return boxes;
}

}  // namespace

SelfDistance min_self_distance(const std::vector<Eigen::Vector3d>& curve,
                               const std::vector<double>& arc_length, double separation) {
  if (curve.size() != arc_length.size())
    throw std::invalid_argument("min_self_distance: curve and arc_length differ in size");
  if (!(separation >= 0.0)) throw std::invalid_argument("min_self_distance: separation must be >= 0");
  for (std::size_t i = 1; i < arc_length.size(); ++i)
    if (!(arc_length[i] > arc_length[i - 1]))
      throw std::invalid_argument("min_self_distance: arc_length must be strictly increasing");
  SelfDistance best{std::numeric_limits<double>::infinity(), 0.0, 0.0};
  const std::vector<Eigen::AlignedBox3d> boxes = segment_boxes(curve);
  const std::size_t segments = boxes.size();
  const auto& s = arc_length;

  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3 &p0 = curve[i], &p1 = curve[i + 1];
    const double li = s[i + 1] - s[i];
    // Same segment: points `separation` apart along it.
    if (li >= separation) {
      const double distance = (p1 - p0).norm() * separation / li;
      if (distance < best.distance) best = {distance, s[i], s[i] + separation};
    }
    for (std::size_t j = i + 1; j < segments; ++j) {
      if (s[j + 1] - s[i] < separation) continue;  // every pair of points closer along the curve
      if (boxes[i].squaredExteriorDistance(boxes[j]) >= best.distance * best.distance) continue;
      const Vec3 &q0 = curve[j], &q1 = curve[j + 1];
      const double lj = s[j + 1] - s[j];
      auto [a, b] = closest_parameters(p0, p1, q0, q1);
      if (s[j] + b * lj - (s[i] + a * li) < separation) {
        // The constrained minimum lies on the line s2 - s1 = separation: b = b0 + a li / lj, with a and b
        // in [0, 1]; the squared distance is a convex quadratic in a along it.
        const double b0 = (separation - (s[j] - s[i])) / lj, slope = li / lj;
        const double a_lo = std::max(0.0, -b0 / slope), a_hi = std::min(1.0, (1.0 - b0) / slope);
        if (a_lo > a_hi) continue;
        const Vec3 w0 = p0 - q0 - b0 * (q1 - q0), v = (p1 - p0) - slope * (q1 - q0);
        const double vv = v.squaredNorm();
        a = vv > 0.0 ? std::clamp(-w0.dot(v) / vv, a_lo, a_hi) : a_lo;
        b = std::clamp(b0 + slope * a, 0.0, 1.0);
      }
      const double distance = (p0 + a * (p1 - p0) - q0 - b * (q1 - q0)).norm();
      if (distance < best.distance) best = {distance, s[i] + a * li, s[j] + b * lj};
    }
  }
  return best;
}

CurveDistance min_distance_between(const std::vector<Eigen::Vector3d>& curve1,
                                   const std::vector<double>& arc_length1,
                                   const std::vector<Eigen::Vector3d>& curve2,
                                   const std::vector<double>& arc_length2) {
  if (curve1.size() != arc_length1.size() || curve2.size() != arc_length2.size())
    throw std::invalid_argument("min_distance_between: a curve and its arc lengths differ in size");
  CurveDistance best{std::numeric_limits<double>::infinity(), 0.0, 0.0};
  const std::vector<Eigen::AlignedBox3d> boxes1 = segment_boxes(curve1), boxes2 = segment_boxes(curve2);
  for (std::size_t i = 0; i < boxes1.size(); ++i) {
    for (std::size_t j = 0; j < boxes2.size(); ++j) {
      if (boxes1[i].squaredExteriorDistance(boxes2[j]) >= best.distance * best.distance) continue;
      const Vec3 &p0 = curve1[i], &p1 = curve1[i + 1], &q0 = curve2[j], &q1 = curve2[j + 1];
      const auto [a, b] = closest_parameters(p0, p1, q0, q1);
      const double distance = (p0 + a * (p1 - p0) - q0 - b * (q1 - q0)).norm();
      if (distance < best.distance)
        best = {distance, arc_length1[i] + a * (arc_length1[i + 1] - arc_length1[i]),
                arc_length2[j] + b * (arc_length2[j + 1] - arc_length2[j])};
    }
  }
  return best;
}

std::vector<Eigen::Vector3d> mean_curve(const std::vector<std::vector<Eigen::Vector3d>>& fibres) {
  if (fibres.empty()) throw std::invalid_argument("mean_curve: no fibres");
  std::vector<Eigen::Vector3d> mean(fibres.front().size(), Eigen::Vector3d::Zero());
  for (const auto& fibre : fibres) {
    if (fibre.size() != mean.size())
      throw std::invalid_argument("mean_curve: the fibres differ in their numbers of vertices");
    for (std::size_t k = 0; k < mean.size(); ++k) mean[k] += fibre[k];
  }
  for (Eigen::Vector3d& p : mean) p /= static_cast<double>(fibres.size());
  return mean;
}

Centreline beam_centreline(const model::Model& model, const Eigen::VectorXd& state, int beam,
                           int segments_per_element) {
  if (state.size() != model.num_dofs())
    throw std::invalid_argument("beam_centreline: state size differs from the model's number of unknowns");
  if (segments_per_element < 1) throw std::invalid_argument("beam_centreline: segments_per_element < 1");
  const beam::Beam& b = model.beam(beam);
  const auto node = [&](int i) -> Eigen::Vector3d { return state.segment<3>(model.node_dof(b.node(i))); };
  Centreline out;
  out.points.push_back(node(0));
  out.arc_length.push_back(b.abscissa(0));
  for (int e = 0; e < b.num_elements(); ++e) {
    const Eigen::Vector3d r0 = node(2 * e), r1 = node(2 * e + 1), r2 = node(2 * e + 2);
    for (int k = 1; k <= segments_per_element; ++k) {
      const double u = static_cast<double>(k) / segments_per_element;  // fraction of the element
      const beam::QuadraticShape n = beam::quadratic_shape(2.0 * u - 1.0);
      out.points.push_back(n.value[0] * r0 + n.value[1] * r1 + n.value[2] * r2);
      out.arc_length.push_back(b.abscissa(2 * e) + u * b.element_length());
    }
  }
  return out;
}

}  // namespace nodus::analysis
