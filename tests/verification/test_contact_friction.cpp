// Regularised Coulomb friction between beams [Durville 2012, Sect. 5.2, Eq. 55-64], each case against a
// reference the program does not produce: closed-form beam stiffnesses for stick, the support reactions for
// slip (sliding force = mu times the normal force, both measured at the supports), and the geometry of the
// converged states for the absence of pass-through.
//
// Beams: R = 0.1 mm, E = 4000 MPa, nu = 0.3. The 9-dof beam has the Euler-Bernoulli bending stiffness E I,
// the Timoshenko shear stiffness G A (the section-constant shear strain, shear factor 1) and the torsion
// stiffness (E / 2) J (docs/model.md: "Torsion stiffness is (E/2) J").

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {
namespace {

constexpr double kLength = 10.0, kRadius = 0.1, kYoung = 4000.0, kPoisson = 0.3;
constexpr double kMu = 0.3;
const double kArea = std::numbers::pi * kRadius * kRadius;
const double kInertia = std::numbers::pi * std::pow(kRadius, 4) / 4.0;  // I, bending
const double kPolar = 2.0 * kInertia;                                   // J, torsion
const double kShearModulus = kYoung / (2.0 * (1.0 + kPoisson));

class Recorder : public simulation::StepObserver {
 public:
  std::vector<simulation::StepRecord> records;
  std::vector<Eigen::VectorXd> states;
  std::vector<std::vector<simulation::ContactState>> contacts;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    records.push_back(r);
    states.push_back(sim.state());
    contacts.push_back(sim.contact_states());
  }
};

/// Contact elements that carry a normal reaction, and how many of them slide.
struct Carrying {
  int loaded = 0, slipping = 0;
  Eigen::Vector3d friction_on_j = Eigen::Vector3d::Zero();  ///< sum of the friction forces on beam J [N]
};

Carrying carrying(const std::vector<simulation::ContactState>& states) {
  Carrying c;
  for (const simulation::ContactState& s : states) {
    c.friction_on_j += s.tangential;
    if (!(s.normal_reaction > 0.0)) continue;
    ++c.loaded;
    if (s.slip) ++c.slipping;
  }
  return c;
}

// ---------------------------------------------------------------------------------------------------------
// 1 and 3. Two beams crossing at 90 degrees, pressed together, then the upper one dragged along the lower
// one.
// ---------------------------------------------------------------------------------------------------------

constexpr double kGap0 = 0.01;      // initial surface gap [mm]
constexpr double kPress = 0.05;     // downward support displacement of the upper beam [mm]
constexpr double kStickX = 0.004;   // support displacement along x at the end of the stick stage [mm]
constexpr double kSlideX = 0.03;    // ... at the end of the slide stage [mm]
constexpr int kCrossingStages = 4;  // press, stick, hold, slide

/// The crossing of test_contact_crossing with 100 elements per beam (h_c = 0.05 mm, the grid shifted onto the
/// crossing). Lower beam (I) along x, pinned at x = -5 (twist held), on a roller at x = +5 (y, z held): x is
/// held at one end only. Upper beam (J) along y, pinned at y = -5 (twist held by g1z), roller at y = +5 (x, z
/// held): simply supported both in z and in x. press: the upper supports down by kPress; stick: along x by
/// kStickX (short of sliding, see below); hold: no motion (two steps, each with a new detection); slide:
/// along x to kSlideX, 0.002 mm = 2 g_rev_max per nominal step.
const char* kCrossing = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: lower, material: m, radius: 0.1, length: 10, elements: 100, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: upper, material: m, radius: 0.1, length: 10, elements: 100, start: [0, -5, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: l0, type: clamp, beam: lower, at: start, dofs: [position, g1z]}
  - {name: l1, type: clamp, beam: lower, at: end, dofs: [y, z]}
  - {name: u0, type: motion, beam: upper, at: start, dofs: [position, g1z]}
  - {name: u1, type: motion, beam: upper, at: end, dofs: [x, z]}
stages:
  - name: press
    steps: 5
    motions:
      u0: {translation: [0, 0, -0.05]}
      u1: {translation: [0, 0, -0.05]}
  - name: stick
    steps: 8
    motions:
      u0: {translation: [0.004, 0, -0.05]}
      u1: {translation: [0.004, 0, -0.05]}
  - name: hold
    steps: 2
    motions:
      u0: {translation: [0.004, 0, -0.05]}
      u1: {translation: [0.004, 0, -0.05]}
  - name: slide
    steps: 13
    motions:
      u0: {translation: [0.03, 0, -0.05]}
      u1: {translation: [0.03, 0, -0.05]}
contact: {self_contact: false, friction: 0.3}
)";

