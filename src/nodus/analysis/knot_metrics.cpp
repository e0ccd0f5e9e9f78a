#include "nodus/analysis/knot_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

#include <Eigen/SVD>

#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/contact_table.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Throws std::invalid_argument unless the centreline has at least two nodes, as many arc lengths as
/// points, and arc lengths that do not decrease.
void check_centreline(const Centreline& centreline, std::string_view context) {
  if (centreline.points.size() != centreline.arc_length.size())
    throw std::invalid_argument(std::string(context) +
                                ": centreline points and arc lengths differ in number");
  if (centreline.points.size() < 2)
    throw std::invalid_argument(std::string(context) + ": centreline with fewer than two nodes");
  if (!std::is_sorted(centreline.arc_length.begin(), centreline.arc_length.end()))
    throw std::invalid_argument(std::string(context) + ": centreline arc lengths decrease");
}

/// Component `c` of the centreline at arc length `x`, as numpy.interp computes it (same operations, so
/// that the two agree to rounding).
double interpolate(const Centreline& centreline, int c, double x) {
  const std::vector<double>& xp = centreline.arc_length;
  const auto fp = [&](std::size_t j) { return centreline.points[j][c]; };
  const std::size_t last = xp.size() - 1;
  if (x > xp[last]) return fp(last);
  if (x < xp[0]) return fp(0);
  if (x == xp[last]) return fp(last);
  // j with xp[j] <= x < xp[j + 1]
  const std::size_t j = static_cast<std::size_t>(std::upper_bound(xp.begin(), xp.end(), x) - xp.begin()) - 1;
  if (xp[j] == x) return fp(j);
  const double slope = (fp(j + 1) - fp(j)) / (xp[j + 1] - xp[j]);
  return slope * (x - xp[j]) + fp(j);
}

Eigen::Vector3d point_at(const Centreline& centreline, double s) {
  return {interpolate(centreline, 0, s), interpolate(centreline, 1, s), interpolate(centreline, 2, s)};
}

/// numpy's median: the middle value, or the mean of the two middle values; NaN-free input.
double median(std::vector<double> values) {
  const std::size_t n = values.size();
  std::sort(values.begin(), values.end());
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
}

/// Largest value, NaN if one is (numpy's max); `empty` without values.
double nan_max(const Eigen::VectorXd& values, double empty) {
  if (values.size() == 0) return empty;
  double best = values[0];
  for (double v : values) {
    if (std::isnan(v)) return kNaN;
    best = std::max(best, v);
  }
  return best;
}

/// The distinct zone indices, increasing (numpy.unique).
std::vector<int> unique_zones(const ContactTable& contact) {
  const std::set<int> zones(contact.zone.begin(), contact.zone.end());
  return {zones.begin(), zones.end()};
}

