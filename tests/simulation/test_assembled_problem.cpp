// The assembled tangent of EquilibriumProblem against central finite differences of its residual, column by
// column over the free unknowns, with every term of the equilibrium present at once: beam internal forces,
// contact with friction (sticking and slipping elements both), a dead force and a moment load (whose load
// stiffness is not symmetric), and the viscous stabilisation drag. Three beams: A along x, clamped at its
// start and loaded at its end; B and C crossing it at 30 degrees, above and below, clamped at their starts.
// The contact geometry (normals, particles) is detected once and held fixed, as during Newton; the committed
// state is the reference, and the evaluated states slide B and C along x, one by more than g_rev_max (its
// contact slips), the other by less (its contact sticks), plus a small random perturbation of every unknown.
// Which elements touch, slip or stick is read from contact::contact_response on the same inputs (the
// problem's own contact_states() is not part of the API these tests hold to).
//
// Only the public API of EquilibriumProblem that is kept: the constructor, set_contact, set_contact_laws,
// set_stabilization, set_time, commit, restore, evaluate, tangent, unknowns, set_unknowns, full_residual,
// size. restore() also puts back the contact elements and penalties that a failed step attempt changed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "nodus/contact/contact_mechanics.hpp"
#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::simulation {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kRadius = 0.1;           // mm, all beams
constexpr double kLift = 0.195;           // mm, axis distance of B and C to A: penetration 5 um
constexpr double kPenalty = 50.0;         // N/mm
constexpr double kRegularization = 0.01;  // p_reg [mm]: the 5 um penetrations lie in the quadratic part
constexpr double kMu = 0.3;
constexpr double kMaxReversible = 1e-3;  // g_rev_max [mm]

/// The model, its conditions and the problem, at the committed reference state.
struct Assembly {
  model::Model model{2, 0.0};
  loading::Conditions conditions;
  std::optional<EquilibriumProblem> problem;
  Eigen::VectorXd reference_unknowns;
  contact::ContactGeometry geometry;  ///< as given to the problem

  /// `eta`: the drag coefficient of the stabilisation [N s/mm^2], constant over the stage [0, 1].
  Assembly(bool exact_friction_tangent, double eta) {
    const beam::ElasticConstants material{4000.0, 0.3};
    const double angle = std::numbers::pi / 6.0;
    const Vec3 along_b(std::cos(angle), std::sin(angle), 0.0),
        along_c(std::cos(angle), -std::sin(angle), 0.0);
    model.add_beam({"A", 4.0, kRadius, 8, Vec3(-2.0, 0.0, 0.0), Vec3::UnitX(), Vec3::UnitY(), material, 1.0});
    model.add_beam(
        {"B", 2.0, kRadius, 4, Vec3(-0.5, 0.0, kLift) - along_b, along_b, Vec3::UnitZ(), material, 1.0});
    model.add_beam(
        {"C", 2.0, kRadius, 4, Vec3(0.8, 0.0, -kLift) - along_c, along_c, Vec3::UnitZ(), material, 1.0});
    const loading::DofMask all{true, true, true, true, true, true, true, true, true};
    for (int b = 0; b < 3; ++b) {
      const int c = conditions.add_motion("clamp", model.beam(b).node(0), all);
      conditions.activate(c, 0.0, model.reference());
    }
    // The end of A: a dead force and a moment about a fixed axis, ramped from 0 at t = 0 to their values at
    // t = 1.
    const Vec3 axis = Vec3(0.3, 1.0, 0.5).normalized();
    const int load = conditions.add_load("end", model.beam(0).node(16), Vec3::Zero(), axis, 0.0);
    conditions.activate(load, 0.0, model.reference());
    conditions.add_load_keyframe(load, 1.0, Vec3(0.0, 0.02, -0.05), 0.01);

    problem.emplace(model, conditions, Tolerances{});
    contact::DetectionParameters given;
    given.self_contact = false;
    const contact::DetectionParameters detection = contact::resolve_parameters(given, model, {});
    geometry = contact::detect(model, model.reference(), detection);
    const std::size_t zones = geometry.zones.size(), elements = geometry.elements.size();
    problem->set_contact(geometry, std::vector<double>(zones, kPenalty),
                         std::vector<Vec3>(elements, Vec3::Zero()));
    contact::ResponseOptions options;
    options.friction_normal_coupling = exact_friction_tangent;
    problem->set_contact_laws(kRegularization, contact::FrictionLaw{kMu, kMaxReversible}, options);
    problem->set_stabilization({0.0, 1.0, eta, eta});
    problem->set_time(0.0);
    problem->commit();
    reference_unknowns = problem->unknowns();
  }
};

