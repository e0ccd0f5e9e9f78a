// The 3x1 multifilament overhand knot of Durville 2012, Sect. 7.3: examples/knot_3x1.yaml (three fibres of
// 100 elements twisted into a yarn, tied with two clamping beams holding the loop while end B dives,
// tightened at 0.5 N, then released with mu = 0.3), run twice:
// - `Knot3x1Coarse`, in CI: the example's program with the yarn twisted by two turns (720 degrees in 60
//   steps) instead of 1030 degrees in 140, and one detection of the contact elements a step instead of two
//   until the knot is tightened (the release takes the example's two). The tying, tightening and release are
//   the example's, stage for stage. About 4 minutes on one thread (docs/knot_3x1.md, "Variants for CI"); it
//   carries the label `long` (the Release pass, not the sanitizer pass).
// - `Knot3x1`, the example as it is: 5 to 8 minutes on 2 cores, labelled `slow`, which CI's 30 minutes leave
//   out (`ctest -L slow` runs it).
// Fewer elements do not make either cheaper (docs/knot_3x1.md, "Variants for CI"). The knot is checked, not
// assumed:
// - each fibre's centreline closed far away, and the yarn's mean centreline, has the Alexander polynomial of
//   the trefoil, 1 - t + t^2, once tightened and again after the force has been released with mu = 0.3;
// - in every converged step no fibre passes through another or through itself: the clearance between the
//   surfaces (contact::min_clearance, every pair of parts, the clamps' too) stays above -2 p_max, and no step
//   takes two axes through each other (contact.crossing_guard);
// - the clamps press the loop while end B dives (stage `thread`);
// - no element folds: det[g1, g2, r'] above 1/2 at every Gauss point and element centre, chords above 0.9 h;
// - twisted, the fibres wind about the yarn's centre by the angle end B's bodies turned (1030 or 720
//   degrees): they could lose whole turns only by passing through one another (before the crossing guard, the
//   yarn of the example wound by 310 degrees, 720 fewer, docs/knot_3x1.md);
// - the tightened yarn is in equilibrium with the pulling force: end A's clamps take it up, to within the
//   drag left;
// - released with mu = 0.3, the knot holds at rest: the drag has decayed to exactly 0 and Newton converged
//   without it, and end B's three bodies, bound along x, are still together.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "nodus/analysis/knot.hpp"
#include "nodus/analysis/yarn_metrics.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::verification {
namespace {

/// The beams of the yarn's fibres (yarn.rK.fJ), in model order: the clamping beams are not among them.
std::vector<int> fibres_of(const model::Model& model) {
  std::vector<int> fibres;
  for (int b = 0; b < static_cast<int>(model.beams().size()); ++b)
    if (model.beam(b).name().starts_with("yarn.")) fibres.push_back(b);
  return fibres;
}

class Watcher : public simulation::StepObserver {
 public:
  double min_clearance = INFINITY;
  int min_clearance_step = 0;
  double min_orientation = INFINITY;
  double min_chord = INFINITY;
  simulation::StepRecord last;
  /// Each fibre's winding about the yarn's centre, seen along x, at the end of the first stage (the twist)
  /// [rad].
  std::vector<double> twist_winding;
  void on_stage_end(const simulation::Simulation& sim, int stage) override {
    if (stage != 0) return;
    const std::vector<int> fibres = fibres_of(sim.model());
    for (int b : fibres)
      twist_winding.push_back(
          analysis::winding_about_centre(sim.model(), sim.state(), b, fibres, Eigen::Vector3d::UnitX()));
  }
  /// The largest sum of the normal reactions between the clamping beams and the yarn at the end of a step of
  /// `thread` [N].
  double clamp_force = 0.0;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    last = r;
    if (sim.contact() && sim.scenario().stages.at(static_cast<std::size_t>(r.stage)).name == "thread") {
      const std::vector<int> fibres = fibres_of(sim.model());
      const auto fibre = [&](int b) { return std::find(fibres.begin(), fibres.end(), b) != fibres.end(); };
      const contact::ContactGeometry& g = *sim.contact();
      double force = 0.0;
      for (std::size_t k = 0; k < g.elements.size() && k < sim.contact_states().size(); ++k) {
        const contact::ContactElement& e = g.elements[k];
        if (fibre(e.particle_i.beam) != fibre(e.particle_j.beam))
          force += sim.contact_states()[k].normal_reaction;
      }
      clamp_force = std::max(clamp_force, force);
    }
    if (r.min_clearance < min_clearance) {
      min_clearance = r.min_clearance;
      min_clearance_step = r.step;
    }
    min_orientation = std::min(min_orientation, r.min_orientation);
    min_chord = std::min(min_chord, r.min_chord);
  }
  void reset() { *this = Watcher(); }
};