/// The abscissa_i and abscissa_j of the elements in contact (normal_force > 0).
std::vector<double> touched_abscissas(const ContactTable& contact) {
  std::vector<double> s;
  for (std::size_t k = 0; k < contact.size(); ++k)
    if (contact.normal_force[k] > 0.0) s.push_back(contact.abscissa_i[k]);
  for (std::size_t k = 0; k < contact.size(); ++k)
    if (contact.normal_force[k] > 0.0) s.push_back(contact.abscissa_j[k]);
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// The contact table.

void ContactTable::resize(std::size_t n) {
  const auto m = static_cast<Eigen::Index>(n);
  for (Eigen::VectorXi* v : {&zone, &beam_i, &beam_j, &state}) v->resize(m);
  for (Eigen::VectorXd* v : {&zeta, &abscissa_i, &abscissa_j, &gap, &normal_force, &tangential_force})
    v->resize(m);
  particle_i.resize(m, 3);
  particle_j.resize(m, 3);
}

void ContactTable::check() const {
  const Eigen::Index n = zone.size();
  bool same = particle_i.rows() == n && particle_j.rows() == n;
  for (const Eigen::VectorXi* v : {&beam_i, &beam_j, &state}) same = same && v->size() == n;
  for (const Eigen::VectorXd* v : {&zeta, &abscissa_i, &abscissa_j, &gap, &normal_force, &tangential_force})
    same = same && v->size() == n;
  if (!same) throw std::invalid_argument("contact table: columns of different lengths");
}

ContactTable contact_table(const contact::ContactGeometry& geometry,
                           const std::vector<simulation::ContactState>* states) {
  constexpr std::string_view kContext = "contact table";
  output::check_contact_geometry(geometry, kContext);
  output::check_contact_states(geometry, states, kContext);
  ContactTable table;
  table.resize(geometry.elements.size());
  for (std::size_t k = 0; k < geometry.elements.size(); ++k) {
    const output::ContactRow row = output::contact_row(geometry, k, states);
    const auto i = static_cast<Eigen::Index>(k);
    table.zone[i] = row.zone;
    table.beam_i[i] = row.beam_i;
    table.beam_j[i] = row.beam_j;
    table.zeta[i] = row.zeta;
    table.abscissa_i[i] = row.abscissa_i;
    table.abscissa_j[i] = row.abscissa_j;
    table.particle_i.row(i) = row.position_i.transpose();
    table.particle_j.row(i) = row.position_j.transpose();
    table.gap[i] = row.gap;
    table.normal_force[i] = row.with_forces ? row.normal_force : kNaN;
    table.tangential_force[i] = row.with_forces ? row.tangential_force : kNaN;
    table.state[i] = row.with_forces ? static_cast<int>(row.status) : kNoStatus;
  }
  return table;
}

ContactTable contact_table(const simulation::Simulation& sim) {
  const contact::ContactGeometry* geometry = sim.contact();
  if (!geometry) return {};
  return contact_table(*geometry, output::contact_states_to_write(sim));
}

ContactTable sorted_by_zone_and_zeta(const ContactTable& table, std::vector<std::size_t>* order) {
  table.check();
  std::vector<std::size_t> index(table.size());
  std::iota(index.begin(), index.end(), std::size_t{0});
  std::stable_sort(index.begin(), index.end(), [&](std::size_t a, std::size_t b) {
    const auto i = static_cast<Eigen::Index>(a), j = static_cast<Eigen::Index>(b);
    if (table.zone[i] != table.zone[j]) return table.zone[i] < table.zone[j];
    return table.zeta[i] < table.zeta[j];
  });
  ContactTable sorted;
  sorted.resize(table.size());
  for (std::size_t k = 0; k < index.size(); ++k) {
    const auto to = static_cast<Eigen::Index>(k), from = static_cast<Eigen::Index>(index[k]);
    sorted.zone[to] = table.zone[from];
    sorted.beam_i[to] = table.beam_i[from];
    sorted.beam_j[to] = table.beam_j[from];
    sorted.zeta[to] = table.zeta[from];
    sorted.abscissa_i[to] = table.abscissa_i[from];
    sorted.abscissa_j[to] = table.abscissa_j[from];
    sorted.particle_i.row(to) = table.particle_i.row(from);
    sorted.particle_j.row(to) = table.particle_j.row(from);
    sorted.gap[to] = table.gap[from];
    sorted.normal_force[to] = table.normal_force[from];
    sorted.tangential_force[to] = table.tangential_force[from];
    sorted.state[to] = table.state[from];
  }
  if (order) *order = std::move(index);
  return sorted;
}

// ---------------------------------------------------------------------------------------------------------
// The metrics.

Points centreline_at(const Centreline& centreline, const Eigen::VectorXd& s) {
  check_centreline(centreline, "centreline_at");
  Points out(s.size(), 3);
  for (Eigen::Index k = 0; k < s.size(); ++k) out.row(k) = point_at(centreline, s[k]).transpose();
  return out;
}

Points midpoints(const ContactTable& contact) {
  contact.check();
  return (contact.particle_i + contact.particle_j) / 2.0;
}

Eigen::VectorXd intermediate_abscissa(const ContactTable& contact) {
  const Points mid = midpoints(contact);
  Eigen::VectorXd abscissa = Eigen::VectorXd::Zero(mid.rows());
  double start = 0.0;
  for (int zone : unique_zones(contact)) {
    double sum = 0.0;  // cumulative length of the zone's polyline, then offset by `start` (numpy.cumsum)
    Eigen::Index previous = -1;
    for (Eigen::Index k = 0; k < mid.rows(); ++k) {
      if (contact.zone[k] != zone) continue;
      if (previous >= 0) sum += (mid.row(k) - mid.row(previous)).norm();
      abscissa[k] = start + sum;
      previous = k;
    }
    start = abscissa[previous];
  }
  return abscissa;
}

double intermediate_length(const ContactTable& contact, const Eigen::VectorXd& abscissa) {
  contact.check();
  if (abscissa.size() != contact.zone.size())
    throw std::invalid_argument("intermediate_length: one abscissa per contact element expected");
  double length = 0.0;
  for (int zone : unique_zones(contact)) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Eigen::Index k = 0; k < abscissa.size(); ++k)
      if (contact.zone[k] == zone && contact.normal_force[k] > 0.0) {
        lo = std::min(lo, abscissa[k]);
        hi = std::max(hi, abscissa[k]);
      }
    if (lo <= hi) length += hi - lo;
  }
  return length;
}