/// Global index of each free unknown, in the problem's order: every node but the clamped first one of each
/// beam (the conditions above), node by node.
std::vector<int> free_dofs(const model::Model& m) {
  std::vector<int> dofs;
  for (int b = 0; b < 3; ++b)
    for (int i = 1; i < m.beam(b).num_nodes(); ++i)
      for (int d = 0; d < 9; ++d) dofs.push_back(9 * m.beam(b).node(i) + d);
  return dofs;
}

/// The free unknowns of the state where beams B and C have slid along x by `slide_b` and `slide_c` [mm]
/// (their clamped starts staying put), plus a random perturbation of amplitude `noise` (mm on centres, - on
/// directors) of every free unknown.
Eigen::VectorXd slid_state(const model::Model& m, double slide_b, double slide_c, double noise,
                           std::mt19937& rng) {
  Eigen::VectorXd x = m.reference();
  for (int b = 1; b < 3; ++b)
    for (int i = 1; i < m.beam(b).num_nodes(); ++i) x[9 * m.beam(b).node(i)] += b == 1 ? slide_b : slide_c;
  const std::vector<int> dofs = free_dofs(m);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd free(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k)
    free[static_cast<Eigen::Index>(k)] = x[dofs[k]] + noise * u(rng);
  return free;
}

struct Comparison {
  double max_error = 0.0;  ///< max |K_ij - FD_ij| [N/mm or N]
  double scale = 0.0;      ///< max |K_ij|
  Eigen::MatrixXd tangent, fd;
};

/// Assembled tangent and central differences of the residual with step h at unknowns u, at load time t.
Comparison compare(EquilibriumProblem& p, const Eigen::VectorXd& u, double h) {
  Comparison c;
  p.set_unknowns(u);
  Eigen::VectorXd r;
  p.evaluate(r, true);
  c.tangent = Eigen::MatrixXd(p.tangent());
  const int n = p.size();
  c.fd.resize(n, n);
  Eigen::VectorXd rp, rm;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd v = u;
    v[j] += h;
    p.set_unknowns(v);
    p.evaluate(rp, false);
    v[j] = u[j] - h;
    p.set_unknowns(v);
    p.evaluate(rm, false);
    c.fd.col(j) = (rp - rm) / (2.0 * h);
  }
  p.set_unknowns(u);
  p.evaluate(r, false);
  c.scale = c.tangent.cwiseAbs().maxCoeff();
  c.max_error = (c.tangent - c.fd).cwiseAbs().maxCoeff();
  return c;
}

/// The evaluated states: slides of B and C [mm] (one beyond g_rev_max = 1e-3 mm: slip, one within: stick),
/// and the noise seed.
struct TestState {
  double slide_b, slide_c;
  unsigned seed;
};
constexpr TestState kStates[] = {{3e-3, 3e-4, 5}, {-4e-4, 2.5e-3, 6}, {-2e-3, -5e-4, 7}};
constexpr double kEta = 10.0;  // N s/mm^2: drag c = eta w / dt ~ 3 N/mm per node at dt = 0.5, w ~ h/6 .. 2h/3

/// The response of each contact element at free unknowns u (committed state: the reference, g_rev = 0).
std::vector<contact::ContactResponse> responses(const Assembly& a, const Eigen::VectorXd& u) {
  Eigen::VectorXd x = a.model.reference();
  const std::vector<int> dofs = free_dofs(a.model);
  for (std::size_t k = 0; k < dofs.size(); ++k) x[dofs[k]] = u[static_cast<Eigen::Index>(k)];
  const contact::FrictionLaw friction{kMu, kMaxReversible};
  std::vector<contact::ContactResponse> out;
  for (const contact::ContactElement& e : a.geometry.elements) {
    const int i = e.particle_i.element, j = e.particle_j.element;
    out.push_back(contact::contact_response(
        e, a.model.gather(x, i), a.model.gather(x, j), a.model.gather(a.model.reference(), i),
        a.model.gather(a.model.reference(), j), contact::NormalLaw{kPenalty, kRegularization}, &friction,
        Vec3::Zero()));
  }
  return out;
}