/// The knot types of the fibres and of their mean centreline.
struct Knots {
  std::vector<analysis::KnotInvariant> fibres;
  analysis::KnotInvariant mean;
};

Knots knots_of(const simulation::Simulation& sim) {
  Knots k;
  std::vector<std::vector<Eigen::Vector3d>> curves;
  for (const int b : fibres_of(sim.model())) {
    curves.push_back(analysis::beam_centreline(sim.model(), sim.state(), b).points);
    k.fibres.push_back(analysis::knot_invariant(curves.back()));
  }
  k.mean = analysis::knot_invariant(analysis::mean_curve(curves));
  return k;
}

void expect_trefoils(const Knots& k, const char* state) {
  for (std::size_t f = 0; f < k.fibres.size(); ++f)
    EXPECT_TRUE(k.fibres[f].is_trefoil()) << state << ": fibre " << f << ": " << k.fibres[f].to_string();
  EXPECT_TRUE(k.mean.is_trefoil()) << state << ": mean centreline: " << k.mean.to_string();
}

std::size_t condition_index(const scenario::Scenario& s, const std::string& name) {
  for (std::size_t c = 0; c < s.conditions.size(); ++c)
    if (s.conditions[c].name == name) return c;
  ADD_FAILURE() << "no condition " << name;
  return 0;
}

scenario::Scenario example() {
  std::ifstream in(NODUS_SOURCE_DIR "/examples/knot_3x1.yaml");
  EXPECT_TRUE(in) << "examples/knot_3x1.yaml";
  std::stringstream text;
  text << in.rdbuf();
  return scenario::parse_scenario(text.str(), "knot_3x1.yaml");
}

