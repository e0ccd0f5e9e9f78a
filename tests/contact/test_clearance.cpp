// The clearance between beam surfaces (contact/clearance.hpp) against closed forms: two beams crossing at
// right angles, apart or passed through each other; a hairpin's legs; and a loop crossing itself, with the
// parts nearer than delta_separ along the beam left out.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "contact_test_support.hpp"
#include "nodus/contact/clearance.hpp"

namespace nodus::contact {
namespace {

using testing::beam_definition;
using testing::constant;
using testing::line;
using testing::place_beam;

constexpr double kPi = std::numbers::pi;

/// Beam I along x, beam J along y at height D, crossing at their middles (abscissa 2, a node of both); the
/// directors of both scaled by `shrink` (a contracted section reaches shrink R).
double crossing_clearance(double distance, double shrink = 1.0) {
  model::Model m;
  m.add_beam(beam_definition(4.0, 0.1, 80));
  m.add_beam(beam_definition(4.0, 0.08, 60));
  Eigen::VectorXd x = m.reference();
  place_beam(m, x, 0, line(Vec3(-2.0, 0.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  place_beam(m, x, 1, line(Vec3(0.0, -2.0, distance), Vec3::UnitY()), constant(Vec3::UnitZ()));
  for (Eigen::Index node = 0; node < x.size() / 9; ++node) x.segment<6>(9 * node + 3) *= shrink;
  const Clearance c = min_clearance(m, x, {}, 1.2, 0.3);
  EXPECT_EQ(c.beam_i, 0);
  EXPECT_EQ(c.beam_j, 1);
  EXPECT_NEAR(c.s_i, 2.0, 1e-9);
  EXPECT_NEAR(c.s_j, 2.0, 1e-9);
  return c.value;
}

TEST(Clearance, CrossingBeamsApartOrPassedThrough) {
  EXPECT_NEAR(crossing_clearance(0.25), 0.25 - 0.18, 1e-12);
  EXPECT_NEAR(crossing_clearance(0.05), 0.05 - 0.18, 1e-12);               // deep inside each other
  EXPECT_NEAR(crossing_clearance(-0.02), 0.02 - 0.18, 1e-12);              // J under I
  EXPECT_NEAR(crossing_clearance(0.17, 0.95), 0.17 - 0.95 * 0.18, 1e-12);  // contracted sections
}

TEST(Clearance, NothingWithinReachIsInfinite) {
  model::Model m;
  m.add_beam(beam_definition(4.0, 0.1, 20));
  m.add_beam(beam_definition(4.0, 0.1, 20));
  Eigen::VectorXd x = m.reference();
  place_beam(m, x, 1, line(Vec3(0.0, 1.0, 0.0), Vec3::UnitX()), constant(Vec3::UnitZ()));
  EXPECT_TRUE(std::isinf(min_clearance(m, x, {}, 1.2, 0.3).value));
}

TEST(Clearance, HairpinLegsAndNotTheBend) {
  // Legs along x, 2 rho = 0.24 mm apart, joined by a half circle: the legs' clearance is 2 rho - 2 R = 0.04
  // mm; around the bend, parts nearer than delta_separ along the beam are not compared (the neighbouring
  // points of an axis are always closer than 2 R).
  const double leg = 3.0, rho = 0.12, radius = 0.1, bend = kPi * rho;
  model::Model m;
  m.add_beam(beam_definition(2.0 * leg + bend, radius, 200));
  Eigen::VectorXd x = m.reference();
  place_beam(
      m, x, 0,
      [=](double s) -> Vec3 {
        if (s <= leg) return Vec3(leg - s, 0.0, 0.0);
        if (s <= leg + bend)
          return Vec3(-rho * std::sin((s - leg) / rho), rho - rho * std::cos((s - leg) / rho), 0.0);
        return Vec3(s - leg - bend, 2.0 * rho, 0.0);
      },
      constant(Vec3::UnitZ()));
  const Clearance c = min_clearance(m, x, {}, 1.2, 0.3);
  EXPECT_NEAR(c.value, 2.0 * rho - 2.0 * radius, 1e-12);
  EXPECT_GE(c.s_j - c.s_i, 1.2);
  // With delta_separ shorter than the bend, the bend's own neighbouring parts count.
  EXPECT_LT(min_clearance(m, x, {}, 0.1, 0.3).value, 2.0 * rho - 2.0 * radius - 0.01);
}

}  // namespace
}  // namespace nodus::contact