double element_spacing(const ContactTable& contact, double min_spacing) {
  contact.check();
  std::vector<double> differences;
  for (int zone : unique_zones(contact)) {
    Eigen::Index previous = -1;
    for (Eigen::Index k = 0; k < contact.zone.size(); ++k) {
      if (contact.zone[k] != zone) continue;
      if (previous >= 0)
        differences.push_back(std::abs(contact.abscissa_i[k] - contact.abscissa_i[previous]));
      previous = k;
    }
  }
  if (differences.empty()) return min_spacing;
  const double m = median(std::move(differences));
  return min_spacing > m ? min_spacing : m;  // Python's max(m, min_spacing)
}

double tail_angle(const Centreline& centreline, double s_a, double s_b, double tail_chord) {
  check_centreline(centreline, "tail_angle");
  const double s_min = centreline.arc_length.front(), s_max = centreline.arc_length.back();
  const Eigen::Vector3d chord_a =
      point_at(centreline, std::max(s_a - tail_chord, s_min)) - point_at(centreline, s_a);
  const Eigen::Vector3d chord_b =
      point_at(centreline, std::min(s_b + tail_chord, s_max)) - point_at(centreline, s_b);
  const double length_a = chord_a.norm(), length_b = chord_b.norm();
  if (length_a < 1e-12 || length_b < 1e-12) return kNaN;
  const double cosine = chord_a.dot(chord_b) / (length_a * length_b);
  return std::acos(std::clamp(cosine, -1.0, 1.0)) * (180.0 / std::numbers::pi);
}

std::optional<Interval> longest_uncovered(std::vector<double> centres, double half_width, double lo,
                                          double hi) {
  std::sort(centres.begin(), centres.end());
  std::optional<Interval> best;
  double position = lo;
  for (double c : centres) {
    const double start = c - half_width, end = c + half_width;
    if (start > position && (!best || start - position > best->length()))
      best = Interval{position, std::min(start, hi)};
    if (end > position) position = end;
    if (position >= hi) break;
  }
  if (position < hi && (!best || hi - position > best->length())) best = Interval{position, hi};
  return best;
}

double fit_circle(const Points& points) {
  if (points.rows() < 3) return kNaN;
  const Points centred = points.rowwise() - points.colwise().mean();
  const Eigen::JacobiSVD<Eigen::MatrixXd> plane(centred, Eigen::ComputeThinV);
  const Eigen::VectorXd u = centred * plane.matrixV().col(0), v = centred * plane.matrixV().col(1);
  Eigen::MatrixXd a(points.rows(), 3);
  a.col(0) = 2.0 * u;
  a.col(1) = 2.0 * v;
  a.col(2).setOnes();
  const Eigen::VectorXd rhs = u.array().square() + v.array().square();
  const Eigen::Vector3d x = a.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(rhs);
  return std::sqrt(x[2] + x[0] * x[0] + x[1] * x[1]);
}

