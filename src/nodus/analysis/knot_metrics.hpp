#pragma once
/// Metrics of a tightened or released knot [Durville 2012, Sect. 7.2, Figs. 14, 15, 17], the numbers of
/// scripts/knot_report.py computed from memory: the contact elements as a table of columns, the extent of
/// the knot along the rod, the reactions along the intermediate geometries, the angle between the tails and
/// the loop. Same definitions and constants as knot_report.py (its functions centreline ... rod_radius and
/// analyse); units mm, N, degrees.
///
/// The contact table is a set of columns, one entry per contact element, rather than a vector of structs:
/// each column maps onto a numpy array without a copy (Eigen::Ref), as knot_report.py holds its CSV tables.

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "nodus/analysis/knot.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::simulation {
class Simulation;
}

namespace nodus::analysis {

/// n x 3 points, one per row (the memory layout of a C-ordered numpy (n, 3) array) [mm].
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Value of ContactTable::state for an element whose table was built without contact states.
inline constexpr int kNoStatus = -1;

/// The contact elements of a state as columns, entry k for element k, in the order of the rows of
/// contact_final.csv (that of the contact geometry: zones in order, each zone's elements by increasing
/// zeta). The columns knot_report.py reads from the CSV, plus the beams of each element's zone.
struct ContactTable {
  Eigen::VectorXi zone;              ///< zone index (from 0)
  Eigen::VectorXi beam_i;            ///< beam I of the zone (model index)
  Eigen::VectorXi beam_j;            ///< beam J of the zone (model index)
  Eigen::VectorXd zeta;              ///< relative abscissa on the intermediate geometry, in [0, 1]
  Eigen::VectorXd abscissa_i;        ///< reference arc length xi3 of the particle on beam I [mm]
  Eigen::VectorXd abscissa_j;        ///< reference arc length xi3 of the particle on beam J [mm]
  Points particle_i;                 ///< current position x_i of the particle on beam I [mm]
  Points particle_j;                 ///< current position x_j of the particle on beam J [mm]
  Eigen::VectorXd gap;               ///< <x_j - x_i, n> [mm], negative when the surfaces overlap
  Eigen::VectorXd normal_force;      ///< R_N [N]; NaN without contact states
  Eigen::VectorXd tangential_force;  ///< |T| [N]; NaN without contact states
  /// output::ContactStatus as int: 0 open (R_N = 0), 1 stick, 2 slip; kNoStatus without contact states.
  Eigen::VectorXi state;

