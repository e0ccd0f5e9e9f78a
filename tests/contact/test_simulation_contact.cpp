// Contact detection inside a run: counts per step, the geometry of the committed state, and the check of the
// resolved lengths when the run starts.

#include <gtest/gtest.h>

#include <tuple>

#include "nodus/beam/beam.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::simulation {
namespace {

/// Two parallel rods 0.22 mm apart (R = 0.1 mm), one of them pushed sideways towards the other at its end.
std::string pair_scenario(const std::string& contact) {
  return R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: a, material: m, radius: 0.1, length: 10, elements: 20, start: [0, 0.11, 0]}
  - {name: b, material: m, radius: 0.1, length: 10, elements: 20, start: [0, -0.11, 0]}
conditions:
  - {name: a_root, type: clamp, beam: a, at: start}
  - {name: b_root, type: clamp, beam: b, at: start}
  - {name: a_end, type: motion, beam: a, at: end}
  - {name: b_end, type: clamp, beam: b, at: end}
stages:
  - name: push
    steps: 4
    motions:
      a_end: {translation: [0, 0.5, 0]}
)" + contact;
}

class Recorder : public StepObserver {
 public:
  std::vector<StepRecord> records;
  void on_step(const Simulation&, const StepRecord& r) override { records.push_back(r); }
};

TEST(SimulationContact, EachStepCountsTheZonesOfItsConvergedState) {
  Simulation sim(scenario::parse_scenario(pair_scenario("contact: {forces: false}\n"), "pair.yaml"));
  ASSERT_NE(sim.contact(), nullptr);
  // Before the first step: the rods lie side by side along their whole length.
  ASSERT_EQ(sim.contact()->zones.size(), 1u);
  EXPECT_NEAR(sim.contact()->elements.front().gap, 0.02, 1e-12);
  EXPECT_DOUBLE_EQ(sim.detection_parameters().proximity_distance, 0.3);
  Recorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  ASSERT_EQ(recorder.records.size(), 4u);
  // The end of a moves 0.5 mm away from b: the zone shrinks to the part near the clamped roots.
  for (const StepRecord& r : recorder.records) EXPECT_EQ(r.zones, 1);
  EXPECT_LT(recorder.records.back().contact_elements, recorder.records.front().contact_elements);
  EXPECT_EQ(recorder.records.back().contact_elements, static_cast<int>(sim.contact()->elements.size()));
  const contact::ProximityZone& z = sim.contact()->zones[0];
  EXPECT_DOUBLE_EQ(z.a, 0.0);
  EXPECT_LT(z.b, 10.0);
}

TEST(SimulationContact, NoContactSectionNoDetection) {
  Simulation sim(scenario::parse_scenario(pair_scenario(""), "pair.yaml"));
  EXPECT_EQ(sim.contact(), nullptr);
  Recorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  for (const StepRecord& r : recorder.records) EXPECT_EQ(r.zones, 0);
}

TEST(SimulationContact, InconsistentResolvedLengthsAreRefusedInOneLine) {
  // delta_prox defaults to 3 R = 0.3 mm, above the separation distance given.
  try {
    Simulation sim(
        scenario::parse_scenario(pair_scenario("contact: {separation_distance: 0.25}\n"), "pair.yaml"));
    FAIL() << "expected a ScenarioError";
  } catch (const scenario::ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos);
    EXPECT_EQ(message.rfind("pair.yaml: contact: separation_distance 0.25 mm", 0), 0u) << message;
  }
}

TEST(SimulationContact, TheFrictionTangentFollowsItsKeyNotTheLinearSolver) {
  const auto coupling = [](const std::string& sections) {
    return Simulation(scenario::parse_scenario(pair_scenario(sections), "pair.yaml"))
        .contact_laws()
        .friction_normal_coupling;
  };
  // umfpack alone used to switch on the tangent with R_N varying; now only the key does.
  EXPECT_FALSE(coupling("contact: {friction: 0.3}\nsolver: {linear_solver: umfpack}\n"));
  EXPECT_FALSE(coupling("contact: {friction: 0.3}\n"));
  EXPECT_TRUE(
      coupling("contact: {friction: 0.3, friction_tangent: varying}\nsolver: {linear_solver: umfpack}\n"));
}

