// Contact detection against exact geometric answers [Durville 2012, Eq. 24-48]: crossings, parallel and
// antiparallel beams, a double helix, self-contact in a loop and a hairpin, the proximity limit, and the
// invariances under renumbering and rigid motion; the update of the normals, which reads only the elements
// carrying the particles.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "contact_test_support.hpp"

namespace nodus::contact {
namespace {

using testing::beam_definition;
using testing::constant;
using testing::line;
using testing::place_beam;

constexpr double kPi = std::numbers::pi;

/// The geometry of a model whose beams are placed by `place`.
struct Assembly {
  model::Model model;
  Eigen::VectorXd x;
};

/// The resolved parameters for an assembly whose largest radius is 0.1 mm: delta_prox 0.3 mm,
/// h_dist = sqrt(0.3^2 - 0.2^2) mm, l_p = 2 h_dist, delta_separ = 1.2 mm.
DetectionParameters defaults(const model::Model& model) {
  return resolve_parameters({}, model, {});
}

TEST(DetectionParameters, DefaultsFollowFromTheLargestRadius) {
  model::Model m;
  m.add_beam(beam_definition(4.0, 0.1, 80));
  m.add_beam(beam_definition(4.0, 0.08, 40));
  const DetectionParameters p = defaults(m);
  EXPECT_DOUBLE_EQ(p.proximity_distance, 0.3);
  EXPECT_DOUBLE_EQ(p.test_point_spacing, std::sqrt(0.3 * 0.3 - 0.2 * 0.2));
  EXPECT_DOUBLE_EQ(p.matching_length, 2.0 * p.test_point_spacing);
  EXPECT_DOUBLE_EQ(p.separation_distance, 1.2);
  EXPECT_EQ(p.element_spacing, 0.0);  // per zone
  // Only the listed beams count.
  EXPECT_DOUBLE_EQ(resolve_parameters({}, m, {1}).proximity_distance, 0.24);
  // Set values are kept; inconsistent ones are refused.
  DetectionParameters given;
  given.proximity_distance = 0.5;
  EXPECT_DOUBLE_EQ(resolve_parameters(given, m, {}).separation_distance, 2.0);
  given.separation_distance = 0.4;
  EXPECT_THROW(resolve_parameters(given, m, {}), std::invalid_argument);
  given.self_contact = false;
  EXPECT_NO_THROW(resolve_parameters(given, m, {}));
  DetectionParameters short_intervals;
  short_intervals.test_point_spacing = 0.2;
  short_intervals.matching_length = 0.1;
  EXPECT_THROW(resolve_parameters(short_intervals, m, {}), std::invalid_argument);
}

/// Two straight beams of length 4 mm crossing at their middles at `angle`, axis distance D: beam I along x
/// (R 0.1, 80 elements), beam J at height D along (cos angle, sin angle, 0) (R 0.08, 80 elements).
Assembly crossing(double angle, double distance) {
  Assembly a;
  a.model.add_beam(beam_definition(4.0, 0.1, 80));
  a.model.add_beam(beam_definition(4.0, 0.08, 80));
  a.x = a.model.reference();
  const Vec3 dir(std::cos(angle), std::sin(angle), 0.0);
  place_beam(a.model, a.x, 0, line(Vec3(-2.0, 0.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  place_beam(a.model, a.x, 1, line(Vec3(0.0, 0.0, distance) - 2.0 * dir, dir), constant(Vec3::UnitZ()));
  return a;
}

/// One zone, centred on the crossing (abscissa 2 on both beams), of half-length X + l_p / 2 on both beams
/// with X the largest test point offset within delta_prox: X <= sqrt(delta^2 - D^2) / sin(angle) < X +
/// h_dist.
void expect_crossing_zone(const ContactGeometry& g, const DetectionParameters& p, double angle,
                          double distance) {
  ASSERT_EQ(g.zones.size(), 1u);
  const ProximityZone& z = g.zones[0];
  EXPECT_EQ(z.beam_i, 0);
  EXPECT_EQ(z.beam_j, 1);
  const double reach =
      std::sqrt(p.proximity_distance * p.proximity_distance - distance * distance) / std::sin(angle);
  for (const auto& [lo, hi] : {std::pair{z.a, z.b}, std::pair{std::min(z.c, z.d), std::max(z.c, z.d)}}) {
    EXPECT_NEAR(0.5 * (lo + hi), 2.0, 1e-12);
    const double half = 0.5 * (hi - lo) - 0.5 * p.matching_length;
    EXPECT_LE(half, reach + 1e-12);
    EXPECT_GT(half, reach - p.test_point_spacing);
  }
  EXPECT_LT(z.c, z.d);  // acute crossing: the parts run the same way
}

TEST(Detection, CrossingAtRightAngles) {
  const double D = 0.17;  // axis distance; R_I + R_J = 0.18: the surfaces overlap by 0.01 mm
  const double r_i = 0.1, r_j = 0.08;
  const Assembly a = crossing(kPi / 2.0, D);
  const DetectionParameters p = defaults(a.model);
  const ContactGeometry g = detect(a.model, a.x, {});
  expect_crossing_zone(g, p, kPi / 2.0, D);
  ASSERT_GE(g.elements.size(), 5u);

  // At every contact element, with u_I, u_J the particles' offsets from the crossing along their beams, the
  // particles lie where the direction between the section centres, projected on each section, meets its
  // border, the normal is e_z (the tangents' cross product), and the gap is
  // D - R_I D / hypot(u_J, D) - R_J D / hypot(u_I, D).
  for (const ContactElement& e : g.elements) {
    const double u_i = e.particle_i.abscissa - 2.0, u_j = e.particle_j.abscissa - 2.0;
    const double rho_i = std::hypot(u_i, D), rho_j = std::hypot(u_j, D);
    EXPECT_NEAR((e.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((e.position_i - Vec3(u_i, r_i * u_j / rho_j, r_i * D / rho_j)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((e.position_j - Vec3(r_j * u_i / rho_i, u_j, D - r_j * D / rho_i)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(e.gap, D - r_i * D / rho_j - r_j * D / rho_i, 1e-12);
    EXPECT_NEAR(e.particle_i.transverse.norm(), r_i, 1e-12);
    EXPECT_NEAR(e.particle_j.transverse.norm(), r_j, 1e-12);
  }
  // The middle of the intermediate geometry is the crossing, where the gap is D - (R_I + R_J).
  ContactElement middle;
  ASSERT_TRUE(contact_element_at(a.model, a.x, g.zones[0], 0.5, middle));
  EXPECT_NEAR(middle.particle_i.abscissa, 2.0, 1e-12);
  EXPECT_NEAR(middle.particle_j.abscissa, 2.0, 1e-12);
  EXPECT_NEAR(middle.gap, D - (r_i + r_j), 1e-12);
}

TEST(Detection, CrossingAtTenDegrees) {
  const double D = 0.2, angle = 10.0 * kPi / 180.0;
  const Assembly a = crossing(angle, D);
  const DetectionParameters p = defaults(a.model);
  const ContactGeometry g = detect(a.model, a.x, {});
  expect_crossing_zone(g, p, angle, D);
  ContactElement middle;
  ASSERT_TRUE(contact_element_at(a.model, a.x, g.zones[0], 0.5, middle));
  EXPECT_NEAR(middle.particle_i.abscissa, 2.0, 1e-12);
  EXPECT_NEAR(middle.particle_j.abscissa, 2.0, 1e-12);
  EXPECT_NEAR((middle.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(middle.gap, D - 0.18, 1e-12);
  // The crossing is where the axes come closest: no gap along the zone is smaller.
  for (const ContactElement& e : g.elements) EXPECT_GE(e.gap, D - 0.18 - 1e-12);
  // 10 degrees lies between the two regimes of the normal (5 and 15 degrees): a blend.
  EXPECT_GT(g.elements[g.elements.size() / 2].parallel_weight, 0.0);
  EXPECT_LT(g.elements[g.elements.size() / 2].parallel_weight, 1.0);
}

/// Beam I along x from the origin; beam J along x at distance D in y, from x = 1 (parallel) or back from
/// x = 5 (antiparallel): the beams overlap over x in [1, 4].
Assembly side_by_side(bool antiparallel, double distance) {
  Assembly a;
  a.model.add_beam(beam_definition(4.0, 0.1, 80));
  a.model.add_beam(beam_definition(4.0, 0.08, 60));
  a.x = a.model.reference();
  place_beam(a.model, a.x, 0, line(Vec3::Zero(), Vec3::UnitX()), constant(Vec3::UnitZ()));
  if (antiparallel)
    place_beam(a.model, a.x, 1, line(Vec3(5.0, distance, 0.0), -Vec3::UnitX()), constant(Vec3::UnitZ()));
  else
    place_beam(a.model, a.x, 1, line(Vec3(1.0, distance, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  return a;
}

void expect_line_contact(bool antiparallel) {
  const double D = 0.19;
  const Assembly a = side_by_side(antiparallel, D);
  const ContactGeometry g = detect(a.model, a.x, {});
  ASSERT_EQ(g.zones.size(), 1u);
  const ProximityZone& z = g.zones[0];
  // The zone covers the overlap: x in [1, 4] on I, and s in [0, 3] (parallel) or [1, 4] (antiparallel) on J.
  EXPECT_LE(z.a, 1.0);
  EXPECT_DOUBLE_EQ(z.b, 4.0);
  if (antiparallel) {
    EXPECT_GT(z.c, z.d);
    EXPECT_GE(z.c, 4.0);
    EXPECT_LE(z.d, 1.0);
  } else {
    EXPECT_DOUBLE_EQ(z.c, 0.0);
    EXPECT_GE(z.d, 3.0);
  }
  // Elements at spacing h_c = 0.5 min(4/80, 4/60) = 0.025 along the shorter interval, those whose plane cuts
  // both beams kept: at least the overlap's worth.
  EXPECT_GE(static_cast<double>(g.elements.size()), 3.0 / 0.025);
  for (const ContactElement& e : g.elements) {
    EXPECT_NEAR((e.normal - Vec3::UnitY()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(e.gap, D - 0.18, 1e-12);
    EXPECT_NEAR(e.position_i.x(), e.position_j.x(), 1e-12);  // the section plane is normal to both axes
    EXPECT_DOUBLE_EQ(e.parallel_weight, 1.0);
  }
}

/// The overlap along the line of centres does not depend on the normal: two parallel beams 0.15 mm apart
/// (R_I + R_J = 0.18 mm) overlap by 0.03 mm at every element, whichever way the normal points, while the gap
/// along a normal turned across the line of centres is 0. With the sections shrunk by 5 % (directors of
/// length 0.95), the overlap is 0.95 * 0.18 - 0.15 mm.
TEST(Detection, CentreOverlapDoesNotDependOnTheNormal) {
  Assembly a = side_by_side(false, 0.15);
  const ContactGeometry g = detect(a.model, a.x, {});
  ASSERT_GE(g.elements.size(), 100u);
  Eigen::VectorXd shrunk = a.x;
  for (int node = 0; node < shrunk.size() / 9; ++node) shrunk.segment<6>(9 * node + 3) *= 0.95;
  for (ContactElement e : g.elements) {
    EXPECT_NEAR(e.gap, -0.03, 1e-12);
    EXPECT_NEAR(centre_overlap(a.model, a.x, e), 0.03, 1e-12);
    e.normal = Vec3::UnitZ();  // across the line of centres (e_y)
    EXPECT_NEAR((e.position_j - e.position_i).dot(e.normal), 0.0, 1e-12);
    EXPECT_NEAR(centre_overlap(a.model, a.x, e), 0.03, 1e-12);
    EXPECT_NEAR(centre_overlap(a.model, shrunk, e), 0.95 * 0.18 - 0.15, 1e-12);
  }
}

TEST(Detection, ParallelBeams) {
  expect_line_contact(false);
}
TEST(Detection, AntiparallelBeams) {
  expect_line_contact(true);
}

/// Two strands of a double helix of radius rho about the z axis, helix angle alpha, half a turn apart.
Assembly double_helix(double rho, double alpha, double r_i, double r_j, int elements_i, int elements_j,
                      bool swap = false) {
  Assembly a;
  const double length = 4.0;
  const auto strand = [=](double phase) {
    return [=](double s) -> Vec3 {
      const double phi = phase + s * std::sin(alpha) / rho;
      return Vec3(rho * std::cos(phi), rho * std::sin(phi), s * std::cos(alpha));
    };
  };
  const auto radial = [=](double phase) {
    return [=](double s) -> Vec3 {
      const double phi = phase + s * std::sin(alpha) / rho;
      return Vec3(std::cos(phi), std::sin(phi), 0.0);
    };
  };
  const int first =
      a.model.add_beam(beam_definition(length, swap ? r_j : r_i, swap ? elements_j : elements_i));
  const int second =
      a.model.add_beam(beam_definition(length, swap ? r_i : r_j, swap ? elements_i : elements_j));
  a.x = a.model.reference();
  place_beam(a.model, a.x, swap ? second : first, strand(0.0), radial(0.0));
  place_beam(a.model, a.x, swap ? first : second, strand(kPi), radial(kPi));
  return a;
}

class DoubleHelix : public ::testing::TestWithParam<double> {};

TEST_P(DoubleHelix, HasAConstantGap) {
  // Helix angle 20 degrees: the strands cross at 40 degrees, the normal is the tangents' cross product;
  // 2 degrees: 4 degrees between strands, the double cross product (Eq. 44).
  const double rho = 0.1, alpha = GetParam() * kPi / 180.0, radius = 0.095;
  const Assembly a = double_helix(rho, alpha, radius, radius, 160, 160);
  const ContactGeometry g = detect(a.model, a.x, {});
  ASSERT_EQ(g.zones.size(), 1u);
  EXPECT_LT(g.zones[0].a, 0.1);
  EXPECT_GT(g.zones[0].b, 3.9);
  ASSERT_GT(g.elements.size(), 100u);
  // Exact gap 2 rho - 2 R. Tolerances: the quadratic interpolation of the helix (nodes h / 2 apart), whose
  // error bounds are |r'''| / 6 * 2 / (3 sqrt 3) * (h / 2)^3 = 5e-7 mm on positions and |r'''| (h / 2)^2 / 3
  // = 2e-4 on tangents, with |r'''| = sin^3(alpha) / rho^2 <= 4 mm^-2 and h = 0.025 mm.
  double worst_gap = 0.0, worst_normal = 0.0;
  for (const ContactElement& e : g.elements) {
    worst_gap = std::max(worst_gap, std::abs(e.gap - (2.0 * rho - 2.0 * radius)));
    // The normal is radial, from strand I (at phi = s sin(alpha) / rho) to strand J through the axis.
    const double phi = e.particle_i.abscissa * std::sin(alpha) / rho;
    worst_normal = std::max(worst_normal, (e.normal + Vec3(std::cos(phi), std::sin(phi), 0.0)).norm());
  }
  EXPECT_LT(worst_gap, 5e-7);
  EXPECT_LT(worst_normal, 2e-4);
  EXPECT_EQ(g.elements.front().parallel_weight, GetParam() < 5.0 ? 1.0 : 0.0);
  std::printf(
      "double helix, helix angle %g deg: %zu contact elements, max |gap - (2 rho - 2 R)| = %.2e mm, "
      "max normal error %.2e\n",
      GetParam(), g.elements.size(), worst_gap, worst_normal);
}

INSTANTIATE_TEST_SUITE_P(Detection, DoubleHelix, ::testing::Values(2.0, 20.0));

TEST(Detection, NothingBeyondTheProximityDistance) {
  model::Model m;
  m.add_beam(beam_definition(4.0, 0.1, 80));
  const double delta = defaults(m).proximity_distance;
  for (const auto& [distance, zones] : {std::pair{delta + 0.01, 0u}, std::pair{delta - 0.01, 1u}}) {
    const Assembly parallel = side_by_side(false, distance);
    EXPECT_EQ(detect(parallel.model, parallel.x, {}).zones.size(), zones) << "parallel at " << distance;
    const Assembly crossed = crossing(kPi / 3.0, distance);
    EXPECT_EQ(detect(crossed.model, crossed.x, {}).zones.size(), zones) << "crossing at " << distance;
  }
}

/// A prolate cycloid x = t - 2 sin t, y = -2 cos t, whose loop crosses itself at t = +-t* (t* = 2 sin t*),
/// lifted by z = (D / 2) sin(pi t / (2 t*)) so that the two parts pass each other at axis distance D there,
/// with horizontal tangents. t spans [-T, T]; T puts t* on a node (node 204 of 240).
struct Loop {
  Assembly assembly;
  double crossing_later = 0.0, crossing_earlier = 0.0;  // abscissas of the crossing on the two parts
};

Loop alpha_loop(double distance) {
  double t_star = 1.9;
  for (int i = 0; i < 60; ++i) t_star -= (t_star - 2.0 * std::sin(t_star)) / (1.0 - 2.0 * std::cos(t_star));
  const int elements = 120;
  const double length = 12.0, big_t = t_star * elements / (204.0 - elements);
  Loop loop;
  Assembly& a = loop.assembly;
  a.model.add_beam(beam_definition(length, 0.1, elements));
  a.x = a.model.reference();
  const auto curve = [=](double s) -> Vec3 {
    const double t = -big_t + 2.0 * big_t * s / length;
    return Vec3(t - 2.0 * std::sin(t), -2.0 * std::cos(t), 0.5 * distance * std::sin(0.5 * kPi * t / t_star));
  };
  place_beam(a.model, a.x, 0, curve, constant(Vec3::UnitZ()));
  loop.crossing_later = length * (t_star + big_t) / (2.0 * big_t);
  loop.crossing_earlier = length - loop.crossing_later;
  return loop;
}

TEST(Detection, SelfContactWhereALoopCrossesItself) {
  const double D = 0.21;
  const Loop loop = alpha_loop(D);
  const Assembly& a = loop.assembly;
  const ContactGeometry g = detect(a.model, a.x, {});
  ASSERT_EQ(g.zones.size(), 1u);  // nothing along the loop or the tails
  const ProximityZone& z = g.zones[0];
  EXPECT_EQ(z.beam_i, 0);
  EXPECT_EQ(z.beam_j, 0);
  EXPECT_LT(z.a, loop.crossing_later);
  EXPECT_GT(z.b, loop.crossing_later);
  EXPECT_GT(z.c, loop.crossing_earlier);  // the parts cross at an obtuse angle: antiparallel
  EXPECT_LT(z.d, loop.crossing_earlier);
  EXPECT_NEAR(z.a + z.c, a.model.beam(0).length(), 1e-9);  // the loop is symmetric: so is the zone
  EXPECT_NEAR(z.b + z.d, a.model.beam(0).length(), 1e-9);
  // The element through the crossing: the later part's particle on top, the gap D - 2R (exact: the crossing
  // lies on a node, the tangents are horizontal there up to O(h^2), which tilts the normal by O(h^2)).
  ContactElement e;
  ASSERT_TRUE(contact_element_at(a.model, a.x, z, (loop.crossing_later - z.a) / (z.b - z.a), e));
  EXPECT_NEAR(e.particle_i.abscissa, loop.crossing_later, 1e-9);
  EXPECT_NEAR(e.particle_j.abscissa, loop.crossing_earlier, 1e-9);
  EXPECT_NEAR(e.gap, D - 0.2, 1e-8);
  EXPECT_LT(e.normal.z(), -1.0 + 1e-6);  // from the later (upper) part down to the earlier one
  for (const ContactElement& c : g.elements) EXPECT_GE(c.gap, D - 0.2 - 1e-8);
}

TEST(Detection, HairpinPairsOnlyPartsFartherApartThanTheSeparationDistance) {
  // A beam folded back on itself: straight leg along -x from (3, 0, 0) to the origin, half circle of radius
  // rho, straight leg back along +x at y = 2 rho. Points of the two legs at distance e from the bend are
  // pi rho + 2 e apart along the beam: only those with pi rho + 2 e >= delta_separ may be paired.
  const double leg = 3.0, rho = 0.12, radius = 0.1;
  const double bend = kPi * rho, length = 2.0 * leg + bend;
  model::Model m;
  m.add_beam(beam_definition(length, radius, 200));
  Eigen::VectorXd x = m.reference();
  const auto curve = [=](double s) -> Vec3 {
    if (s <= leg) return Vec3(leg - s, 0.0, 0.0);
    if (s <= leg + bend) {
      const double phi = (s - leg) / rho;
      return Vec3(-rho * std::sin(phi), rho - rho * std::cos(phi), 0.0);
    }
    return Vec3(s - leg - bend, 2.0 * rho, 0.0);
  };
  place_beam(m, x, 0, curve, constant(Vec3::UnitZ()));
  const DetectionParameters p = defaults(m);
  const ContactGeometry g = detect(m, x, {});
  ASSERT_EQ(g.zones.size(), 1u);
  const ProximityZone& z = g.zones[0];
  EXPECT_GT(z.c, z.d);  // the legs run antiparallel
  EXPECT_GE(z.a, leg + bend);
  double closest = length;
  for (const ContactElement& e : g.elements) {
    const double separation = e.particle_i.abscissa - e.particle_j.abscissa;
    closest = std::min(closest, separation);
    // The matched test points are delta_separ apart at least; the zone's ends reach l_p / 2 beyond them.
    EXPECT_GE(separation, p.separation_distance - p.matching_length);
    // On the straight legs (one element clear of the bend), the gap is exact.
    const double h = m.beam(0).element_length();
    if (e.particle_j.abscissa < leg - h && e.particle_i.abscissa > leg + bend + h) {
      EXPECT_NEAR(e.gap, 2.0 * rho - 2.0 * radius, 1e-12);
      EXPECT_NEAR((e.normal + Vec3::UnitY()).norm(), 0.0, 1e-12);  // from the later leg (I) down to J
    }
  }
  // And the zone does reach the parts just beyond delta_separ.
  EXPECT_LT(closest, p.separation_distance + p.test_point_spacing);
  // Without self-contact, nothing.
  DetectionParameters no_self;
  no_self.self_contact = false;
  EXPECT_TRUE(detect(m, x, no_self).zones.empty());
}

/// A zone of a beam with itself whose intervals meet, [a, b] = [s0 - 1, s0] with [c, d] = [s0 + 1, s0], on a
/// circular arc: the bisector's equation (the centre line normal to the pair's mean tangent) holds for every
/// pair (s0 - u, s0 + u) by symmetry, down to sections 0.1 mm apart, which report a penetration, and to the
/// section paired with itself at u = 0, where the centre line vanishes. Detection pairs no points of one beam
/// closer than delta_separ (Eq. 29), delta_separ - l_p with its zones' padding; nor may an element.
TEST(Detection, NoElementPairsSectionsOfOneBeamCloserThanTheSeparationDistance) {
  const double rho = 2.0, radius = 0.1, length = 6.0, s0 = 3.0;
  model::Model m;
  m.add_beam(beam_definition(length, radius, 120));
  Eigen::VectorXd x = m.reference();
  const auto arc = [=](double s) -> Vec3 {
    return Vec3(rho * std::sin(s / rho), rho * std::cos(s / rho), 0.0);
  };
  place_beam(m, x, 0, arc, constant(Vec3::UnitZ()));
  ProximityZone zone;
  zone.beam_i = zone.beam_j = 0;
  zone.a = s0 - 1.0;
  zone.b = s0;
  zone.c = s0 + 1.0;
  zone.d = s0;
  const double separation = defaults(m).separation_distance - defaults(m).matching_length;  // 0.753 mm
  int near = 0, far = 0;
  for (int k = 0; k <= 20; ++k) {
    const double zeta = 0.05 * k;
    ContactElement any, kept;
    const bool built = contact_element_at(m, x, zone, zeta, any, SectionPairing::bisector);
    const bool built_kept = contact_element_at(m, x, zone, zeta, kept, SectionPairing::bisector, separation);
    if (!built) continue;
    const double apart = any.particle_j.abscissa - any.particle_i.abscissa;
    EXPECT_NEAR(apart, 2.0 * (1.0 - zeta), 1e-6);  // the symmetric pair
    if (apart < separation) {
      ++near;
      EXPECT_FALSE(built_kept) << "zeta " << zeta << ": sections " << apart << " mm apart";
    } else {
      ++far;
      ASSERT_TRUE(built_kept);
      EXPECT_EQ(kept.gap, any.gap);
    }
  }
  EXPECT_GE(near, 6);  // closer pairs exist without the limit: 0.7 mm down to 0.1 mm apart
  EXPECT_GE(far, 5);
}

/// Two fibres side by side (axes 2 w apart in the plane of the loop) along the alpha loop's centreline: the
/// yarn of a knot. Where the loop crosses itself (the parts D apart in z), each fibre's later part crosses
/// both fibres' earlier part: fibre I's later part passes over fibre J's earlier part, which lies along fibre
/// I's earlier part, paired with J all along. That crossing lies inside the box of the fibres' side-by-side
/// zone on both beams, but far from its pairing (|s_I - s_J| of about 7 mm against l_p = 0.48 mm). Its axes'
/// closest approach (found by sampling the exact curves) must carry a contact element.
TEST(Detection, TwoFibresOfAYarnAlsoCrossWhereTheirLoopCrossesItself) {
  const double radius = 0.095, w = 0.1, D = 0.21;  // side by side: gap 0.01; crossing: gap 0.02
  double t_star = 1.9;
  for (int i = 0; i < 60; ++i) t_star -= (t_star - 2.0 * std::sin(t_star)) / (1.0 - 2.0 * std::cos(t_star));
  const int elements = 240;
  const double length = 12.0, big_t = 2.6;
  const auto fibre = [=](double side) {
    return [=](double s) -> Vec3 {
      const double t = -big_t + 2.0 * big_t * s / length;
      const Vec3 m = Vec3(-2.0 * std::sin(t), 1.0 - 2.0 * std::cos(t), 0.0).normalized();
      return Vec3(t - 2.0 * std::sin(t), -2.0 * std::cos(t), 0.5 * D * std::sin(0.5 * kPi * t / t_star)) +
             side * w * m;
    };
  };
  model::Model m;
  m.add_beam(beam_definition(length, radius, elements));
  m.add_beam(beam_definition(length, radius, elements));
  Eigen::VectorXd x = m.reference();
  place_beam(m, x, 0, fibre(1.0), constant(Vec3::UnitZ()));
  place_beam(m, x, 1, fibre(-1.0), constant(Vec3::UnitZ()));
  DetectionParameters no_self;
  no_self.self_contact = false;  // the fibres' self-contact at the crossing is another matter
  const ContactGeometry g = detect(m, x, no_self);

  // Closest approach of the later part of one fibre to the earlier part of the other: sampled every 0.5 um.
  const auto closest = [&](double later_side, double earlier_side) {
    const auto later = fibre(later_side), earlier = fibre(earlier_side);
    std::array<double, 3> best{1e9, 0.0, 0.0};
    for (double s = 0.6 * length; s <= 0.95 * length; s += 0.02)
      for (double u = 0.05 * length; u <= 0.4 * length; u += 0.02)
        if (const double d = (later(s) - earlier(u)).norm(); d < best[0]) best = {d, s, u};
    for (double step = 0.01; step >= 5e-4; step /= 2.0)
      for (bool moved = true; moved;) {
        moved = false;
        for (const auto& [ds, du] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}}) {
          const double d = (later(best[1] + ds) - earlier(best[2] + du)).norm();
          if (d < best[0]) {
            best = {d, best[1] + ds, best[2] + du};
            moved = true;
          }
        }
      }
    return best;
  };
  for (const auto& [later_side, earlier_side] : {std::pair{1.0, -1.0}, std::pair{-1.0, 1.0}}) {
    const auto [distance, s_later, s_earlier] = closest(later_side, earlier_side);
    ASSERT_NEAR(distance, D, 0.01);  // the construction: the parts cross D apart
    const double s_i = later_side > 0.0 ? s_later : s_earlier, s_j = later_side > 0.0 ? s_earlier : s_later;
    const ContactElement* nearest = nullptr;
    for (const ContactElement& e : g.elements)
      if (!nearest || std::hypot(e.particle_i.abscissa - s_i, e.particle_j.abscissa - s_j) <
                          std::hypot(nearest->particle_i.abscissa - s_i, nearest->particle_j.abscissa - s_j))
        nearest = &e;
    ASSERT_NE(nearest, nullptr);
    EXPECT_LT(std::hypot(nearest->particle_i.abscissa - s_i, nearest->particle_j.abscissa - s_j), 0.1)
        << "no contact element at the crossing of fibre " << (later_side > 0.0 ? "I" : "J")
        << "'s later part (s = " << s_later << ") over the other's earlier part (s = " << s_earlier << ")";
    EXPECT_NEAR(nearest->gap, distance - 2.0 * radius, 1e-4);  // the element is off by 0.4 um at most
    std::printf(
        "yarn loop: crossing at (%.3f, %.3f) mm, axes %.5f mm apart; nearest element %.4f mm off, gap "
        "%.5f mm\n",
        s_i, s_j, distance,
        std::hypot(nearest->particle_i.abscissa - s_i, nearest->particle_j.abscissa - s_j), nearest->gap);
  }
  // And the fibres are still paired side by side along the yarn.
  int side_by_side = 0;
  for (const ContactElement& e : g.elements)
    if (std::abs(e.particle_i.abscissa - e.particle_j.abscissa) < 0.1) ++side_by_side;
  EXPECT_GT(side_by_side, 200);
}

/// Elements of `a` and `b` match with the particles of I and J exchanged, opposite normals, same gaps.
void expect_swapped(const ContactGeometry& a, const ContactGeometry& b) {
  ASSERT_EQ(a.zones.size(), b.zones.size());
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (const ContactElement& e : a.elements) {
    const auto it = std::find_if(b.elements.begin(), b.elements.end(), [&](const ContactElement& f) {
      return std::abs(f.particle_j.abscissa - e.particle_i.abscissa) < 1e-9 &&
             std::abs(f.particle_i.abscissa - e.particle_j.abscissa) < 1e-9;
    });
    ASSERT_NE(it, b.elements.end()) << "no match for the element at zeta " << e.zeta;
    EXPECT_NEAR((it->particle_j.transverse - e.particle_i.transverse).norm(), 0.0, 1e-9);
    EXPECT_NEAR((it->particle_i.transverse - e.particle_j.transverse).norm(), 0.0, 1e-9);
    EXPECT_NEAR((it->normal + e.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR(it->gap, e.gap, 1e-12);
  }
}

TEST(DetectionInvariance, RenumberingTheBeamsSwapsTheParticlesAndFlipsTheNormals) {
  // A double helix of unequal strands.
  const double rho = 0.1, alpha = 25.0 * kPi / 180.0;
  const Assembly helix = double_helix(rho, alpha, 0.095, 0.09, 160, 120);
  const Assembly helix_swapped = double_helix(rho, alpha, 0.095, 0.09, 160, 120, true);
  const ContactGeometry h1 = detect(helix.model, helix.x, {});
  ASSERT_FALSE(h1.elements.empty());
  expect_swapped(h1, detect(helix_swapped.model, helix_swapped.x, {}));

  // Two bent beams crossing at 70 degrees, curving away from each other: A in the xy-plane through the
  // origin along x, B through (0, 0, 0.16) bending upwards.
  const Vec3 t_b(std::cos(70.0 * kPi / 180.0), std::sin(70.0 * kPi / 180.0), 0.0);
  const auto curve_a = [](double s) -> Vec3 {
    const double phi = (s - 1.5) / 3.0;
    return Vec3(3.0 * std::sin(phi), 3.0 * std::cos(phi) - 3.0, 0.0);
  };
  const auto curve_b = [&](double s) -> Vec3 {
    const double psi = (s - 1.4) / 2.0;
    return Vec3(0.0, 0.0, 0.16) + 2.0 * (std::sin(psi) * t_b + (1.0 - std::cos(psi)) * Vec3::UnitZ());
  };
  const auto build = [&](bool swap) {
    Assembly a;
    a.model.add_beam(beam_definition(3.0, swap ? 0.07 : 0.1, swap ? 70 : 90));
    a.model.add_beam(beam_definition(3.0, swap ? 0.1 : 0.07, swap ? 90 : 70));
    a.x = a.model.reference();
    place_beam(a.model, a.x, swap ? 1 : 0, curve_a, constant(Vec3::UnitZ()));
    place_beam(a.model, a.x, swap ? 0 : 1, curve_b, constant(Vec3::UnitY()));
    return a;
  };
  const Assembly crossed = build(false), crossed_swapped = build(true);
  const ContactGeometry c1 = detect(crossed.model, crossed.x, {});
  ASSERT_EQ(c1.zones.size(), 1u);
  expect_swapped(c1, detect(crossed_swapped.model, crossed_swapped.x, {}));
}

TEST(DetectionInvariance, ARigidMotionMovesTheContactElementsAndKeepsTheGaps) {
  const Eigen::Matrix3d q =
      Eigen::AngleAxisd(128.0 * kPi / 180.0, Vec3(1.0, -2.0, 0.5).normalized()).matrix();
  const Vec3 shift(3.0, -1.0, 7.5);
  const Loop loop = alpha_loop(0.19);
  const Assembly helix = double_helix(0.1, 0.3, 0.095, 0.09, 160, 120);
  for (const Assembly* a : {&loop.assembly, &helix}) {
    const ContactGeometry g = detect(a->model, a->x, {});
    const ContactGeometry h = detect(a->model, testing::moved(a->x, q, shift), {});
    ASSERT_FALSE(g.elements.empty());
    ASSERT_EQ(g.zones.size(), h.zones.size());
    ASSERT_EQ(g.elements.size(), h.elements.size());
    for (std::size_t k = 0; k < g.elements.size(); ++k) {
      const ContactElement &e = g.elements[k], &f = h.elements[k];
      EXPECT_NEAR(f.particle_i.abscissa, e.particle_i.abscissa, 1e-9);
      EXPECT_NEAR(f.particle_j.abscissa, e.particle_j.abscissa, 1e-9);
      EXPECT_NEAR((f.particle_i.transverse - e.particle_i.transverse).norm(), 0.0, 1e-9);
      EXPECT_NEAR((f.position_i - (q * e.position_i + shift)).norm(), 0.0, 1e-9);
      EXPECT_NEAR((f.position_j - (q * e.position_j + shift)).norm(), 0.0, 1e-9);
      EXPECT_NEAR((f.normal - q * e.normal).norm(), 0.0, 1e-9);
      EXPECT_NEAR(f.gap, e.gap, 1e-12);
    }
  }
}

/// Four beams in contact (two crossing at right angles, two parallel in line contact) among `bundle` beams
/// far from them and from each other, numbered before, between and after the contact beams; `bundle` 0: the
/// four alone. The contact beams' indices in the model are returned in `contact`.
Assembly contact_among_bundle(int bundle, std::vector<int>& contact) {
  Assembly a;
  contact.clear();
  const auto add_bundle = [&](int count) {
    for (int k = 0; k < count; ++k) a.model.add_beam(beam_definition(4.0, 0.1, 8));  // placed below
  };
  add_bundle(bundle / 3);
  for (int k = 0; k < 2; ++k) contact.push_back(a.model.add_beam(beam_definition(4.0, 0.1, 16)));
  add_bundle(bundle / 3);
  for (int k = 0; k < 2; ++k) contact.push_back(a.model.add_beam(beam_definition(4.0, 0.1, 12)));
  add_bundle(bundle - 2 * (bundle / 3));
  a.x = a.model.reference();
  int next = 0;
  for (int b = 0; b < static_cast<int>(a.model.beams().size()); ++b) {
    if (std::find(contact.begin(), contact.end(), b) != contact.end()) continue;
    place_beam(a.model, a.x, b,
               line(Vec3(-2.0, 20.0 + 2.0 * (next % 10), 20.0 + 2.0 * (next / 10)), Vec3::UnitX()),
               constant(Vec3::UnitY()));
    ++next;
  }
  // Overlaps of 0.01 mm (axis distance 0.19 mm, 2 R = 0.2 mm).
  place_beam(a.model, a.x, contact[0], line(Vec3(-2.0, 0.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitY()));
  place_beam(a.model, a.x, contact[1], line(Vec3(0.0, -2.0, 0.19), Vec3::UnitY()), constant(Vec3::UnitX()));
  place_beam(a.model, a.x, contact[2], line(Vec3(-2.0, 0.0, 5.0), Vec3::UnitX()), constant(Vec3::UnitY()));
  place_beam(a.model, a.x, contact[3], line(Vec3(-2.0, 0.0, 5.19), Vec3::UnitX()), constant(Vec3::UnitY()));
  return a;
}

/// `x` with the nodes of the beams in `beams` moved by a smooth displacement (positions and directors), the
/// same function of each node's place on its beam in any model.
Eigen::VectorXd deformed(const model::Model& model, const Eigen::VectorXd& x, const std::vector<int>& beams) {
  Eigen::VectorXd y = x;
  for (int k = 0; k < static_cast<int>(beams.size()); ++k) {
    const beam::Beam& b = model.beam(beams[static_cast<std::size_t>(k)]);
    for (int i = 0; i < b.num_nodes(); ++i) {
      const double s = b.abscissa(i) + k;
      auto node = y.segment<beam::kNodeDofs>(beam::kNodeDofs * b.node(i));
      node.head<3>() += 0.02 * Vec3(std::sin(s), std::cos(2.0 * s), std::sin(3.0 * s + 1.0));
      node.segment<3>(3) += 0.05 * Vec3(std::cos(s), 0.3, std::sin(2.0 * s));
      node.segment<3>(6) += 0.05 * Vec3(0.2, std::sin(s), std::cos(3.0 * s));
    }
  }
  return y;
}

void expect_identical(const ContactElement& e, const ContactElement& f) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(e.normal[c], f.normal[c]);
    EXPECT_EQ(e.position_i[c], f.position_i[c]);
    EXPECT_EQ(e.position_j[c], f.position_j[c]);
  }
  EXPECT_EQ(e.gap, f.gap);
  EXPECT_EQ(e.parallel_weight, f.parallel_weight);
  EXPECT_EQ(e.particle_i.transverse, f.particle_i.transverse);
  EXPECT_EQ(e.particle_j.transverse, f.particle_j.transverse);
}

TEST(UpdateNormal, ReadsOnlyTheElementsOfTheParticlesAndMatchesAFullDetectionExactly) {
  std::vector<int> in_bundle, alone;
  const Assembly big = contact_among_bundle(90, in_bundle);
  const Assembly small = contact_among_bundle(0, alone);
  ASSERT_EQ(big.model.beams().size(), 94u);
  ASSERT_GT(big.model.first_element(in_bundle[0]), 0);  // the particles' element numbers differ in the two
  const ContactGeometry g = detect(big.model, big.x, {}, in_bundle);
  ASSERT_EQ(g.zones.size(), 2u);
  ASSERT_GT(g.elements.size(), 10u);
  const Eigen::VectorXd x_big = deformed(big.model, big.x, in_bundle);
  const Eigen::VectorXd x_small = deformed(small.model, small.x, alone);
  // The same contact elements in the model of the four beams alone: particles renumbered.
  const auto renumbered = [&](Particle p) {
    const auto k =
        static_cast<std::size_t>(std::find(in_bundle.begin(), in_bundle.end(), p.beam) - in_bundle.begin());
    p.element += small.model.first_element(alone[k]) - big.model.first_element(p.beam);
    p.beam = alone[k];
    return p;
  };
  for (const bool facing : {false, true}) {
    for (const ContactElement& e : g.elements) {
      ContactElement in_big = e, in_small = e;
      in_small.particle_i = renumbered(e.particle_i);
      in_small.particle_j = renumbered(e.particle_j);
      ASSERT_TRUE(update_normal(big.model, x_big, in_big, facing));
      ASSERT_TRUE(update_normal(small.model, x_small, in_small, facing));
      expect_identical(in_big, in_small);
      EXPECT_GT((in_big.normal - e.normal).norm(), 1e-3);  // the deformation turned the normal
    }
  }
  // In the state they were detected in, updating the normals of a detection (which builds the geometry of
  // every contact beam) changes nothing, to the last bit.
  const ContactGeometry h = detect(big.model, x_big, {}, in_bundle);
  ASSERT_FALSE(h.elements.empty());
  for (const ContactElement& e : h.elements) {
    ContactElement updated = e;
    ASSERT_TRUE(update_normal(big.model, x_big, updated));
    expect_identical(updated, e);
  }
}

/// The contact elements of `a` with the sections paired by `pairing` (default lengths).
ContactGeometry detect_paired(const Assembly& a, SectionPairing pairing) {
  DetectionParameters p;
  p.pairing = pairing;
  return detect(a.model, a.x, p);
}

/// Where the paired points face each other (the centre line normal to both axes or, at a symmetric crossing,
/// to the bisector of their tangents), the bisector pairing finds the paper's sections: parallel and
/// antiparallel line contact, crossings at 90 and 10 degrees, the double helix.
TEST(SectionPairing, BisectorPairsThePapersSectionsWhereTheyFaceEachOther) {
  const std::vector<std::pair<const char*, Assembly>> cases = {
      {"crossing 90 deg", crossing(kPi / 2.0, 0.17)},
      {"crossing 10 deg", crossing(10.0 * kPi / 180.0, 0.2)},
      {"parallel", side_by_side(false, 0.19)},
      {"antiparallel", side_by_side(true, 0.19)},
      {"double helix 20 deg", double_helix(0.1, 20.0 * kPi / 180.0, 0.095, 0.095, 160, 160)}};
  for (const auto& [name, a] : cases) {
    const ContactGeometry plane = detect_paired(a, SectionPairing::plane);
    const ContactGeometry bisector = detect_paired(a, SectionPairing::bisector);
    ASSERT_EQ(plane.zones.size(), bisector.zones.size()) << name;
    ASSERT_EQ(plane.elements.size(), bisector.elements.size()) << name;
    ASSERT_GT(plane.elements.size(), 4u) << name;
    for (std::size_t k = 0; k < plane.elements.size(); ++k) {
      const ContactElement &p = plane.elements[k], &b = bisector.elements[k];
      EXPECT_NEAR(p.particle_i.abscissa, b.particle_i.abscissa, 1e-9) << name << " element " << k;
      EXPECT_NEAR(p.particle_j.abscissa, b.particle_j.abscissa, 1e-9) << name << " element " << k;
      EXPECT_NEAR(p.gap, b.gap, 1e-9) << name << " element " << k;
      EXPECT_NEAR((p.normal - b.normal).norm(), 0.0, 1e-9) << name << " element " << k;
    }
  }
}

/// A strand wrapping round a straight one at a steep angle, its pitch growing along it (as a strand of a knot
/// pulled tight wraps round the other): beam I along x (R 0.1, 2 mm, 40 elements); beam J the curve
/// x(theta) = 0.6 + p theta + q theta^2, y = rho cos theta, z = rho sin theta, theta = 2 pi s / L_J for s in
/// [0, L_J] (R 0.08, L_J 1.4 mm, 40 elements; the section stretched, as a deformed state may be), rho = 0.19,
/// p = 0.07, q = 0.09 / (4 pi): the strands cross at 70 degrees at theta = 0 and 50 at 2 pi. The closest
/// point of I's axis to J's section at theta is x(theta), at distance rho: the pairing s_I = x(theta(s_J)) is
/// quadratic, not linear. Exactly: <r_J - r_I, (b - a) r_I' + (d - c) r_J'> = (x - s_I) ((b - a) + (d - c)
/// 2 pi x' / L_J), zero only there, so the bisector pairing finds it, to the quadratic interpolation of J's
/// axis: nodes h / 2 = 0.0175 mm apart, |r'''| <= rho (2 pi / L_J)^3 = 17.2 mm^-2, so positions within
/// |r'''| / 6 * 2 / (3 sqrt 3) * (h / 2)^3 = 6e-6 mm and tangents within |r'''| (h / 2)^2 / 3 = 1.8e-3 (the
/// bounds of the double helix's test): offsets within 5e-5 mm, normals within 2e-3, gaps within 2e-5 mm. The
/// plane cut pairs sections up to 0.08 mm off. Either way the normal is radial and the gap rho - R_I - R_J,
/// since the offset lies along I's axis: only the pairing tells them apart.
TEST(SectionPairing, BisectorFollowsTheClosestPointsOfAStrandWrappingRoundAnother) {
  const double rho = 0.19, p = 0.07, q = 0.09 / (4.0 * kPi), length_j = 1.4;
  const auto x_of = [&](double theta) { return 0.6 + p * theta + q * theta * theta; };
  Assembly a;
  a.model.add_beam(beam_definition(2.0, 0.1, 40));
  a.model.add_beam(beam_definition(length_j, 0.08, 40));
  a.x = a.model.reference();
  place_beam(a.model, a.x, 0, line(Vec3::Zero(), Vec3::UnitX()), constant(Vec3::UnitZ()));
  const auto theta_of = [&](double s) { return 2.0 * kPi * s / length_j; };
  place_beam(
      a.model, a.x, 1,
      [&](double s) {
        const double t = theta_of(s);
        return Vec3(x_of(t), rho * std::cos(t), rho * std::sin(t));
      },
      [&](double s) { return Vec3(0.0, std::cos(theta_of(s)), std::sin(theta_of(s))); });

  const auto worst_offset = [&](const ContactGeometry& g) {
    double worst = 0.0;
    for (const ContactElement& e : g.elements)
      worst = std::max(worst, std::abs(e.particle_i.abscissa - x_of(theta_of(e.particle_j.abscissa))));
    return worst;
  };
  const ContactGeometry bisector = detect_paired(a, SectionPairing::bisector);
  ASSERT_EQ(bisector.zones.size(), 1u);
  ASSERT_GE(bisector.elements.size(), 20u);
  EXPECT_LT(worst_offset(bisector), 5e-5);
  for (const ContactElement& e : bisector.elements) {
    const double t = theta_of(e.particle_j.abscissa);
    EXPECT_NEAR((e.normal - Vec3(0.0, std::cos(t), std::sin(t))).norm(), 0.0, 2e-3);
    EXPECT_NEAR(e.gap, rho - 0.18, 2e-5);
  }
  const ContactGeometry plane = detect_paired(a, SectionPairing::plane);
  ASSERT_EQ(plane.zones.size(), 1u);
  EXPECT_GT(worst_offset(plane), 0.01);
  std::printf(
      "wrapping strand: %zu elements; largest offset of s_I from the closest point: bisector %.3g mm, "
      "plane %.3g mm\n",
      bisector.elements.size(), worst_offset(bisector), worst_offset(plane));
}

}  // namespace
}  // namespace nodus::contact