  /// Number of contact elements.
  std::size_t size() const { return static_cast<std::size_t>(zone.size()); }
  /// Gives every column `n` entries (values unspecified).
  void resize(std::size_t n);
  /// Throws std::invalid_argument if the columns differ in length.
  void check() const;
};

/// The contact table of `geometry`, one entry per element, built from the same rows as contact_final.csv
/// (output::contact_row): with `states` (one per element, same order) the forces and status, without them
/// NaN forces and kNoStatus. Throws std::invalid_argument on an inconsistent geometry or states that do not
/// match the elements (output::check_contact_geometry, output::check_contact_states).
ContactTable contact_table(const contact::ContactGeometry& geometry,
                           const std::vector<simulation::ContactState>* states = nullptr);

/// The contact table of the last detection of `sim`, with the forces of its last converged step where
/// contact_final.csv has them (output::contact_states_to_write); empty without contact.
ContactTable contact_table(const simulation::Simulation& sim);

/// The elements of `table` sorted by (zone, zeta), ties in table order (knot_report.py's read_contact,
/// np.lexsort); `order`, if given, receives the table index of each sorted element.
ContactTable sorted_by_zone_and_zeta(const ContactTable& table, std::vector<std::size_t>* order = nullptr);

/// The constants of knot_report.py, as defaults.
struct KnotMetricsOptions {
  /// TAIL_CHORD: length along each tail of the chord giving its direction [mm].
  double tail_chord = 2.0;
  /// MIN_SPACING: least element spacing for the contact coverage of the loop [mm].
  double min_spacing = 0.05;
  /// MIN_LOOP_NODES: centreline nodes needed for the circle fit of the loop.
  int min_loop_nodes = 5;
};

/// DEFAULT_RADIUS of knot_report.py: the rod radius of Sect. 7.2 when the contact tables give none [mm].
inline constexpr double kDefaultRodRadius = 0.1;

/// Centreline points c(s) at reference arc lengths `s` [mm]: linear between nodes, clamped to the rod ends
/// (c(s) = c(s_0) for s < s_0, c(s_last) beyond s_last; numpy.interp). Throws std::invalid_argument if the
/// centreline has fewer than two nodes or sizes that differ.
Points centreline_at(const Centreline& centreline, const Eigen::VectorXd& s);

/// Midpoint (x_i + x_j) / 2 of each contact element [mm].
Points midpoints(const ContactTable& contact);

/// Abscissa of each element along the intermediate geometry [mm]: within a zone (its elements in table
/// order) the length of the polyline of midpoints from the zone's first element,
///   a_k = a_first + sum_{m = first + 1}^{k} |mid_m - mid_{m-1}|,
/// zones in increasing number, each starting where the previous one ends (a_first of a zone = a of the last
/// element of the previous zone; 0 for the first zone).
Eigen::VectorXd intermediate_abscissa(const ContactTable& contact);

/// Sum over zones of max(a) - min(a) over the zone's elements in contact (normal_force > 0) [mm]; a zone
/// with none adds 0. `abscissa` from intermediate_abscissa.
double intermediate_length(const ContactTable& contact, const Eigen::VectorXd& abscissa);

/// Element spacing [mm]: the median of |abscissa_i[k+1] - abscissa_i[k]| over successive elements of each
/// zone (table order), at least `min_spacing`; `min_spacing` when there is no such pair.
double element_spacing(const ContactTable& contact, double min_spacing = 0.05);

/// Angle [deg] between the tail directions leaving the knot [s_a, s_b]: the chords c(s_a) -> c(s_a - L) and
/// c(s_b) -> c(s_b + L), L = `tail_chord` [mm], their far ends clamped to the rod ends;
/// acos(clamp(u . v / (|u| |v|), -1, 1)). 180 deg: the tails are pulled apart. NaN if a chord is shorter
/// than 1e-12 mm.
double tail_angle(const Centreline& centreline, double s_a, double s_b, double tail_chord = 2.0);

/// A closed interval [lo, hi] of arc length [mm].
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  double length() const { return hi - lo; }
};

/// The longest sub-interval of [lo, hi] farther than `half_width` from every centre [mm] (the gaps between
/// the sorted intervals [c - half_width, c + half_width]; the first of equal length wins); nullopt when the
/// intervals cover [lo, hi].
std::optional<Interval> longest_uncovered(std::vector<double> centres, double half_width, double lo,
                                          double hi);

/// Radius [mm] of the least-squares circle through 3-D points [mm]: the plane of the two leading right
/// singular vectors e1, e2 of the centred points (JacobiSVD), then the algebraic fit of Kasa (1976) in it:
/// (u_k, v_k) = ((p_k - mean) . e1, (p_k - mean) . e2); least squares of
///   2 u c_u + 2 v c_v + c = u^2 + v^2,   radius = sqrt(c + c_u^2 + c_v^2).
/// Exact, to rounding, for points on a circle (zero residual), also on a short arc. NaN for fewer than
/// three points (knot_report.py's fit_circle fails below two).
double fit_circle(const Points& points);

/// The loop of a knot: radius [mm] of the circle fitted to its nodes, its length in arc length [mm].
struct LoopGeometry {
  double radius = 0.0;
  double length = 0.0;
};

/// The loop of the knot [s_a, s_b]: the longest sub-interval of [s_a, s_b] farther than h from every
/// abscissa_i and abscissa_j of an element in contact (normal_force > 0), h = element_spacing(contact) / 2;
/// its length, and the radius of the circle fitted to the centreline nodes with s in it (NaN below
/// `options.min_loop_nodes` nodes). Both NaN when the contact covers [s_a, s_b]. As in knot_report.py, two
/// touched abscissas about 2 h apart may leave between them a gap of rounding size (1e-16 mm), which then
/// counts as a loop of that length (radius NaN: no node in it).
LoopGeometry loop_geometry(const Centreline& centreline, const ContactTable& contact, double s_a, double s_b,
                           const KnotMetricsOptions& options = {});

