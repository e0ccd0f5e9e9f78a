#include "nodus/model/yarn_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nodus::model {

namespace {

/// Relative tolerance under which two squared distances (or second moments, or yarn radii) count as equal.
constexpr double kTieTolerance = 1e-9;
/// The turns of roving 0's pattern tried by yarn_layout: 2 pi i / kPatternAngles.
constexpr int kPatternAngles = 720;

/// Angle of `p` in [0, 2 pi).
double angle_of(const Vec2& p) {
  const double a = std::atan2(p.y(), p.x());
  return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
}

Vec2 rotated(const Vec2& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

/// Sum of |p - mean|^2 over `points` [mm^2].
double second_moment(const std::vector<Vec2>& points) {
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double sum = 0.0;
  for (const Vec2& p : points) sum += (p - mean).squaredNorm();
  return sum;
}

/// The `n` lattice points nearest to `centre`: whole shells of equal distance, then, from the shell that
/// does not fit whole, one point at a time the one that keeps the second moment smallest (the smallest
/// angle about `centre` on a tie).
std::vector<Vec2> nearest_points(const std::vector<Vec2>& lattice, const Vec2& centre, int n,
                                 double spacing) {
  std::vector<Vec2> sorted = lattice;
  const auto key = [&centre](const Vec2& p) { return (p - centre).squaredNorm(); };
  std::sort(sorted.begin(), sorted.end(), [&](const Vec2& a, const Vec2& b) {
    const double da = key(a), db = key(b);
    if (std::abs(da - db) > kTieTolerance * spacing * spacing) return da < db;
    return angle_of(a - centre) < angle_of(b - centre);
  });
  std::vector<Vec2> chosen;
  std::size_t next = 0;
  while (static_cast<int>(chosen.size()) < n) {
    std::size_t shell_end = next;
    while (shell_end < sorted.size() &&
           std::abs(key(sorted[shell_end]) - key(sorted[next])) <= kTieTolerance * spacing * spacing)
      ++shell_end;
    if (static_cast<int>(chosen.size() + (shell_end - next)) <= n) {
      chosen.insert(chosen.end(), sorted.begin() + static_cast<std::ptrdiff_t>(next),
                    sorted.begin() + static_cast<std::ptrdiff_t>(shell_end));
      next = shell_end;
      continue;
    }
    std::vector<Vec2> shell(sorted.begin() + static_cast<std::ptrdiff_t>(next),
                            sorted.begin() + static_cast<std::ptrdiff_t>(shell_end));
    while (static_cast<int>(chosen.size()) < n) {
      std::size_t best = 0;
      double best_moment = 0.0;
      for (std::size_t i = 0; i < shell.size(); ++i) {
        std::vector<Vec2> trial = chosen;
        trial.push_back(shell[i]);
        const double moment = second_moment(trial);
        // The shell is in angle order: the first of equal moments has the smallest angle.
        if (i == 0 || moment < best_moment - kTieTolerance * spacing * spacing) {
          best = i;
          best_moment = moment;
        }
      }
      chosen.push_back(shell[best]);
      shell.erase(shell.begin() + static_cast<std::ptrdiff_t>(best));
    }
  }
  return chosen;
}

std::vector<Vec2> hexagonal_pattern(int n, double d) {
  const int reach = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))) + 2;
  const Vec2 a1(d, 0.0), a2(0.5 * d, 0.5 * std::sqrt(3.0) * d);
  std::vector<Vec2> lattice;
  for (int i = -reach; i <= reach; ++i) {
    for (int j = -reach; j <= reach; ++j) lattice.push_back(i * a1 + j * a2);
  }
  // A lattice point, the centroid of a lattice triangle, the midpoint of a lattice bond.
  const Vec2 centres[] = {Vec2::Zero(), (a1 + a2) / 3.0, a1 / 2.0};
  std::vector<Vec2> best;
  double best_moment = 0.0;
  Vec2 best_centre = Vec2::Zero();
  for (const Vec2& centre : centres) {
    std::vector<Vec2> points = nearest_points(lattice, centre, n, d);
    const double moment = second_moment(points);
    if (best.empty() || moment < best_moment - kTieTolerance * d * d) {
      best = std::move(points);
      best_moment = moment;
      best_centre = centre;
    }
  }
  // Deterministic order: by distance from the lattice centre, then by angle about it.
  std::sort(best.begin(), best.end(), [&](const Vec2& a, const Vec2& b) {
    const double da = (a - best_centre).squaredNorm(), db = (b - best_centre).squaredNorm();
    if (std::abs(da - db) > kTieTolerance * d * d) return da < db;
    return angle_of(a - best_centre) < angle_of(b - best_centre);
  });
  return best;
}

