// The overhand knot formed from a straight rod by moving its ends (examples/overhand_knot_forming.yaml, the
// rod of Durville 2012, Table 1, here with 100 instead of 300 elements). The knot is checked, not assumed:
// the final centreline, closed far away, has the Alexander polynomial of the trefoil, 1 - t + t^2; and in
// every converged step the rod never passes through itself: the smallest distance between two points of
// the axis farther apart along it than delta_separ stays above 2 R - 2 p_max.

#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "nodus/analysis/knot.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::verification {
namespace {

class Watcher : public simulation::StepObserver {
 public:
  double separation = 0.0;
  double smallest = INFINITY;
  double smallest_time = 0.0;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    // 8 segments per element: the polyline follows the curved axis to 0.4 um (knot.hpp).
    const analysis::Centreline c = analysis::beam_centreline(sim.model(), sim.state(), 0, 8);
    const analysis::SelfDistance d = analysis::min_self_distance(c.points, c.arc_length, separation);
    if (d.distance < smallest) {
      smallest = d.distance;
      smallest_time = r.time;
    }
  }
};

TEST(KnotForming, EndMotionsTieATrefoilWithoutPassThrough) {
  std::ifstream in(NODUS_SOURCE_DIR "/examples/overhand_knot_forming.yaml");
  ASSERT_TRUE(in) << "examples/overhand_knot_forming.yaml";
  std::stringstream text;
  text << in.rdbuf();
  const std::string coarse = std::regex_replace(text.str(), std::regex("elements: 300"), "elements: 100");
  ASSERT_NE(coarse, text.str());
  simulation::Simulation sim(scenario::parse_scenario(coarse, "overhand_knot_forming.yaml"));
  Watcher watcher;
  watcher.separation = sim.detection_parameters().separation_distance;
  const simulation::RunSummary summary = sim.run({&watcher});
  ASSERT_TRUE(summary.converged) << summary.failure;

  const analysis::Centreline c = analysis::beam_centreline(sim.model(), sim.state(), 0);
  const analysis::KnotInvariant knot = analysis::knot_invariant(c.points);
  const double radius = 0.1, limit = 2.0 * radius - 2.0 * sim.contact_laws().max_penetration;
  std::printf(
      "%d steps, %d Newton iterations; knot %s (%d crossings); smallest distance %.6f mm at t %.4f "
      "(separation %.3f mm, limit %.6f mm)\n",
      summary.steps, summary.newton_iterations, knot.to_string().c_str(), knot.crossings, watcher.smallest,
      watcher.smallest_time, watcher.separation, limit);
  EXPECT_TRUE(knot.is_trefoil()) << knot.to_string();
  EXPECT_GT(watcher.smallest, limit);
}

}  // namespace
}  // namespace nodus::verification