/// Counts the elements in contact (R_N > 0) that slip and that stick at free unknowns u.
std::pair<int, int> slip_and_stick(const Assembly& a, const Eigen::VectorXd& u) {
  int slip = 0, stick = 0;
  for (const contact::ContactResponse& r : responses(a, u))
    if (r.normal_reaction > 0.0) ++(r.friction.slip ? slip : stick);
  return {slip, stick};
}

// The FD step: the error max |K - FD| on the first state, h = 1e-4 .. 1e-7 (mm on centres, - on directors):
// 2.9e-3, 2.9e-5, 2.9e-7, 2.0e-6, against max |K| = 1.8e3: the truncation error falls as h^2 down to h =
// 1e-6, below which round-off (eps |R| / h) takes over. So h = 1e-6, and the tolerance 1e-8 max |K| (60 times
// the error seen there, and 1e-4 of the frozen-R_N error that the exact variant must not have).
constexpr double kStep = 1e-6;
constexpr double kTolerance = 1e-8;

TEST(AssembledProblem, ExactTangentMatchesFiniteDifferencesWithSlipAndStick) {
  Assembly a(true, kEta);
  EquilibriumProblem& p = *a.problem;
  ASSERT_EQ(p.size(), static_cast<int>(free_dofs(a.model).size()));
  ASSERT_EQ(a.geometry.zones.size(), 2u) << "B over A and C under A";
  p.set_time(0.5);
  int columns = 0;
  for (const TestState& t : kStates) {
    std::mt19937 rng(t.seed);
    const Eigen::VectorXd u = slid_state(a.model, t.slide_b, t.slide_c, 1e-5, rng);
    const Comparison c = compare(p, u, kStep);
    const auto [slip, stick] = slip_and_stick(a, u);
    EXPECT_GE(slip, 1) << "seed " << t.seed;
    EXPECT_GE(stick, 1) << "seed " << t.seed;
    EXPECT_LE(c.max_error, kTolerance * c.scale) << "seed " << t.seed;
    columns += static_cast<int>(c.fd.cols());
  }
  EXPECT_EQ(columns, 3 * p.size());
  // The step choice: on the first state the error shrinks by 100 per decade of h from 1e-4 to 1e-6.
  std::mt19937 rng(kStates[0].seed);
  const Eigen::VectorXd u = slid_state(a.model, kStates[0].slide_b, kStates[0].slide_c, 1e-5, rng);
  const double e4 = compare(p, u, 1e-4).max_error, e5 = compare(p, u, 1e-5).max_error;
  EXPECT_NEAR(e4 / e5, 100.0, 10.0);
}

TEST(AssembledProblem, EveryTermIsPresent) {
  // The drag, the loads and the contact each change the residual of the first state (so that the comparison
  // above has checked their tangents).
  std::mt19937 rng(kStates[0].seed);
  Assembly with(true, kEta), without(true, 0.0);
  const Eigen::VectorXd u = slid_state(with.model, kStates[0].slide_b, kStates[0].slide_c, 1e-5, rng);
  Eigen::VectorXd r_with, r_without;
  for (Assembly* a : {&with, &without}) {
    a->problem->set_time(0.5);
    a->problem->set_unknowns(u);
    a->problem->evaluate(a == &with ? r_with : r_without, false);
  }
  EXPECT_GT((r_with - r_without).norm(), 1e-3) << "the drag";
  double normal = 0.0, friction = 0.0;
  for (const contact::ContactResponse& r : responses(with, u)) {
    normal += r.normal_reaction;
    friction += r.friction.force.norm();
  }
  EXPECT_GT(normal, 0.05);
  EXPECT_GT(friction, 1e-3);
  // The end load: the residual at the loaded node's centre moves with time by the force ramp.
  Eigen::VectorXd r_late;
  with.problem->set_time(1.0);
  with.problem->set_unknowns(u);
  with.problem->evaluate(r_late, false);
  EXPECT_GT((r_late - r_with).norm(), 0.01);
}