/// Support displacement of the upper beam along x at load time t (each stage lasts 1 s).
double crossing_shift(double t) {
  if (t <= 1.0) return 0.0;
  if (t <= 2.0) return kStickX * (t - 1.0);
  if (t <= 3.0) return kStickX;
  return kStickX + (kSlideX - kStickX) * (t - 3.0);
}

/// Compliance of the two beams at the crossing for a tangential force T along x, one on each beam at the
/// particles, i.e. at the surfaces [mm/N]:
/// - upper beam, loaded across its length at mid-span, simply supported in x: bending L^3 / (48 E I) and
///   shear L / (4 G A); T acts at distance R below its axis, a torque T R about its axis carried by the half
///   beam from the twist-held end, which turns the contact point along T by R^2 (L / 2) / ((E / 2) J);
/// - lower beam, loaded along its axis: the half from its pinned end in tension, (L / 2) / (E A); T acts at R
///   above its axis, a moment T R at mid-span of the simply supported beam, which turns the section by
///   T R L / (12 E I) and moves the contact point along T by R^2 L / (12 E I).
/// The beams are in series with each other and with the regularised friction law (below).
double crossing_structural_compliance() {
  const double upper = std::pow(kLength, 3) / (48.0 * kYoung * kInertia) +
                       kLength / (4.0 * kShearModulus * kArea) +
                       kRadius * kRadius * (kLength / 2.0) / (0.5 * kYoung * kPolar);
  const double lower =
      (kLength / 2.0) / (kYoung * kArea) + kRadius * kRadius * kLength / (12.0 * kYoung * kInertia);
  return upper + lower;
}

class CrossingFriction : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim_ = new VerifiedSimulation(scenario::parse_scenario(kCrossing, "crossing_friction.yaml"));
    recorder_ = new Recorder;
    converged_ = sim_->run({recorder_}).converged;
  }
  static void TearDownTestSuite() {
    delete recorder_;
    delete sim_;
  }
  /// The upper beam's support reactions: along x (the friction force it carries) and -z (the normal force).
  static double friction_x(const simulation::StepRecord& r) {
    return r.sections[2].force.x() + r.sections[3].force.x();
  }
  static double normal(const simulation::StepRecord& r) {
    return -(r.sections[2].force.z() + r.sections[3].force.z());
  }
  /// Index of the last step of the press stage.
  static std::size_t press_end() {
    std::size_t k = 0;
    while (k + 1 < recorder_->records.size() && recorder_->records[k + 1].stage == 0) ++k;
    return k;
  }
  /// Support shift at which the stick law reaches mu N (N and the friction at the end of the press).
  static double saturation_shift() {
    const simulation::StepRecord& p = recorder_->records[press_end()];
    const double g_rev_max = sim_->contact_laws().friction->max_reversible;
    const double compliance = crossing_structural_compliance() + g_rev_max / (kMu * normal(p));
    return (kMu * normal(p) - friction_x(p)) * compliance;
  }

  static VerifiedSimulation* sim_;
  static Recorder* recorder_;
  static bool converged_;
};

VerifiedSimulation* CrossingFriction::sim_ = nullptr;
Recorder* CrossingFriction::recorder_ = nullptr;
bool CrossingFriction::converged_ = false;

