// The equilibrium as a sum of terms over general unknowns (model/term.hpp, model/dof_map.hpp): a toy term
// with unknowns of its own, a point tied by a spring to a beam's tip and by another to a fixed anchor, is
// registered in the assembled problem beside the beam's terms. Its residual rows are checked against the
// spring forces in closed form, the assembled tangent against central finite differences of the assembled
// residual, and the solved equilibrium against the closed-form position of a point between two springs.

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/model/term.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/newton.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {
namespace {

using Vec3 = Eigen::Vector3d;

/// Energy k/2 |r_tip - p|^2 + k_anchor/2 |p - a|^2 of a point p (its own block of three position unknowns),
/// tied to the centre r_tip of a beam node and to a fixed anchor a [k in N/mm].
class TwoSprings final : public model::Term {
 public:
  TwoSprings(const model::Model& model, int tip_node, int point_block, double k, double k_anchor, Vec3 anchor)
      : model_(model), tip_(tip_node), point_(point_block), k_(k), k_anchor_(k_anchor), anchor_(anchor) {}

  std::string_view name() const override { return "two springs"; }
  void couplings(std::vector<std::vector<int>>& groups) const override { groups.push_back({tip_, point_}); }
  void add(const model::TermState& state, Eigen::VectorXd& residual,
           solver::SparseAssembler* tangent) override {
    const int r = model_.node_dof(tip_), p = model_.dofs().first(point_);
    const Vec3 stretch = state.x.segment<3>(r) - state.x.segment<3>(p);
    residual.segment<3>(r) += k_ * stretch;
    residual.segment<3>(p) += -k_ * stretch + k_anchor_ * (state.x.segment<3>(p) - anchor_);
    if (!tangent) return;
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(beam::kNodeDofs + 3, beam::kNodeDofs + 3);
    const Eigen::Matrix3d i = Eigen::Matrix3d::Identity();
    k.block<3, 3>(0, 0) = k_ * i;
    k.block<3, 3>(0, beam::kNodeDofs) = -k_ * i;
    k.block<3, 3>(beam::kNodeDofs, 0) = -k_ * i;
    k.block<3, 3>(beam::kNodeDofs, beam::kNodeDofs) = (k_ + k_anchor_) * i;
    const int blocks[2] = {tip_, point_};
    tangent->add(blocks, k);
  }

 private:
  const model::Model& model_;
  int tip_, point_;
  double k_, k_anchor_;
  Vec3 anchor_;
};

constexpr model::DofKind kPoint[3] = {model::DofKind::position, model::DofKind::position,
                                      model::DofKind::position};

struct CantileverWithPoint {
  model::Model model;
  loading::Conditions conditions;
  int point = -1;
  int tip = -1;
  std::unique_ptr<EquilibriumProblem> problem;

  CantileverWithPoint() {
    // A cantilever 10 mm long, radius 0.2 mm, E = 1000 MPa, clamped at its start.
    model.add_beam({"rod", 10.0, 0.2, 4, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), {1000.0, 0.3}, 1.0});
    tip = model.beam(0).node(8);
    point = model.add_unknowns(kPoint, Vec3(11.0, 1.0, 0.5));
    const int clamp =
        conditions.add_motion("clamp", model.beam(0).node(0),
                              loading::DofMask{true, true, true, true, true, true, true, true, true});
    conditions.activate(clamp, 0.0, model.reference());
    problem = std::make_unique<EquilibriumProblem>(model, conditions, Tolerances{});
  }
};

TEST(DofMap, HandsOutBlocksOfAnySize) {
  model::DofMap map;
  EXPECT_EQ(map.add_block(model::kBeamNodeKinds), 0);
  const model::DofKind body[6] = {model::DofKind::position, model::DofKind::position,
                                  model::DofKind::position, model::DofKind::rotation,
                                  model::DofKind::rotation, model::DofKind::rotation};
  EXPECT_EQ(map.add_block(body), 1);
  const model::DofKind multiplier[1] = {model::DofKind::other};
  EXPECT_EQ(map.add_block(multiplier), 2);
  EXPECT_EQ(map.num_dofs(), 16);
  EXPECT_EQ(map.first(1), 9);
  EXPECT_EQ(map.size(1), 6);
  EXPECT_EQ(map.first(2), 15);
  EXPECT_EQ(map.kind(12), model::DofKind::rotation);
  EXPECT_EQ(map.kind(4), model::DofKind::director);
  EXPECT_THROW(map.add_block({}), std::invalid_argument);
}

TEST(DofMap, BeamsComeBeforeOtherUnknowns) {
  model::Model m;
  m.add_beam({"a", 1.0, 0.1, 1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), {1000.0, 0.3}, 1.0});
  const int block = m.add_unknowns(kPoint, Vec3(1, 2, 3));
  EXPECT_EQ(block, 3);  // after the three nodes of the beam
  EXPECT_EQ(m.num_dofs(), 30);
  EXPECT_EQ(m.reference().tail<3>(), Vec3(1, 2, 3));
  EXPECT_THROW(m.add_beam({"b", 1.0, 0.1, 1, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), {1000.0, 0.3}, 1.0}),
               std::logic_error);
}