TEST(AssembledProblem, RestoreGoesBackToTheCommittedContactElementsAndPenalties) {
  // A failed step attempt: a new set of contact elements (here B's only), a penalty raised by loop 3, the
  // unknowns moved. restore() must give back the committed state's residual exactly, contact included.
  std::mt19937 rng(kStates[0].seed);
  Assembly a(true, 0.0);
  const Eigen::VectorXd u = slid_state(a.model, kStates[0].slide_b, kStates[0].slide_c, 1e-5, rng);
  a.problem->set_time(0.5);
  a.problem->set_unknowns(u);
  Eigen::VectorXd committed_residual;
  a.problem->evaluate(committed_residual, true);
  a.problem->commit();
  const std::size_t zones = a.geometry.zones.size();
  ASSERT_GE(zones, 2u);

  contact::ContactGeometry fewer = a.geometry;
  fewer.zones.resize(1);
  fewer.elements.resize(static_cast<std::size_t>(fewer.zones[0].num_elements));
  a.problem->set_contact(fewer, {1e3 * kPenalty}, std::vector<Vec3>(fewer.elements.size(), Vec3::Zero()));
  a.problem->set_time(0.75);
  a.problem->set_unknowns(u * 1.001);
  Eigen::VectorXd failed;
  a.problem->evaluate(failed, true);
  ASSERT_GT((failed - committed_residual).norm(), 1e-3);

  a.problem->restore();
  EXPECT_EQ(a.problem->contact_geometry().elements.size(), a.geometry.elements.size());
  EXPECT_EQ(a.problem->zone_penalty(), std::vector<double>(zones, kPenalty));
  Eigen::VectorXd restored;
  a.problem->evaluate(restored, true);
  EXPECT_EQ(restored, committed_residual);
}

TEST(AssembledProblem, APatternIsBuiltOnlyWhenTheCouplingsChange) {
  // A detection that finds contact elements between the same beam elements keeps the pattern (and the
  // solver's analysis of it); one that couples other elements, and the restore of a failed attempt's
  // elements, build a new one and say so by the pattern version (NewtonSolver then analyses it again).
  Assembly a(true, 0.0);
  EquilibriumProblem& p = *a.problem;
  const std::size_t zones = a.geometry.zones.size();
  ASSERT_GE(zones, 2u);
  const std::uint64_t first = p.pattern_version();
  const Eigen::Index entries = p.tangent().nonZeros();
  const solver::SparseMatrix* matrix = &p.tangent();

  // The same elements again, and the same beam elements with other particles and normals: same pattern.
  EXPECT_FALSE(p.set_contact(a.geometry, std::vector<double>(zones, kPenalty),
                             std::vector<Vec3>(a.geometry.elements.size(), Vec3::Zero())));
  contact::ContactGeometry moved = a.geometry;
  for (contact::ContactElement& e : moved.elements) {
    e.normal = -e.normal;
    e.particle_i.local *= 0.5;
  }
  EXPECT_FALSE(p.set_contact(moved, std::vector<double>(zones, kPenalty),
                             std::vector<Vec3>(moved.elements.size(), Vec3::Zero())));
  EXPECT_EQ(p.pattern_version(), first);
  EXPECT_EQ(&p.tangent(), matrix);

  // B's zone alone: C's couplings with A leave the pattern.
  p.commit();
  contact::ContactGeometry fewer = a.geometry;
  fewer.zones.resize(1);
  fewer.elements.resize(static_cast<std::size_t>(fewer.zones[0].num_elements));
  EXPECT_TRUE(p.set_contact(fewer, {kPenalty}, std::vector<Vec3>(fewer.elements.size(), Vec3::Zero())));
  EXPECT_EQ(p.pattern_version(), first + 1);
  EXPECT_LT(p.tangent().nonZeros(), entries);

  // restore() puts the committed elements back, with their pattern: a new version, which the next
  // detection of the same elements keeps.
  p.restore();
  EXPECT_EQ(p.pattern_version(), first + 2);
  EXPECT_EQ(p.tangent().nonZeros(), entries);
  EXPECT_FALSE(p.set_contact(a.geometry, std::vector<double>(zones, kPenalty),
                             std::vector<Vec3>(a.geometry.elements.size(), Vec3::Zero())));
  EXPECT_EQ(p.pattern_version(), first + 2);

  // The tangent assembled into a kept pattern equals the one assembled into a new pattern.
  Eigen::VectorXd r;
  p.set_time(0.5);
  p.evaluate(r, true);
  const Eigen::MatrixXd kept(p.tangent());
  Assembly b(true, 0.0);
  b.problem->set_time(0.5);
  b.problem->evaluate(r, true);
  EXPECT_EQ(kept, Eigen::MatrixXd(b.problem->tangent()));
}