TEST_F(CrossingFriction, SticksWithTheBeamStiffnessThenSlidesAtMuN) {
  ASSERT_TRUE(converged_);
  const std::vector<simulation::StepRecord>& records = recorder_->records;
  ASSERT_EQ(records.back().stage, kCrossingStages - 1);
  ASSERT_TRUE(sim_->contact_laws().friction.has_value());
  const double g_rev_max = sim_->contact_laws().friction->max_reversible;
  const double p_max = sim_->contact_laws().max_penetration;
  const std::size_t k0 = press_end();
  // The press already leaves a small friction force (0.7 % of mu N): the axes do not stretch, so as they bend
  // the mid-spans move towards the pinned ends by the integral of w'^2 / 2 (4.4e-5 mm), the lower one along
  // -x and the upper one along -y. The stick law below is for the force added from there on.
  const double n_press = normal(records[k0]), t_press = friction_x(records[k0]);
  const double shift_sat = saturation_shift();

  // The press stage: the crossing formula of test_contact_crossing with the shear compliance of each beam,
  // F = (delta - g0 - p) / (2 (L^3 / (48 E I) + L / (4 G A))). 0.5 %: as there (the contact element sits on
  // the crossing; (R / L)^2 = 1e-4 effects of the 9-dof beam).
  const double press_compliance =
      2.0 * (std::pow(kLength, 3) / (48.0 * kYoung * kInertia) + kLength / (4.0 * kShearModulus * kArea));
  const double press_reference = (kPress - kGap0 - records[k0].penetration_ratio * p_max) / press_compliance;
  std::printf("press: N = %.6e N (supports), reference %.6e N, error %.3f %%\n", n_press, press_reference,
              100.0 * (n_press / press_reference - 1.0));
  EXPECT_NEAR(n_press, press_reference, 5e-3 * press_reference);
  std::printf("stick law reaches mu N at a support shift of %.5f mm (g_rev_max = %.5f mm)\n", shift_sat,
              g_rev_max);

  int stick_steps = 0, slip_steps = 0;
  for (std::size_t k = k0 + 1; k < records.size(); ++k) {
    const simulation::StepRecord& r = records[k];
    const Carrying c = carrying(recorder_->contacts[k]);
    const double shift = crossing_shift(r.time), n = normal(r), t = friction_x(r);
    // Stick: T = T_press + shift / (c_beams + g_rev_max / (mu N)), with the compliance of the regularised law
    // (force mu N g_rev / g_rev_max on g_rev) in series with the beams'.
    const double compliance = crossing_structural_compliance() + g_rev_max / (kMu * n);
    const double stick_reference = t_press + shift / compliance;
    std::printf(
        "t %.4f shift %.5f mm: T = %.6e N (supports), stick law %.6e N, mu N = %.6e N, T / mu N = %.5f; "
        "N change %.2e; slipping %d of %d; Newton %d, detections %d, normal iterations %d, cutbacks %d\n",
        r.time, shift, t, stick_reference, kMu * n, t / (kMu * n), n / n_press - 1.0, c.slipping, c.loaded,
        r.newton_iterations, r.detections, r.normal_iterations, r.cutbacks);
    EXPECT_EQ(r.slipping, c.slipping);
    EXPECT_GE(c.loaded, 1);
    // Friction is the only x force on the upper beam, so its x reactions equal the friction force on it
    // (-friction_on_j), and the lower beam's only x support (l0) carries it back. 1e-3: the solver's force
    // floor, 6.4e-9 N, is 1e-4 of mu N.
    EXPECT_NEAR(-c.friction_on_j.x(), t, 1e-3 * kMu * n);
    EXPECT_NEAR(r.sections[0].force.x() + r.sections[1].force.x(), -t, 1e-3 * kMu * n);
    // The normal force stays as pressed, up to the geometric stiffening of the lower beam: friction puts its
    // half between l0 and the crossing in tension mu N, which changes its bending compliance by at most
    // mu N / (pi^2 E I / L^2) = 2.8e-3; the lower beam is half of the compliance.
    EXPECT_NEAR(n, n_press,
                kMu * n_press * kLength * kLength /
                    (std::numbers::pi * std::numbers::pi * kYoung * kInertia) * n_press);
    if (shift <= 0.98 * shift_sat) {
      ++stick_steps;
      EXPECT_EQ(r.slipping, 0);
      // 0.5 %: the reference is linear elasticity of the beams and the friction law; what it leaves out is
      // the history lost where a new particle on the lower beam lies between the loaded old one and an
      // unloaded neighbour (the crossing moves by about 8e-5 mm per step against 0.05 mm between
      // particles: below 0.1 % of T over the stage) and the (R / L)^2 = 1e-4 effects of the 9-dof beam.
      EXPECT_NEAR(t, stick_reference, 5e-3 * (stick_reference - t_press));
    } else if (shift >= 1.02 * shift_sat) {
      ++slip_steps;
      EXPECT_EQ(c.slipping, c.loaded);
      // Sliding: the x reaction is mu times the normal force, both at the supports. 1e-3 (tighter than
      // 1 %): the force floor of the solver (1e-4 of mu N) and the direction of sliding, which keeps
      // the y component of the press stage's friction (about 1 % of mu N, so cos = 1 - 5e-5).
      EXPECT_NEAR(t, kMu * n, 1e-3 * kMu * n);
    }
  }
  EXPECT_GE(stick_steps, 8);  // the stick and hold stages, and the first slide step
  EXPECT_GE(slip_steps, 8);
}