std::vector<Vec2> ring_pattern(int n, double d) {
  if (n == 1) return {Vec2::Zero()};
  const double radius = d / (2.0 * std::sin(std::numbers::pi / n));
  std::vector<Vec2> points;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * std::numbers::pi * j / n;
    points.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return points;
}

/// The rovings at distance `rho` for the pattern turned by `phi`.
std::vector<std::vector<Vec2>> place(const std::vector<Vec2>& pattern, int m, double rho, double phi) {
  std::vector<std::vector<Vec2>> fibres(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    const double theta = 2.0 * std::numbers::pi * k / m;
    const Vec2 centre = rho * Vec2(std::cos(theta), std::sin(theta));
    for (const Vec2& p : pattern)
      fibres[static_cast<std::size_t>(k)].push_back(centre + rotated(p, theta + phi));
  }
  return fibres;
}

/// The smallest rho beyond which no two fibres of different rovings are closer than d (yarn_layout).
double roving_distance(const std::vector<Vec2>& pattern, int m, double phi, double d) {
  if (m == 1) return 0.0;
  const std::vector<std::vector<Vec2>> turned = place(pattern, m, 0.0, phi);  // Q(theta_k + phi) p_j
  double rho = 0.0;
  for (int k = 0; k < m; ++k) {
    for (int l = k + 1; l < m; ++l) {
      const double tk = 2.0 * std::numbers::pi * k / m, tl = 2.0 * std::numbers::pi * l / m;
      const Vec2 w = Vec2(std::cos(tk), std::sin(tk)) - Vec2(std::cos(tl), std::sin(tl));
      const double ww = w.squaredNorm();
      for (const Vec2& a : turned[static_cast<std::size_t>(k)]) {
        for (const Vec2& b : turned[static_cast<std::size_t>(l)]) {
          const Vec2 v = a - b;
          const double wv = w.dot(v);
          const double discriminant = wv * wv - ww * (v.squaredNorm() - d * d);
          if (discriminant <= 0.0) continue;  // never closer than d
          rho = std::max(rho, (-wv + std::sqrt(discriminant)) / ww);
        }
      }
    }
  }
  return rho;
}

}  // namespace

std::vector<Vec2> roving_pattern(RovingPacking packing, int fibres, double spacing) {
  if (fibres < 1 || !(spacing > 0.0) || !std::isfinite(spacing))
    throw std::invalid_argument("roving_pattern: needs fibres >= 1 and a finite spacing > 0");
  std::vector<Vec2> points = packing == RovingPacking::hexagonal ? hexagonal_pattern(fibres, spacing)
                                                                 : ring_pattern(fibres, spacing);
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  for (Vec2& p : points) p -= mean;
  return points;
}

YarnLayout yarn_layout(RovingPacking packing, int rovings, int fibres_per_roving, double spacing) {
  if (rovings < 1) throw std::invalid_argument("yarn_layout: needs rovings >= 1");
  const std::vector<Vec2> pattern = roving_pattern(packing, fibres_per_roving, spacing);
  YarnLayout best;
  double best_radius = 0.0;
  for (int i = 0; i < kPatternAngles; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / kPatternAngles;
    const double rho = roving_distance(pattern, rovings, phi, spacing);
    std::vector<std::vector<Vec2>> fibres = place(pattern, rovings, rho, phi);
    double radius = 0.0;
    for (const auto& roving : fibres) {
      for (const Vec2& p : roving) radius = std::max(radius, p.norm());
    }
    if (i == 0 || radius < best_radius - kTieTolerance * spacing) {
      best = {std::move(fibres), rho, phi};
      best_radius = radius;
    }
  }
  return best;
}

}  // namespace nodus::model