TEST(Terms, ToyTermResidualMatchesItsForces) {
  CantileverWithPoint s;
  const double k = 3.0, k_anchor = 5.0;
  const Vec3 anchor(12.0, -1.0, 0.0);
  s.problem->add_term(std::make_unique<TwoSprings>(s.model, s.tip, s.point, k, k_anchor, anchor));
  Eigen::VectorXd residual;
  s.problem->set_time(0.0);
  s.problem->evaluate(residual, false);
  // In the reference state the beam carries no force: the residual is the springs' alone.
  const Vec3 r = s.model.reference().segment<3>(s.model.node_dof(s.tip));
  const Vec3 p(11.0, 1.0, 0.5);
  const Eigen::VectorXd& full = s.problem->full_residual();
  const int pf = s.model.dofs().first(s.point);
  EXPECT_LT((full.segment<3>(pf) - (-k * (r - p) + k_anchor * (p - anchor))).norm(), 1e-12);
  EXPECT_LT((full.segment<3>(s.model.node_dof(s.tip)) - k * (r - p)).norm(), 1e-9);
  // The point's unknowns are free and counted: 9 per node but the clamped one, and 3.
  EXPECT_EQ(s.problem->size(), 9 * 8 + 3);
}

TEST(Terms, AssembledTangentWithAToyTermMatchesFiniteDifferences) {
  CantileverWithPoint s;
  s.problem->add_term(
      std::make_unique<TwoSprings>(s.model, s.tip, s.point, 30.0, 50.0, Vec3(12.0, -1.0, 0.0)));
  s.problem->set_time(0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x0 = s.problem->unknowns();
  for (Eigen::Index i = 0; i < x0.size(); ++i) x0[i] += 0.02 * u(rng);  // a deformed state, beam stressed
  s.problem->set_unknowns(x0);
  Eigen::VectorXd residual;
  s.problem->evaluate(residual, true);
  const Eigen::MatrixXd k = Eigen::MatrixXd(s.problem->tangent());
  ASSERT_EQ(k.rows(), x0.size());
  // Central differences: truncation error ~ h^2 |R'''| and round-off ~ eps |R| / h; h = 1e-6 of unknowns of
  // size ~10 keeps both near 1e-8 of the tangent's scale.
  const double h = 1e-6, scale = k.cwiseAbs().maxCoeff();
  double worst = 0.0;
  for (Eigen::Index j = 0; j < x0.size(); ++j) {
    Eigen::VectorXd xp = x0, xm = x0, rp, rm;
    xp[j] += h;
    xm[j] -= h;
    s.problem->set_unknowns(xp);
    s.problem->evaluate(rp, false);
    s.problem->set_unknowns(xm);
    s.problem->evaluate(rm, false);
    worst = std::max(worst, ((rp - rm) / (2 * h) - k.col(j)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-6 * scale);
  // The coupling between the tip and the point is in the pattern and has the springs' value.
  const int pf = static_cast<int>(x0.size()) - 3;
  EXPECT_NEAR(k(pf, pf), 80.0, 1e-12);
}

TEST(Terms, NewtonSolvesTheProblemWithAToyTerm) {
  CantileverWithPoint s;
  const double k = 0.5, k_anchor = 2.0;
  const Vec3 anchor(10.0, 3.0, 0.0);
  s.problem->add_term(std::make_unique<TwoSprings>(s.model, s.tip, s.point, k, k_anchor, anchor));
  auto linear = solver::make_linear_solver(solver::LinearSolverKind::cholmod);
  solver::NewtonSolver newton(*linear, {});
  s.problem->set_time(0.0);
  const solver::NewtonReport report = newton.solve(*s.problem);
  ASSERT_TRUE(report.converged) << report.failure;
  // The point is in balance between the springs: p = (k r_tip + k_anchor a) / (k + k_anchor), and the tip
  // has moved towards it (the beam bends).
  const Eigen::VectorXd& x = s.problem->state();
  const Vec3 r = x.segment<3>(s.model.node_dof(s.tip));
  const Vec3 p = x.segment<3>(s.model.dofs().first(s.point));
  EXPECT_LT((p - (k * r + k_anchor * anchor) / (k + k_anchor)).norm(), 1e-8);
  EXPECT_GT(r.y(), 0.01);
}

TEST(Terms, IncrementsAreScaledByTheKindOfUnknown) {
  CantileverWithPoint s;
  const int n = s.problem->size();
  Eigen::VectorXd du = Eigen::VectorXd::Zero(n);
  du[n - 1] = 0.5;  // a position of the point: scaled by the longest beam, 10 mm
  EXPECT_DOUBLE_EQ(s.problem->scaled_increment(du), 0.05);
  du.setZero();
  du[3] = 0.5;  // a director component of the second node
  EXPECT_DOUBLE_EQ(s.problem->scaled_increment(du), 0.5);
}

}  // namespace
}  // namespace nodus::simulation