LoopGeometry loop_geometry(const Centreline& centreline, const ContactTable& contact, double s_a, double s_b,
                           const KnotMetricsOptions& options) {
  check_centreline(centreline, "loop_geometry");
  const std::optional<Interval> loop = longest_uncovered(
      touched_abscissas(contact), element_spacing(contact, options.min_spacing) / 2.0, s_a, s_b);
  if (!loop) return {kNaN, kNaN};
  std::vector<Eigen::Index> inside;
  for (std::size_t k = 0; k < centreline.points.size(); ++k)
    if (centreline.arc_length[k] >= loop->lo && centreline.arc_length[k] <= loop->hi)
      inside.push_back(static_cast<Eigen::Index>(k));
  double radius = kNaN;
  if (static_cast<int>(inside.size()) >= options.min_loop_nodes) {
    Points points(static_cast<Eigen::Index>(inside.size()), 3);
    for (std::size_t k = 0; k < inside.size(); ++k)
      points.row(static_cast<Eigen::Index>(k)) =
          centreline.points[static_cast<std::size_t>(inside[k])].transpose();
    radius = fit_circle(points);
  }
  return {radius, loop->length()};
}

Interval knot_extent(const ContactTable& contact) {
  contact.check();
  const std::vector<double> s = touched_abscissas(contact);
  if (s.empty()) return {kNaN, kNaN};
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  return {*lo, *hi};
}

double rod_radius(const std::vector<Centreline>& centrelines, const std::vector<ContactTable>& contacts,
                  double default_radius) {
  if (centrelines.size() != contacts.size())
    throw std::invalid_argument("rod_radius: one centreline per contact table expected");
  std::vector<double> distances;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactTable& contact = contacts[k];
    contact.check();
    if (contact.size() == 0) continue;
    const Points on_axis = centreline_at(centrelines[k], contact.abscissa_i);
    for (Eigen::Index e = 0; e < on_axis.rows(); ++e)
      distances.push_back((contact.particle_i.row(e) - on_axis.row(e)).norm());
  }
  return distances.empty() ? default_radius : median(std::move(distances));
}

KnotMetrics analyse_knot(const Centreline& centreline, const ContactTable& table,
                         const KnotMetricsOptions& options) {
  check_centreline(centreline, "analyse_knot");
  std::vector<std::size_t> order;
  const ContactTable contact = sorted_by_zone_and_zeta(table, &order);
  const Eigen::VectorXd abscissa = intermediate_abscissa(contact);
  const Interval extent = knot_extent(contact);

  KnotMetrics m;
  m.zones = static_cast<int>(unique_zones(contact).size());
  m.contact_elements = static_cast<int>(contact.size());
  m.elements_in_contact = static_cast<int>((contact.normal_force.array() > 0.0).count());
  m.intermediate_length = intermediate_length(contact, abscissa);
  m.max_normal = nan_max(contact.normal_force, 0.0);
  m.total_normal = contact.normal_force.sum();
  m.max_tangential = nan_max(contact.tangential_force, 0.0);
  m.total_tangential = contact.tangential_force.sum();
  m.max_penetration = nan_max(-contact.gap, kNaN);
  m.s_a = extent.lo;
  m.s_b = extent.hi;
  if (std::isnan(extent.lo)) {
    m.tail_angle = m.loop_radius = m.loop_length = kNaN;
  } else {
    m.tail_angle = tail_angle(centreline, extent.lo, extent.hi, options.tail_chord);
    const LoopGeometry loop = loop_geometry(centreline, contact, extent.lo, extent.hi, options);
    m.loop_radius = loop.radius;
    m.loop_length = loop.length;
  }

  ReactionsTable& r = m.reactions;
  r.element = std::move(order);
  r.zone = contact.zone;
  r.zeta = contact.zeta;
  r.abscissa = abscissa;
  r.s_i = contact.abscissa_i;
  r.s_j = contact.abscissa_j;
  r.midpoint = midpoints(contact);
  r.normal = contact.normal_force;
  r.tangential = contact.tangential_force;
  r.state = contact.state;
  return m;
}

}  // namespace nodus::analysis