TEST(SimulationContact, TheSolutionDoesNotDependOnTheLinearSolver) {
  // Rod a pressed onto rod b and dragged along it with friction (8 elements a rod, for the sanitizer build's
  // sake): every solver factorises the same tangents, so the runs take the same steps and iterations and end
  // in the same state, to the solvers' rounding.
  const auto run = [](const std::string& sections) {
    std::string text = pair_scenario(sections);
    const std::string away = "a_end: {translation: [0, 0.5, 0]}";
    text.replace(text.find(away), away.size(), "a_end: {translation: [0.2, -0.03, 0]}");
    for (std::size_t at; (at = text.find("elements: 20")) != std::string::npos;)
      text.replace(at, 12, "elements: 8");
    Simulation sim(scenario::parse_scenario(text, "pair.yaml"));
    Recorder recorder;
    const RunSummary summary = sim.run({&recorder});
    EXPECT_TRUE(summary.converged) << sections << summary.failure;
    EXPECT_GT(recorder.records.back().contact_elements, 0) << sections;
    return std::make_tuple(summary.steps, summary.newton_iterations, Eigen::VectorXd(sim.state()));
  };
  const auto check = [](const auto& reference, const auto& other, const std::string& what) {
    EXPECT_EQ(std::get<0>(other), std::get<0>(reference)) << what;
    EXPECT_EQ(std::get<1>(other), std::get<1>(reference)) << what;
    EXPECT_LT((std::get<2>(other) - std::get<2>(reference)).template lpNorm<Eigen::Infinity>(), 1e-9) << what;
  };
  // The symmetric tangent: CHOLMOD's LL^T (the default) against MUMPS's LDL^T and UMFPACK's LU.
  const auto frozen = run("contact: {friction: 0.3}\n");
  check(frozen, run("contact: {friction: 0.3}\nsolver: {linear_solver: mumps}\n"), "mumps, frozen");
  check(frozen, run("contact: {friction: 0.3}\nsolver: {linear_solver: umfpack}\n"), "umfpack, frozen");
  check(frozen, run("contact: {friction: 0.3}\nsolver: {linear_solver: klu}\n"), "klu, frozen");
  // The varying friction tangent, not symmetric: UMFPACK's LU against MUMPS's and KLU's.
  const std::string varying = "contact: {friction: 0.3, friction_tangent: varying}\nsolver: {linear_solver: ";
  const auto umfpack = run(varying + "umfpack}\n");
  check(umfpack, run(varying + "mumps}\n"), "mumps, varying");
  check(umfpack, run(varying + "klu}\n"), "klu, varying");
}

/// Rod a along x, 0.45 mm above rod b along y (R = 0.1 mm, delta_prox 0.3 mm: no proximity between them),
/// both ends of a driven 0.9 mm down in one step, b clamped at both ends: the step takes a's axis through
/// b's.
std::string drive_through_scenario(const std::string& contact) {
  return R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: a, material: m, radius: 0.1, length: 4, elements: 8, start: [-2, 0, 0.45]}
  - {name: b, material: m, radius: 0.1, length: 4, elements: 8, start: [0, -2, 0], direction: [0, 1, 0]}
conditions:
  - {name: a_start, type: motion, beam: a, at: start}
  - {name: a_end, type: motion, beam: a, at: end}
  - {name: b_start, type: clamp, beam: b, at: start}
  - {name: b_end, type: clamp, beam: b, at: end}
stages:
  - name: down
    steps: 1
    motions:
      a_start: {translation: [0, 0, -0.9]}
      a_end: {translation: [0, 0, -0.9]}
)" + contact;
}

/// Height of a's middle above b's middle at the end of a run [mm].
double height_of_a_over_b(const Simulation& sim) {
  const model::Model& m = sim.model();
  const auto z = [&](int beam) { return sim.state()(beam::kNodeDofs * m.beam(beam).node(8) + 2); };
  return z(0) - z(1);
}