/// Twists, ties and tightens the yarn of `main`, releases it with mu = 0.3 (its first branch) with
/// `release_detections` detections a step at most, and checks both states (the file's head).
void tie_tighten_release(const scenario::Scenario& main, int release_detections) {
  const double pull = 0.5;
  simulation::Simulation sim(main);
  ASSERT_EQ(fibres_of(sim.model()).size(), 3u);
  const double limit = -2.0 * sim.contact_laws().max_penetration;

  // Twisting, tying and tightening.
  Watcher watcher;
  const simulation::RunSummary summary = sim.run({&watcher});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const simulation::StepRecord tightened = watcher.last;
  Eigen::Vector3d end_a = Eigen::Vector3d::Zero();
  for (const char* name : {"end_a1", "end_a2", "end_a3"})
    end_a += tightened.sections.at(condition_index(main, name)).force;
  std::printf(
      "tightened: %d steps, %d Newton iterations; smallest clearance %.6f mm at step %d (limit %.6f); normal "
      "force %.4f N, drag %.3g N; end A's supports (%.5f, %.5f, %.5f) N\n",
      summary.steps, summary.newton_iterations, watcher.min_clearance, watcher.min_clearance_step, limit,
      tightened.normal_force, tightened.stabilization_force, end_a.x(), end_a.y(), end_a.z());
  // The twist: end B's bodies turned about x by the twist stage's rotation (turn1's last keyframe).
  ASSERT_EQ(main.stages.at(0).name, "twist");
  const double turned = main.stages[0].motions.at(0).keyframes.back().rotation.x() * std::numbers::pi / 180.0;
  ASSERT_EQ(watcher.twist_winding.size(), 3u);
  for (std::size_t f = 0; f < 3; ++f) {
    std::printf("fibre %zu winds about the yarn's centre by %.2f degrees (its end turned by %.2f)\n", f,
                watcher.twist_winding[f] * 180.0 / std::numbers::pi, turned * 180.0 / std::numbers::pi);
    EXPECT_NEAR(watcher.twist_winding[f], turned, 5.0 * std::numbers::pi / 180.0) << "fibre " << f;
  }
  expect_trefoils(knots_of(sim), "tightened");
  // The main run's bounds were -4 p_max and 0.8 h until end B's dive in `thread` was redrawn (2026-11-28):
  // the yarn, bent sharply at its rigid end, compressed fibre r1's last element to 0.851 h, and its swollen
  // end section overlapped fibre r3's by 3.1 p_max (docs/knot_3x1.md, "End B's dive").
  EXPECT_GT(watcher.min_clearance, limit);
  EXPECT_GT(watcher.min_orientation, 0.5);
  EXPECT_GT(watcher.min_chord, 0.9);
  // The clamping beams hold the loop while end B dives (0.03 to 0.13 N in the example; a variant whose clamps
  // stayed just above the loop pressed nothing, docs/knot_3x1.md).
  std::printf("clamps on the loop in `thread`: up to %.4f N\n", watcher.clamp_force);
  EXPECT_GT(watcher.clamp_force, 0.01);
  // End A's supports hold end B's pull, up to the drag left (its resultant is at most sqrt(nodes) times the
  // norm of its nodal forces that steps.csv reports).
  const double drag_bound =
      std::sqrt(static_cast<double>(sim.model().num_nodes())) * tightened.stabilization_force;
  EXPECT_LT(std::abs(end_a.x() + pull), drag_bound + 1e-6);
  EXPECT_LT(tightened.stabilization_force, 1e-3 * pull);
  EXPECT_GT(tightened.normal_force, pull);

  // Released with mu = 0.3 (the first branch), end A clamped, the force on end B decreasing to 0, then the
  // drag decaying to exactly 0 (`rest`).
  ASSERT_EQ(main.branches.at(0).name, "mu_0.30");
  scenario::Scenario branch = scenario::branch_scenario(main, 0);
  branch.contact.max_detections = release_detections;
  simulation::Simulation released(branch);
  released.restore(sim.snapshot(), simulation::StartKind::branched);
  watcher.reset();
  const simulation::RunSummary loose = released.run({&watcher});
  ASSERT_TRUE(loose.converged) << loose.failure;
  const simulation::StepRecord rest = watcher.last;
  std::vector<double> end_b;
  for (int b = 0; b < static_cast<int>(released.model().bodies().size()); ++b)
    if (released.model().bodies()[static_cast<std::size_t>(b)].name.ends_with(".end"))
      end_b.push_back(released.state()[released.model().body_dof(b)]);
  ASSERT_EQ(end_b.size(), 3u);
  std::printf(
      "released (mu 0.3): %d steps, %d Newton iterations; smallest clearance %.6f mm at step %d; "
      "normal force %.4g N, tangential %.4g N, drag %.3g N; end B bodies at x = %.6f, %.6f, %.6f mm\n",
      loose.steps - summary.steps, loose.newton_iterations - summary.newton_iterations, watcher.min_clearance,
      watcher.min_clearance_step, rest.normal_force, rest.tangential_force, rest.stabilization_force,
      end_b[0], end_b[1], end_b[2]);
  expect_trefoils(knots_of(released), "released, mu = 0.3");
  EXPECT_GT(watcher.min_clearance, limit);
  EXPECT_GT(watcher.min_orientation, 0.5);
  EXPECT_GT(watcher.min_chord, 0.9);
  EXPECT_EQ(rest.stabilization_force, 0.0);  // at rest: held by friction alone
  EXPECT_GT(rest.tangential_force, 0.0);
  EXPECT_LT(rest.normal_force, tightened.normal_force);
  // The tails stay bound: the bind keeps end B's bodies together (their force differences, about 0.04 N, over
  // the bind's stiffness, 1e3 E A / h = 6.7e5 N/mm here: 1e-7 mm).
  const auto [low, high] = std::minmax_element(end_b.begin(), end_b.end());
  EXPECT_LT(*high - *low, 1e-5);
}

TEST(Knot3x1, TwistedTiedTightenedAndReleasedAtMu03EveryFibreStaysATrefoil) {
  const scenario::Scenario main = example();
  tie_tighten_release(main, main.contact.max_detections);
}

TEST(Knot3x1Coarse, TwistedByTwoTurnsTiedTightenedAndReleasedAtMu03EveryFibreStaysATrefoil) {
  scenario::Scenario main = example();
  scenario::StageSpec& twist = main.stages.at(0);
  ASSERT_EQ(twist.name, "twist");
  ASSERT_EQ(twist.motions.size(), 3u);
  // Two turns instead of 1030 degrees, 12 degrees a step against the example's 7.4. One turn (30 steps) was
  // the variant until the clamping beams: with them its smallest clearance came to -1.97 p_max (step 267, as
  // end B is let go in `pull`), where two turns keep -1.40 p_max (docs/knot_3x1.md, "Variants for CI").
  twist.steps = 60;
  for (scenario::MotionTarget& motion : twist.motions) {
    ASSERT_EQ(motion.keyframes.size(), 1u);
    ASSERT_NEAR(motion.keyframes[0].rotation.x(), 1030.0, 1e-9);
    motion.keyframes[0].rotation.x() = 720.0;
  }
  // One detection a step until the knot is tightened: 2,922 Newton iterations there against 3,828 with two,
  // for a smallest clearance of -1.77 p_max (-1.48 p_max with two). The release keeps two: with one as well
  // it overlapped by 2.7 p_max in `rest`.
  const int detections = main.contact.max_detections;
  main.contact.max_detections = 1;
  tie_tighten_release(main, detections);
}

}  // namespace
}  // namespace nodus::verification
