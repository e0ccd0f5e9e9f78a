// Internal force and tangent of the 9-dof beam element against central finite differences, on random deformed
// states of randomly placed elements; rigid motions give no force.

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "nodus/beam/beam.hpp"
#include "nodus/beam/beam_element.hpp"
#include "nodus/beam/section.hpp"

namespace nodus::beam {
namespace {

struct RandomElement {
  ElementVector x;
  ElementProperties props;
};

RandomElement random_deformed_element(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
  const Vec3 d1 = dir.unitOrthogonal();
  BeamDefinition def{"b", 0.4 + 0.2 * (u(rng) + 1),      0.02 + 0.01 * (u(rng) + 1),
                     1,   Vec3(u(rng), u(rng), u(rng)),  dir,
                     d1,  ElasticConstants{4000.0, 0.3}, 0.3 + 0.7 * (u(rng) + 1) / 2};
  const Beam beam(def, 0);
  RandomElement r{ElementVector(), beam.element_properties(3)};
  for (int i = 0; i < kElementNodes; ++i) r.x.segment<kNodeDofs>(kNodeDofs * i) = beam.reference_node(i);
  // Large deformation: perturb positions relative to the element length, directors by O(amplitude).
  for (int i = 0; i < kElementDofs; ++i) r.x[i] += amplitude * u(rng) * ((i % 9) < 3 ? def.length : 1.0);
  return r;
}

TEST(BeamElement, InternalForceIsGradientOfEnergy) {
  std::mt19937 rng(42);
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    RandomElement e = random_deformed_element(rng, 0.2);
    ElementVector f;
    element_internal_force(e.x, e.props, f, nullptr);
    const double scale = f.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    for (int i = 0; i < kElementDofs; ++i) {
      const double h = 1e-6;
      ElementVector xp = e.x, xm = e.x;
      xp[i] += h;
      xm[i] -= h;
      const double fd = (element_energy(xp, e.props) - element_energy(xm, e.props)) / (2 * h);
      EXPECT_NEAR(f[i], fd, 1e-6 * scale) << "trial " << trial << " dof " << i;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 20 * kElementDofs);
}

TEST(BeamElement, TangentIsDerivativeOfInternalForce) {
  std::mt19937 rng(7);
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    RandomElement e = random_deformed_element(rng, 0.2);
    ElementVector f;
    ElementMatrix k;
    element_internal_force(e.x, e.props, f, &k);
    const double scale = k.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale) << "tangent must be symmetric";
    for (int j = 0; j < kElementDofs; ++j) {
      const double h = 1e-6;
      ElementVector xp = e.x, xm = e.x, fp, fm;
      xp[j] += h;
      xm[j] -= h;
      element_internal_force(xp, e.props, fp, nullptr);
      element_internal_force(xm, e.props, fm, nullptr);
      const ElementVector fd = (fp - fm) / (2 * h);
      for (int i = 0; i < kElementDofs; ++i) {
        EXPECT_NEAR(k(i, j), fd[i], 1e-6 * scale) << "trial " << trial << " entry " << i << "," << j;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 20 * kElementDofs * kElementDofs);
}

TEST(BeamElement, RigidMotionGivesNoForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    RandomElement e = random_deformed_element(rng, 0.0);
    const Eigen::Matrix3d q =
        Eigen::AngleAxisd(3.0 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()).matrix();
    const Vec3 shift(10 * u(rng), 10 * u(rng), 10 * u(rng));
    ElementVector moved;
    for (int i = 0; i < kElementNodes; ++i) {
      moved.segment<3>(9 * i) = q * e.x.segment<3>(9 * i) + shift;
      moved.segment<3>(9 * i + 3) = q * e.x.segment<3>(9 * i + 3);
      moved.segment<3>(9 * i + 6) = q * e.x.segment<3>(9 * i + 6);
    }
    ElementVector f;
    element_internal_force(moved, e.props, f, nullptr);
    // Reference: a unit axial strain would give forces of order E A.
    const double ea = e.props.stiffness(kE33, kE33);
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * ea);
    EXPECT_LT(element_energy(moved, e.props), 1e-14 * ea * e.props.length);
  }
}

}  // namespace
}  // namespace nodus::beam