TEST(SimulationContact, TheCrossingGuardCutsBackAStepThatPassesThrough) {
  // Without the guard the step converges with a's axis 0.45 mm below b's: the rods passed through each
  // other, and at both ends of the step they lie beyond delta_prox, where no contact element looks.
  Simulation through(
      scenario::parse_scenario(drive_through_scenario("contact: {crossing_guard: false}\n"), "x.yaml"));
  Recorder unguarded;
  ASSERT_TRUE(through.run({&unguarded}).converged);
  ASSERT_EQ(unguarded.records.size(), 1u);
  EXPECT_NEAR(height_of_a_over_b(through), -0.45, 1e-9);
  // With it (the default) the step is cut back until the rods come into contact, and a rests on b.
  Simulation guarded(scenario::parse_scenario(drive_through_scenario("contact: {}\n"), "x.yaml"));
  Recorder recorder;
  const RunSummary summary = guarded.run({&recorder});
  ASSERT_TRUE(summary.converged) << summary.failure;
  EXPECT_GT(recorder.records.front().cutbacks, 0);
  EXPECT_GT(recorder.records.back().contact_elements, 0);
  // The middles 2 R apart, less the penetration (p_max = 0.002 mm) and the sections' contraction under the
  // contact pressure (the 9-dof beam's directors stretch).
  EXPECT_NEAR(height_of_a_over_b(guarded), 0.2, 0.01);
  // No cutback allowed: the run stops and says where the axes crossed, half way through the step.
  Simulation stopped(
      scenario::parse_scenario(drive_through_scenario("contact: {}\nsolver: {max_cutbacks: 0}\n"), "x.yaml"));
  const RunSummary failed = stopped.run({});
  EXPECT_FALSE(failed.converged);
  EXPECT_NE(failed.failure.find(
                "the axes of beams 'a' at s = 2 mm and 'b' at s = 2 mm passed through each other at "
                "0.5 of the step"),
            std::string::npos)
      << failed.failure;
}

/// A beam along x (R = 0.1 mm, held at its ends, free to turn about its axis) and a rigid tool across it
/// along y (R = 0.2 mm) pressed onto it (`press`), then dragged across it with friction, which turns the
/// beam's sections about x (`drag`); each stage takes `press_line` and `drag_line` (its own particles, or
/// nothing), the contact section the particles `particles`.
std::string press_and_drag_scenario(const std::string& press_line, const std::string& drag_line,
                                    const std::string& particles) {
  return R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: m, radius: 0.1, length: 10, elements: 8, start: [-5, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: m, radius: 0.2, length: 2, elements: 2, start: [0, -1, 0.31], direction: [0, 1, 0],
     director1: [1, 0, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool}
stages:
  - name: press
    steps: 2
)" + press_line +
         R"(    motions:
      press: {translation: [0, 0, -0.1]}
  - name: drag
    steps: 3
)" + drag_line +
         R"(    motions:
      press: {translation: [0, 0.3, -0.1]}
solver: {linear_solver: umfpack}
contact: {self_contact: false, friction: 0.3, friction_tangent: varying, particles: )" +
         particles + "}\n";
}

TEST(SimulationContact, AStageTakesItsOwnParticles) {
  const auto run = [](const std::string& press_line, const std::string& drag_line,
                      const std::string& particles) {
    Simulation sim(
        scenario::parse_scenario(press_and_drag_scenario(press_line, drag_line, particles), "p.yaml"));
    Recorder recorder;
    const RunSummary summary = sim.run({&recorder});
    EXPECT_TRUE(summary.converged) << press_line << drag_line << particles << ": " << summary.failure;
    EXPECT_GT(recorder.records.back().contact_elements, 0);
    return std::make_pair(summary.newton_iterations, Eigen::VectorXd(sim.state()));
  };
  // The stages' own particles give the run of the contact section that says the same, to the last bit, and a
  // stage without its own takes the contact section's again after one with.
  const auto facing_then_centres = run("", "    particles: centres\n", "facing");
  const auto same = run("    particles: facing\n", "", "centres");
  EXPECT_EQ(same.first, facing_then_centres.first);
  EXPECT_EQ((same.second - facing_then_centres.second).lpNorm<Eigen::Infinity>(), 0.0);
  // The choice matters here: the sections turn under the friction moment, and the fixed particles, carried
  // with them, are not where the facing ones are; at the crossing the centres' direction is not the normal.
  const auto facing = run("", "", "facing");
  const auto fixed_then_facing = run("    particles: fixed\n", "", "facing");
  const auto facing_then_fixed = run("", "    particles: fixed\n", "facing");
  EXPECT_GT((facing.second - facing_then_centres.second).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_GT((facing.second - fixed_then_facing.second).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_GT((facing.second - facing_then_fixed.second).lpNorm<Eigen::Infinity>(), 1e-9);
}

}  // namespace
}  // namespace nodus::simulation
