// What a new detection inherits from the last (contact/history_transfer.hpp, Sect. 5.2.3): penalties by the
// zone of largest overlap, and reversible displacements interpolated along the beams. The old history is a
// linear function of the abscissa, which linear interpolation must reproduce exactly.

#include <gtest/gtest.h>

#include "nodus/contact/history_transfer.hpp"

namespace nodus::contact {
namespace {

ProximityZone zone(int i, int j, double a, double b, double c, double d) {
  ProximityZone z;
  z.beam_i = i;
  z.beam_j = j;
  z.a = a;
  z.b = b;
  z.c = c;
  z.d = d;
  return z;
}

ContactElement element(int zone_index, double s_i, double s_j) {
  ContactElement e;
  e.zone = zone_index;
  e.particle_i.abscissa = s_i;
  e.particle_j.abscissa = s_j;
  return e;
}

/// g_rev of an old element whose particle on I sits at abscissa s [mm].
Eigen::Vector3d history(double s) {
  return 1e-3 * Eigen::Vector3d(s, -2.0 * s, 0.5);
}

TEST(HistoryTransfer, PenaltyOfTheZoneOfLargestOverlap) {
  ContactGeometry old;
  old.zones = {zone(0, 1, 0, 10, 0, 10), zone(0, 1, 20, 30, 20, 30)};
  ContactGeometry next;
  next.zones = {zone(0, 1, 8, 25, 9, 26),   // overlaps the first by 2 x 1, the second by 5 x 6
                zone(0, 1, 2, 4, 12, 14),   // on I within the first, on J in neither: no overlap
                zone(0, 2, 0, 10, 0, 10)};  // another pair of beams
  const std::vector<double> penalty = transfer_penalties(old, {5.0, 7.0}, next, 1.0);
  EXPECT_EQ(penalty, (std::vector<double>{7.0, 1.0, 1.0}));
}

TEST(HistoryTransfer, ReversibleDisplacementInterpolatedAlongBothBeams) {
  ContactGeometry old;
  old.zones = {zone(0, 1, 0, 10, 1, 11)};
  std::vector<Eigen::Vector3d> reversible;
  for (int k = 0; k <= 5; ++k) {
    old.elements.push_back(element(0, 2.0 * k, 2.0 * k + 1.0));  // J's particle 1 mm further on
    reversible.push_back(history(2.0 * k));
  }
  ContactGeometry next;
  next.zones = {zone(0, 1, 0, 10, 1, 11), zone(0, 2, 0, 10, 0, 10)};
  next.elements = {element(0, 3.0, 4.0),    // inside: both sides interpolate history(3)
                   element(0, 7.5, 8.5),    // inside: history(7.5)
                   element(0, 10.5, 9.0),   // I outside the stored range: J's side alone, history(8)
                   element(0, 10.5, 11.5),  // both outside: nothing
                   element(1, 3.0, 4.0)};   // another pair of beams: nothing
  const std::vector<Eigen::Vector3d> got = transfer_reversible(old, reversible, next);
  ASSERT_EQ(got.size(), 5u);
  EXPECT_LT((got[0] - history(3.0)).norm(), 1e-15);
  EXPECT_LT((got[1] - history(7.5)).norm(), 1e-15);
  EXPECT_LT((got[2] - history(8.0)).norm(), 1e-15);
  EXPECT_EQ(got[3], Eigen::Vector3d::Zero());
  EXPECT_EQ(got[4], Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace nodus::contact