/// The crossing run with `contact` as its contact section; the sliding steps' ratio T / N at the upper beam's
/// supports (friction force over normal force), one per step of `slide` past twice the saturation shift.
/// `slipping`: every pressing element slips there (false where there is no friction, and so no slip).
std::vector<double> crossing_slide_ratios(const std::string& contact, bool slipping = true) {
  std::string text = kCrossing;
  const std::string original = "contact: {self_contact: false, friction: 0.3}\n";
  text.replace(text.find(original), original.size(), contact);
  VerifiedSimulation sim(scenario::parse_scenario(text, "crossing_pairs.yaml"));
  Recorder recorder;
  EXPECT_TRUE(sim.run({&recorder}).converged);
  std::vector<double> ratios;
  for (std::size_t k = 0; k < recorder.records.size(); ++k) {
    const simulation::StepRecord& r = recorder.records[k];
    if (r.stage != kCrossingStages - 1 || crossing_shift(r.time) < 2.0 * kStickX) continue;
    const double t = r.sections[2].force.x() + r.sections[3].force.x();
    const double n = -(r.sections[2].force.z() + r.sections[3].force.z());
    EXPECT_GT(n, 0.0);
    const Carrying c = carrying(recorder.contacts[k]);
    EXPECT_GE(c.loaded, 1);
    EXPECT_EQ(c.slipping, slipping ? c.loaded : 0);
    ratios.push_back(t / n);
  }
  return ratios;
}

// contact.friction_pairs: the pair's coefficient replaces contact.friction for the contacts between its
// beams. The slide of the crossing, where T = mu N at the supports (above), measures which mu acted.
TEST(ContactFriction, APairOfBeamsSlidesWithItsOwnCoefficient) {
  // Another coefficient for the pair than the default (which then acts nowhere here).
  const std::vector<double> own = crossing_slide_ratios(
      "contact:\n  self_contact: false\n  friction: 0.6\n"
      "  friction_pairs: [{beams: [upper], with: [lower], friction: 0.15}]\n");
  ASSERT_GE(own.size(), 8u);
  for (double ratio : own) EXPECT_NEAR(ratio, 0.15, 1e-3 * 0.15);  // 1e-3 as in the test above
  // Frictionless by default, the pair's friction from its entry alone.
  const std::vector<double> only = crossing_slide_ratios(
      "contact:\n  self_contact: false\n  friction_pairs: [{beams: [lower], friction: 0.3}]\n");
  ASSERT_GE(only.size(), 8u);
  for (double ratio : only) EXPECT_NEAR(ratio, 0.3, 1e-3 * 0.3);
  // A frictionless pair among frictional beams: no tangential force at all.
  const std::vector<double> none = crossing_slide_ratios(
      "contact:\n  self_contact: false\n  friction: 0.3\n"
      "  friction_pairs: [{beams: [lower, upper], friction: 0}]\n",
      false);
  ASSERT_GE(none.size(), 8u);
  // What x force is left comes with the normal, which tilts with the bent lower beam's slope where the upper
  // one crosses it (T / N from 1.4e-5 to 2e-5): far below the default's 0.3.
  for (double ratio : none) EXPECT_NEAR(ratio, 0.0, 1e-4);
}