/// The range [s_a, s_b] of arc length touched by elements in contact: the smallest and largest abscissa_i,
/// abscissa_j of elements with normal_force > 0 [mm]; both NaN if none is in contact.
Interval knot_extent(const ContactTable& contact);

/// The rod radius [mm]: the median, over the elements of every state, of |x_i - c(abscissa_i)|, the distance
/// of the particle on beam I from the centreline of the state at its abscissa; `default_radius` when there
/// are no elements. centrelines[k] and contacts[k] belong to state k; throws std::invalid_argument if the
/// counts differ.
double rod_radius(const std::vector<Centreline>& centrelines, const std::vector<ContactTable>& contacts,
                  double default_radius = kDefaultRodRadius);

/// Per contact element, sorted by (zone, zeta): the reactions along the intermediate geometry (Fig. 14, 17;
/// reactions_*.csv of knot_report.py).
struct ReactionsTable {
  std::vector<std::size_t> element;  ///< index of the element in the table given to analyse_knot
  Eigen::VectorXi zone;              ///< zone index
  Eigen::VectorXd zeta;              ///< relative abscissa on the zone
  Eigen::VectorXd abscissa;          ///< along the intermediate geometry (intermediate_abscissa) [mm]
  Eigen::VectorXd s_i;               ///< abscissa_i [mm]
  Eigen::VectorXd s_j;               ///< abscissa_j [mm]
  Points midpoint;                   ///< (x_i + x_j) / 2 [mm]
  Eigen::VectorXd normal;            ///< R_N [N]
  Eigen::VectorXd tangential;        ///< |T| [N]
  Eigen::VectorXi state;             ///< as ContactTable::state
};

/// The numbers of one row of knot_report.csv that come from the nodes and contact table of a state.
struct KnotMetrics {
  int zones = 0;                     ///< distinct zone indices among the elements
  int contact_elements = 0;          ///< elements in the table
  int elements_in_contact = 0;       ///< elements with normal_force > 0
  double intermediate_length = 0.0;  ///< intermediate_length [mm]
  double max_normal = 0.0;           ///< max R_N [N]; 0 without elements
  double total_normal = 0.0;         ///< sum of R_N [N]
  double max_tangential = 0.0;       ///< max |T| [N]; 0 without elements
  double total_tangential = 0.0;     ///< sum of |T| [N]
  double tail_angle = 0.0;           ///< tail_angle(s_a, s_b) [deg]; NaN without an element in contact
  double loop_radius = 0.0;          ///< loop_geometry radius [mm]; NaN without an element in contact
  double loop_length = 0.0;          ///< loop_geometry length [mm]; NaN without an element in contact
  double max_penetration = 0.0;      ///< max(-gap) [mm]; NaN without elements
  double s_a = 0.0;                  ///< knot_extent lo [mm]; NaN without an element in contact
  double s_b = 0.0;                  ///< knot_extent hi [mm]; NaN without an element in contact
  ReactionsTable reactions;          ///< per element, sorted by (zone, zeta)
};

/// The knot metrics of a state (knot_report.py's analyse, less the columns of steps.csv): `centreline` the
/// rod's nodes in order (beam_centreline with its default of two segments per element gives the nodes of
/// final_nodes.csv, which knot_report.py reads), `contact` its contact elements in any order (sorted first
/// by sorted_by_zone_and_zeta, as knot_report.py's read_contact does). Max and sums are NaN when a value
/// is (numpy's). Throws std::invalid_argument if the centreline has fewer than two nodes or the columns
/// of `contact` differ in length.
KnotMetrics analyse_knot(const Centreline& centreline, const ContactTable& contact,
                         const KnotMetricsOptions& options = {});

}  // namespace nodus::analysis
