// What a new detection inherits from the last (contact/history_transfer.hpp, Sect. 5.2.3): penalties by the
// zone of largest overlap, and reversible displacements interpolated along the beams. The old history is a
// linear function of the abscissa, which linear interpolation must reproduce exactly. A crossing that lies
// within another pairing of the same two beams (two fibres of a yarn, side by side along it and crossed in
// its knot) keeps its own history and penalty.

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
  const std::vector<double> penalty = transfer_penalties(old, {5.0, 7.0}, next, 1.0, 0.5);
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
                   element(0, 10.4, 10.8),  // I outside the stored range: J's side alone, history(9.8)
                   element(0, 10.5, 11.5),  // both outside: nothing
                   element(1, 3.0, 4.0)};   // another pair of beams: nothing
  const std::vector<Eigen::Vector3d> got = transfer_reversible(old, reversible, next, 0.5);
  ASSERT_EQ(got.size(), 5u);
  EXPECT_LT((got[0] - history(3.0)).norm(), 1e-15);
  EXPECT_LT((got[1] - history(7.5)).norm(), 1e-15);
  EXPECT_LT((got[2] - history(9.8)).norm(), 1e-15);
  EXPECT_EQ(got[3], Eigen::Vector3d::Zero());
  EXPECT_EQ(got[4], Eigen::Vector3d::Zero());
}

/// Beams I and J side by side along s in [0, 10] (pairing s_J = s_I), and crossing at (s_I, s_J) = (8, 2):
/// a crossing inside the box of the side-by-side zone, far from its pairing.
TEST(HistoryTransfer, ACrossingWithinAnotherPairingKeepsItsOwnHistoryAndPenalty) {
  ContactGeometry old;
  old.zones = {zone(0, 1, 0, 10, 0, 10), zone(0, 1, 7.8, 8.2, 1.8, 2.2)};
  std::vector<Eigen::Vector3d> reversible;
  for (int k = 0; k <= 10; ++k) {
    old.elements.push_back(element(0, k, k));
    reversible.push_back(history(k));
  }
  const Eigen::Vector3d crossing(0.3, 0.2, -0.1);
  for (double s : {7.8, 8.0, 8.2}) {
    old.elements.push_back(element(1, s, 2.0 + (s - 8.0)));
    reversible.push_back(crossing);
  }
  ContactGeometry next;  // the same zones, slightly moved
  next.zones = {zone(0, 1, 0.1, 10, 0.1, 10), zone(0, 1, 7.85, 8.25, 1.85, 2.25)};
  next.elements = {element(0, 8.05, 8.05), element(1, 8.05, 2.05)};
  const std::vector<Eigen::Vector3d> got = transfer_reversible(old, reversible, next, 0.5);
  EXPECT_LT((got[0] - history(8.05)).norm(), 1e-15);
  EXPECT_LT((got[1] - crossing).norm(), 1e-15);
  EXPECT_EQ(transfer_penalties(old, {5.0, 7.0}, next, 1.0, 0.5), (std::vector<double>{5.0, 7.0}));
}

}  // namespace
}  // namespace nodus::contact