TEST_F(CrossingFriction, StickSurvivesRedetection) {
  ASSERT_TRUE(converged_);
  const std::vector<simulation::StepRecord>& records = recorder_->records;
  const double shift_sat = saturation_shift();
  // The stick steps, from the end of the press (shift 0) on: T is linear in the support shift (the previous
  // test checks the slope), across the stage boundaries press | stick | hold | slide. Every step starts with
  // a new detection and installs new contact elements; loop 2 installs further sets (detections > 1). A lost
  // history lets the friction spring relax at each detection: the beams keep their elastic deflection, so T
  // drops by the spring's share of the compliance, g_rev_max / (mu N) / c_total = 15 % of T, at every step
  // (measured with the history zeroed in install(): 8 % of a step's increment off the line, at every step).
  std::vector<std::size_t> stick;
  for (std::size_t k = 0; k < records.size(); ++k)
    if (records[k].stage > 0 || k == press_end())
      if (crossing_shift(records[k].time) <= 0.98 * shift_sat) stick.push_back(k);
  ASSERT_GE(stick.size(), 10u);
  int redetected = 0, boundaries = 0;
  for (std::size_t i = 1; i + 1 < stick.size(); ++i) {
    const std::size_t a = stick[i - 1], k = stick[i], b = stick[i + 1];
    const double sa = crossing_shift(records[a].time), sk = crossing_shift(records[k].time),
                 sb = crossing_shift(records[b].time);
    const double ta = CrossingFriction::friction_x(records[a]), tk = CrossingFriction::friction_x(records[k]),
                 tb = CrossingFriction::friction_x(records[b]);
    if (records[k].detections > 1) ++redetected;
    if (records[k].stage != records[a].stage) ++boundaries;
    double deviation = 0.0, scale = 0.0;
    if (sb - sa > 1e-12) {  // compare with the line through the neighbours
      deviation = tk - (ta + (tb - ta) * (sk - sa) / (sb - sa));
      scale = 0.5 * std::abs(tb - ta);  // about one step's increment of T
    } else {                            // hold: no motion, T must not move
      deviation = tk - ta;
      scale = std::abs(CrossingFriction::friction_x(records[stick[1]]) -
                       CrossingFriction::friction_x(records[stick[0]]));  // the first stick increment
    }
    std::printf(
        "t %.4f (stage %d): T = %.6e N, off the neighbours' line by %.2e N = %.3f %% of a step's increment; "
        "detections %d\n",
        records[k].time, records[k].stage, tk, deviation, 100.0 * deviation / scale, records[k].detections);
    // 1 % of a step's increment of T: the history interpolation loses, per detection, the fraction
    // shift / (2 spacing) of g_rev where a new particle on the lower beam lies between the loaded old one and
    // an unloaded neighbour (8e-5 mm against 0.05 mm here: 0.1 % of g_rev, of which the friction spring's
    // 15 % shows in T, well below 0.1 % of an increment); a lost history moves T by 8 % of an increment.
    EXPECT_LE(std::abs(deviation), 1e-2 * scale);
  }
  EXPECT_GE(redetected, 3);  // steps where loop 2 installed a further set of contact elements
  // press -> stick and stick -> hold (hold -> slide enters as the last hold step's neighbour).
  EXPECT_GE(boundaries, 2);
}

// ---------------------------------------------------------------------------------------------------------
// 2. A beam pressed along a line onto a straight rigid beam, then pulled along its axis.
// ---------------------------------------------------------------------------------------------------------

constexpr double kLineLoad = 0.01;  // normal force per length [N/mm]
constexpr int kParallelElements = 40;
constexpr double kPullStick = 0.0008;  // pulled end displacement at the end of the stick stage [mm]
constexpr double kPullSlide = 0.02;    // ... at the end of the slide stage [mm]

