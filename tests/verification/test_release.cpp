// Releasing a support ramps its force and moment down to zero over the stage: a cantilever bent by a
// prescribed tip motion and then released returns to its straight, unloaded reference shape (the only
// equilibrium of an unloaded cantilever), and the root reaction vanishes.

#include <gtest/gtest.h>

#include "cantilever.hpp"

namespace nodus::verification {
namespace {

TEST(Release, BentCantileverSpringsBackStraight) {
  BeamCase c;
  c.length = 20.0;
  c.radius = 0.1;
  c.elements = 20;
  scenario::Scenario s = single_beam(c);
  const int root = add_condition(s, "root", scenario::ConditionType::clamp, false);
  const int tip = add_condition(s, "tip", scenario::ConditionType::motion, true);
  scenario::StageSpec bend;
  bend.name = "bend";
  bend.steps = 10;
  bend.motions.push_back({tip, {{1.0, Eigen::Vector3d(0, 3, 1), Eigen::Vector3d(10, -5, 20)}}});
  s.stages.push_back(bend);
  scenario::StageSpec release;
  release.name = "release";
  release.steps = 5;
  release.release.push_back(tip);
  s.stages.push_back(release);
  VerifiedSimulation sim(s);
  struct Capture : simulation::StepObserver {
    simulation::StepRecord bent, last;
    void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
      if (r.stage == 0) bent = r;
      last = r;
      (void)sim;
    }
  } capture;
  const simulation::RunSummary summary = sim.run({&capture});
  ASSERT_TRUE(summary.converged) << summary.failure;
  // The bent state carried a real reaction; the released one carries none.
  const double bent_force = capture.bent.sections[static_cast<std::size_t>(root)].force.norm();
  EXPECT_GT(bent_force, 1e-3);
  EXPECT_LT(capture.last.sections[static_cast<std::size_t>(root)].force.norm(), 1e-8 * bent_force);
  const Eigen::VectorXd& x = sim.state();
  const Eigen::VectorXd& x0 = sim.model().reference();
  EXPECT_LT((x - x0).lpNorm<Eigen::Infinity>(), 1e-8 * c.length);
}

}  // namespace
}  // namespace nodus::verification