// With R_N frozen in the friction tangent (the paper's simplification, the default), the tangent is not the
// exact derivative: for each contact element that rubs (R_N > 0, friction force T = -mu R_N g_rev / g_rev_max
// != 0) it leaves out the term (B^T T / R_N) (d R_N / d x)^T, one outer product. So it must match the finite
// differences in every row and column outside the unknowns of the beam elements that carry such a contact
// element, and differ from them by a matrix of rank at most the number of rubbing elements.
TEST(AssembledProblem, FrozenNormalReactionTangentMissesOnlyARankOneTermPerRubbingElement) {
  Assembly a(false, kEta);
  EquilibriumProblem& p = *a.problem;
  p.set_time(0.5);
  const std::vector<int> dofs = free_dofs(a.model);
  std::vector<int> free_index(static_cast<std::size_t>(a.model.num_dofs()), -1);
  for (std::size_t k = 0; k < dofs.size(); ++k)
    free_index[static_cast<std::size_t>(dofs[k])] = static_cast<int>(k);
  const std::vector<std::vector<int>> element_nodes = a.model.element_nodes();
  for (const TestState& t : kStates) {
    std::mt19937 rng(t.seed);
    const Eigen::VectorXd u = slid_state(a.model, t.slide_b, t.slide_c, 1e-5, rng);
    const Comparison c = compare(p, u, kStep);
    // The unknowns touched by rubbing elements.
    std::vector<bool> touched(dofs.size(), false);
    int rubbing = 0;
    const std::vector<contact::ContactResponse> response = responses(a, u);
    for (std::size_t k = 0; k < response.size(); ++k) {
      if (!(response[k].normal_reaction > 0.0 && response[k].friction.force.norm() > 0.0)) continue;
      ++rubbing;
      const contact::ContactElement& e = a.geometry.elements[k];
      for (int element : {e.particle_i.element, e.particle_j.element})
        for (int node : element_nodes[static_cast<std::size_t>(element)])
          for (int d = 0; d < 9; ++d) {
            const int f = free_index[static_cast<std::size_t>(9 * node + d)];
            if (f >= 0) touched[static_cast<std::size_t>(f)] = true;
          }
    }
    ASSERT_GE(rubbing, 2) << "seed " << t.seed;
    const Eigen::MatrixXd difference = c.fd - c.tangent;
    double outside = 0.0;
    for (Eigen::Index i = 0; i < difference.rows(); ++i)
      for (Eigen::Index j = 0; j < difference.cols(); ++j)
        if (!touched[static_cast<std::size_t>(i)] || !touched[static_cast<std::size_t>(j)])
          outside = std::max(outside, std::abs(difference(i, j)));
    EXPECT_LE(outside, kTolerance * c.scale) << "seed " << t.seed;
    // Inside: a real difference (the frozen tangent is not exact), of rank <= rubbing elements. Singular
    // values below 1e-6 max |K| are the finite differences' own error (1e-10 max |K| per entry).
    EXPECT_GT(c.max_error, 1e-4 * c.scale) << "seed " << t.seed;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(difference);
    int rank = 0;
    for (Eigen::Index k = 0; k < svd.singularValues().size(); ++k)
      if (svd.singularValues()[k] > 1e-6 * c.scale) ++rank;
    EXPECT_GE(rank, 1);
    EXPECT_LE(rank, rubbing) << "seed " << t.seed;
  }
}

}  // namespace
}  // namespace nodus::simulation