/// The lower beam is a rigid tool (12 mm, past both ends of the upper one). The upper beam (10 mm, 40
/// elements, h_c = 0.125 mm) starts overlapping it by 1e-6 mm (so that the contact stiffness is not zero when
/// the load comes) and is pressed by dead loads at every node, with the weights of Simpson's rule (h/6, 4h/6,
/// 2h/6, ...) so that the line load is uniform, kLineLoad L in all. Its end is held in x, y and twist (g1z)
/// and pulled along x, its start held in y. press: the loads; stick: pull by kPullStick (< g_rev_max); slide:
/// pull to kPullSlide.
std::string parallel_scenario() {
  std::string s = fmt::format(R"(
materials:
  - {{name: m, young_modulus: 4000, poisson_ratio: 0.3}}
beams:
  - {{name: tool, material: m, radius: 0.1, length: 12, elements: 24, start: [-1, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}}
  - {{name: upper, material: m, radius: 0.1, length: 10, elements: {}, start: [0, 0, 0.199999],
     direction: [1, 0, 0], director1: [0, 1, 0]}}
conditions:
  - {{name: base, type: rigid, beam: tool}}
  - {{name: pull, type: motion, beam: upper, at: end, dofs: [x, y, g1z]}}
  - {{name: guide, type: clamp, beam: upper, at: start, dofs: [y]}}
)",
                              kParallelElements);
  const double h = kLength / kParallelElements;
  std::string loads;
  for (int n = 0; n <= 2 * kParallelElements; ++n) {
    const double weight = n % 2 == 1 ? 4.0 : (n == 0 || n == 2 * kParallelElements ? 1.0 : 2.0);
    s += fmt::format("  - {{name: q{0}, type: load, beam: upper, at: {0}}}\n", n);
    loads += fmt::format("      q{}: {{force: [0, 0, {:.17g}]}}\n", n, -kLineLoad * weight * h / 6.0);
  }
  s += "stages:\n  - name: press\n    steps: 4\n    loads:\n" + loads;
  s += fmt::format("  - name: stick\n    steps: 4\n    motions:\n      pull: {{translation: [{}, 0, 0]}}\n",
                   kPullStick);
  s += fmt::format("  - name: slide\n    steps: 10\n    motions:\n      pull: {{translation: [{}, 0, 0]}}\n",
                   kPullSlide);
  s += "contact: {self_contact: false, friction: 0.3}\n";
  return s;
}

TEST(ContactFriction, ParallelBeamSlidesAtMuTimesTheNormalForce) {
  VerifiedSimulation sim(scenario::parse_scenario(parallel_scenario(), "parallel_friction.yaml"));
  Recorder recorder;
  ASSERT_TRUE(sim.run({&recorder}).converged);
  const std::vector<simulation::StepRecord>& records = recorder.records;
  const double g_rev_max = sim.contact_laws().friction->max_reversible;
  const double total = kLineLoad * kLength;  // the applied normal force [N]
  const double axial = kYoung * kArea;       // E A [N]

  // Stick: a bar on the elastic foundation of the regularised friction law, stiffness k = mu q / g_rev_max
  // per length, pulled at one end, free at the other (shear lag): EA u'' = k u, u(L) = u0, N(0) = 0, so the
  // pulling force is EA lambda tanh(lambda L) u0 with lambda = sqrt(k / EA). The friction acts on the
  // bottom fibre, R below the axis; the moment it makes is taken up by the pressure on the foundation, not
  // by bending (interior of a beam on a stiff foundation), so the fibre moves with the axis.
  const double lambda = std::sqrt(kMu * kLineLoad / g_rev_max / axial);
  const double stick_stiffness = axial * lambda * std::tanh(lambda * kLength);
  // Full slip once the far end has moved by g_rev_max: the bar then stretches by mu q L^2 / (2 EA).
  const double full_slip = g_rev_max + kMu * kLineLoad * kLength * kLength / (2.0 * axial);
  std::size_t k0 = 0;
  while (records[k0 + 1].stage == 0) ++k0;
  // The press leaves a small axial force at the pulled end (0.7 % of mu N, the bottom fibre of the upper beam
  // moving as it bends under the nodal loads); the stick law is for the force added from there on.
  const double pull_press = records[k0].sections[1].force.x();
  std::printf("shear-lag stiffness %.4f N/mm; full slip from a pull of %.5f mm\n", stick_stiffness,
              full_slip);

  int stick_steps = 0, slip_steps = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const simulation::StepRecord& r = records[k];
    const Carrying c = carrying(recorder.contacts[k]);
    const double pull = r.stage == 0   ? 0.0
                        : r.stage == 1 ? kPullStick * (r.time - 1.0)
                                       : kPullStick + (kPullSlide - kPullStick) * (r.time - 2.0);
    // The measurements: the normal force as the tool's reaction normal to the beams (z), the sliding force
    // as the axial reaction of the pulled end.
    const double normal = r.sections[0].force.z(), sliding = r.sections[1].force.x();
    std::printf(
        "t %.3f pull %.5f mm: N = %.6e N (tool), applied %.6e N; pull force %.6e N, mu N %.6e N, ratio %.5f; "
        "stick law %.6e N; slipping %d of %d; Newton %d, detections %d, normal iterations %d, cutbacks %d\n",
        r.time, pull, normal, r.time >= 1.0 ? total : total * r.time, sliding, kMu * normal,
        sliding / (kMu * normal), pull_press + stick_stiffness * pull, c.slipping, c.loaded,
        r.newton_iterations, r.detections, r.normal_iterations, r.cutbacks);
    if (r.stage == 0) continue;
    // The normal force is the applied load: the upper beam has no support in z. 1e-4: the solver's residual
    // tolerance is 1e-8 of the forces, its floor 1e-6 N.
    EXPECT_NEAR(normal, total, 1e-4 * total);
    // The tool carries the friction back along x.
    EXPECT_NEAR(r.sections[0].force.x(), -sliding, 1e-4 * total);
    if (r.stage == 1) {
      ++stick_steps;
      EXPECT_EQ(r.slipping, 0);
      // 1 %: the closed form takes a uniform pressure; the contact elements are 0.125 mm apart against a
      // decay length 1 / lambda = 6.5 mm ((lambda h_c)^2 / 12 = 3e-5), but within about the foundation length
      // (4 E I / k_n)^(1/4) = 0.6 mm of each end the pressure is not uniform, and the pulled end is where the
      // shear lag weights the friction stiffness most (lambda 0.6 mm = 9 % of it).
      const double expected = stick_stiffness * pull;
      EXPECT_NEAR(sliding - pull_press, expected, 1e-2 * expected);
    } else if (pull >= 1.05 * full_slip) {
      ++slip_steps;
      EXPECT_GE(c.loaded, 2 * kParallelElements - 8);  // a line contact: elements all along the beam
      EXPECT_EQ(c.slipping, c.loaded);
      // 1e-3 (tighter than 1 %): the normal is e_z to the slope of the upper beam between the loaded nodes
      // (below 1e-4 rad) and the solver's residual tolerance is 1e-8 of the forces.
      EXPECT_NEAR(sliding, kMu * normal, 1e-3 * kMu * normal);
    }
  }
  EXPECT_GE(stick_steps, 4);
  EXPECT_GE(slip_steps, 8);
}

// ---------------------------------------------------------------------------------------------------------
// 4. The crossing driven hard: the upper supports down by 1 mm = 10 R in 5 nominal steps of 2 R.
// ---------------------------------------------------------------------------------------------------------

/// The crossing of tests 1 and 3 with 60 elements per beam (h_c = 0.083 mm, the grid shifted onto the
/// crossing), mu = 0.3, the upper supports driven down by 1 mm: each beam deflects by about 0.5 mm.
const char* kHardCrossing = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: lower, material: m, radius: 0.1, length: 10, elements: 60, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: upper, material: m, radius: 0.1, length: 10, elements: 60, start: [0, -5, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: l0, type: clamp, beam: lower, at: start, dofs: [position, g1z]}
  - {name: l1, type: clamp, beam: lower, at: end, dofs: [y, z]}
  - {name: u0, type: motion, beam: upper, at: start, dofs: [position, g1z]}
  - {name: u1, type: motion, beam: upper, at: end, dofs: [x, z]}
stages:
  - name: press
    steps: 5
    motions:
      u0: {translation: [0, 0, -1.0]}
      u1: {translation: [0, 0, -1.0]}
contact: {self_contact: false, friction: 0.3}
)";

/// Point of the axis of beam b at reference abscissa s [mm], by quadratic Lagrange interpolation of the
/// element's three node centres (end, middle, end), computed here from the state vector alone.
Eigen::Vector3d axis_point(const model::Model& model, const Eigen::VectorXd& x, int b, double s) {
  const beam::Beam& beam = model.beam(b);
  const int elements = (beam.num_nodes() - 1) / 2;
  const double h = beam.length() / elements;
  const int e = std::clamp(static_cast<int>(std::floor(s / h)), 0, elements - 1);
  const double xi = 2.0 * (s - e * h) / h - 1.0;
  const auto centre = [&](int local) -> Eigen::Vector3d { return x.segment<3>(9 * beam.node(local)); };
  return 0.5 * xi * (xi - 1.0) * centre(2 * e) + (1.0 - xi * xi) * centre(2 * e + 1) +
         0.5 * xi * (xi + 1.0) * centre(2 * e + 2);
}

/// The smallest distance between the axes of beams 0 and 1: a grid search over both beams, then grids 10
/// times finer around the best pair, down to 5e-5 mm. At a crossing, a sampling offset e on each curve adds
/// e^2 / (2 D) to the distance D: below 1e-8 mm at the finest grid.
double axis_distance(const model::Model& model, const Eigen::VectorXd& x) {
  const double l0 = model.beam(0).length(), l1 = model.beam(1).length();
  double best = INFINITY, s_best = 0.0, t_best = 0.0;
  double step = 0.05, s_lo = 0.0, s_hi = l0, t_lo = 0.0, t_hi = l1;
  for (int level = 0; level < 4; ++level) {
    std::vector<Eigen::Vector3d> on_j;
    for (double t = t_lo; t <= t_hi + 1e-12; t += step) on_j.push_back(axis_point(model, x, 1, t));
    for (double s = s_lo; s <= s_hi + 1e-12; s += step) {
      const Eigen::Vector3d p = axis_point(model, x, 0, s);
      for (std::size_t j = 0; j < on_j.size(); ++j) {
        const double d = (p - on_j[j]).norm();
        if (d < best) {
          best = d;
          s_best = s;
          t_best = t_lo + static_cast<double>(j) * step;
        }
      }
    }
    s_lo = std::max(0.0, s_best - 2.0 * step), s_hi = std::min(l0, s_best + 2.0 * step);
    t_lo = std::max(0.0, t_best - 2.0 * step), t_hi = std::min(l1, t_best + 2.0 * step);
    step /= 10.0;
  }
  return best;
}

TEST(ContactFriction, CrossingDrivenHardNeverPassesThrough) {
  VerifiedSimulation sim(scenario::parse_scenario(kHardCrossing, "hard_crossing.yaml"));
  Recorder recorder;
  const simulation::RunSummary summary = sim.run({&recorder});
  const double p_max = sim.contact_laws().max_penetration;
  // Axis distance at contact R_I + R_J less the penetration, which the penalty keeps below p_max; the
  // particles lie on the section borders, whose shape changes by the Poisson effect (nu E33 R < 1e-6 mm
  // here), so a second p_max is the margin.
  const double limit = 2.0 * kRadius - 2.0 * p_max;
  double smallest = INFINITY;
  for (std::size_t k = 0; k < recorder.records.size(); ++k) {
    const simulation::StepRecord& r = recorder.records[k];
    const double distance = axis_distance(sim.model(), recorder.states[k]);
    double gap = INFINITY;
    for (const simulation::ContactState& c : recorder.contacts[k]) gap = std::min(gap, c.gap);
    smallest = std::min(smallest, distance);
    std::printf(
        "t %.4f (support %.4f mm): axis distance %.6f mm (limit %.6f), smallest gap %.3e mm, penetration "
        "%.3f "
        "p_max, N %.4e N; Newton %d, detections %d, normal iterations %d, cutbacks %d\n",
        r.time, r.time, distance, limit, gap, r.penetration_ratio,
        -(r.sections[2].force.z() + r.sections[3].force.z()), r.newton_iterations, r.detections,
        r.normal_iterations, r.cutbacks);
    EXPECT_GE(distance, limit);
    EXPECT_LE(r.penetration_ratio, 1.0);
    EXPECT_GE(gap, -p_max);
    if (r.time > kGap0 + p_max) {  // the support has moved (1 mm x time) past the initial gap
      EXPECT_GT(r.normal_force, 0.0);
    }
  }
  // Every converged step is checked above, then the run must have reached the end.
  EXPECT_TRUE(summary.converged) << summary.failure;
  ASSERT_FALSE(recorder.records.empty());
  EXPECT_EQ(recorder.records.back().time, 1.0);
  std::printf("smallest axis distance %.6f mm, 2 R - 2 p_max = %.6f mm\n", smallest, limit);
}

}  // namespace
}  // namespace nodus::verification
