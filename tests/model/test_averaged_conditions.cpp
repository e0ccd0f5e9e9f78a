// The averaged conditions that bind rigid bodies to beam sections (model/averaged_conditions_term.hpp):
// residual and tangent against finite differences, invariance under rigid motions, free rearrangements of
// the sections, and the body's rest position against an independent least-squares fit (Kabsch's SVD).
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "nodus/model/averaged_conditions_term.hpp"
#include "nodus/model/rotation_vector.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::model {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Three parallel fibres (a 3x1 yarn's section: an equilateral triangle) with bodies at both ends, and a
/// fourth body bound to one section alone.
Model yarn() {
  Model m;
  const double radius = 0.0564;
  for (int i = 0; i < 3; ++i) {
    beam::BeamDefinition d;
    d.name = "f" + std::to_string(i);
    d.length = 6.0;
    d.radius = radius;
    d.elements = 2;
    const double angle = 2.0 * 3.141592653589793 * i / 3.0;
    d.start = Vec3(0.0, std::cos(angle), std::sin(angle)) * (2.02 * radius / std::sqrt(3.0));
    d.material = {4000.0, 0.3};
    m.add_beam(d);
  }
  const int last = m.beam(0).num_nodes() - 1;
  m.add_body("start", {m.beam(0).node(0), m.beam(1).node(0), m.beam(2).node(0)});
  m.add_body("end", {m.beam(0).node(last), m.beam(1).node(last), m.beam(2).node(last)});
  m.add_body("single", {m.beam(1).node(2)});
  return m;
}

/// The term's residual at x, the last converged state being `committed` (by default x: no tie force).
Eigen::VectorXd residual(AveragedConditionsTerm& term, const Eigen::VectorXd& x,
                         const Eigen::VectorXd* committed = nullptr) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(x.size());
  term.add({x, committed ? *committed : x}, r, nullptr);
  return r;
}

double total_energy(const AveragedConditionsTerm& term, const Model& m, const Eigen::VectorXd& x) {
  double w = 0.0;
  for (int b = 0; b < static_cast<int>(m.bodies().size()); ++b) w += term.energy(b, x);
  return w;
}

/// x moved away from the reference at random: every section and body, rotations of about 1 rad.
Eigen::VectorXd perturbed(const Model& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x = m.reference();
  for (int i = 0; i < x.size(); ++i) x[i] += 0.02 * u(rng);
  for (int b = 0; b < static_cast<int>(m.bodies().size()); ++b)
    x.segment<3>(m.body_dof(b) + 3) = Vec3(u(rng), u(rng), u(rng));
  return x;
}

TEST(AveragedConditions, ResidualIsTheGradientOfThePenaltyEnergy) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {});
  const Eigen::VectorXd x = perturbed(m, 3);
  const Eigen::VectorXd r = residual(term, x);
  const double h = 1e-7;
  double largest = 0.0, worst = 0.0;
  for (int i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const double fd = (total_energy(term, m, xp) - total_energy(term, m, xm)) / (2 * h);
    largest = std::max(largest, std::abs(r[i]));
    worst = std::max(worst, std::abs(fd - r[i]));
  }
  EXPECT_GT(largest, 1.0);  // the conditions are far from satisfied: the check is not trivial
  EXPECT_LT(worst, 1e-6 * largest);
}

// With a committed state elsewhere, so that the tie acts too (made strong here: 0.3 of the penalty).
TEST(AveragedConditions, TangentMatchesFiniteDifferencesOfTheResidual) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {2.0, 0.0, 50.0}, {0.3, 0.3, 0.3});
  for (unsigned seed : {1u, 2u}) {
    const Eigen::VectorXd committed = perturbed(m, seed + 10);
    Eigen::VectorXd x = perturbed(m, seed);
    if (seed == 2) x.segment<3>(m.body_dof(1) + 3) = Vec3(0.5, -1.0, 7.0);  // more than a turn
    std::vector<int> free_index(static_cast<std::size_t>(m.num_dofs()));
    for (int i = 0; i < m.num_dofs(); ++i) free_index[static_cast<std::size_t>(i)] = i;
    std::vector<std::vector<int>> groups;
    term.couplings(groups);
    solver::SparseAssembler assembler(m.dofs().offsets(), free_index, groups);
    assembler.set_zero();
    Eigen::VectorXd r = Eigen::VectorXd::Zero(x.size());
    term.add({x, committed}, r, &assembler);
    const Eigen::MatrixXd k(assembler.matrix());
    EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-9 * k.cwiseAbs().maxCoeff());
    const double h = 1e-6;
    double worst = 0.0;
    for (int j = 0; j < x.size(); ++j) {
      Eigen::VectorXd xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      const Eigen::VectorXd fd = (residual(term, xp, &committed) - residual(term, xm, &committed)) / (2 * h);
      worst = std::max(worst, (fd - k.col(j)).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-6 * k.cwiseAbs().maxCoeff()) << "seed " << seed;
  }
}

TEST(AveragedConditions, RigidMotionOfBodiesAndSectionsCostsNothing) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {});
  const Vec3 rotation(0.4, -2.9, 1.7), translation(0.3, -1.2, 5.0);
  const Mat3 q = rotation_matrix(rotation);
  Eigen::VectorXd x = m.reference();
  for (int n = 0; n < m.num_nodes(); ++n) {
    const int i = m.node_dof(n);
    x.segment<3>(i) = q * x.segment<3>(i) + translation;
    x.segment<3>(i + 3) = q * x.segment<3>(i + 3);
    x.segment<3>(i + 6) = q * x.segment<3>(i + 6);
  }
  for (int b = 0; b < static_cast<int>(m.bodies().size()); ++b) {
    const int i = m.body_dof(b);
    x.segment<3>(i) = q * x.segment<3>(i) + translation;
    x.segment<3>(i + 3) = rotation;
  }
  const double scale = residual(term, perturbed(m, 4)).cwiseAbs().maxCoeff();
  EXPECT_LT(residual(term, x).cwiseAbs().maxCoeff(), 1e-12 * scale);
  for (int b = 0; b < 3; ++b) EXPECT_LT(term.error(b, x), 1e-14);
}

// The tie resists each step's rearrangement of the sections relative to the body, and nothing else: a rigid
// motion of bodies and sections from the committed state leaves it at zero, a rearrangement does not.
TEST(AveragedConditions, TieActsOnRearrangementsWithinAStepOnly) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {}, {});
  const Eigen::VectorXd committed = perturbed(m, 5);
  const Vec3 rotation(0.2, -0.7, 1.1), translation(0.1, 0.2, -0.3);
  const Mat3 q = rotation_matrix(rotation);
  Eigen::VectorXd x = committed;
  for (int n = 0; n < m.num_nodes(); ++n) {
    const int i = m.node_dof(n);
    x.segment<3>(i) = q * committed.segment<3>(i) + translation;
    x.segment<3>(i + 3) = q * committed.segment<3>(i + 3);
    x.segment<3>(i + 6) = q * committed.segment<3>(i + 6);
  }
  for (int b = 0; b < 3; ++b) {
    const int i = m.body_dof(b);
    x.segment<3>(i) = q * committed.segment<3>(i) + translation;
    x.segment<3>(i + 3) = rotation_vector(q * rotation_matrix(committed.segment<3>(i + 3)), Vec3::Zero());
  }
  for (int b = 0; b < 3; ++b) EXPECT_LT(term.tie_force(b, x, committed), 1e-10) << "body " << b;
  // A section moved by s relative to the body: the tie pulls it back with k_t s, k_t = 1e-6 k.
  const double s = 1e-3;
  x[m.node_dof(m.body(2).nodes[0]) + 1] += s;
  EXPECT_NEAR(term.tie_force(2, x, committed), AveragedConditionsTerm::kDefaultTie * term.penalty(2) * s,
              1e-9 * term.penalty(2) * s);
}

TEST(AveragedConditions, SectionsRearrangeFreelyWhileTheAveragesHold) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {});
  Eigen::VectorXd x = m.reference();
  const RigidBody& start = m.body(0);
  const Vec3 c = start.reference_point;
  std::vector<Vec3> a;
  for (int node : start.nodes) a.push_back(m.reference().segment<3>(m.node_dof(node)) - c);
  // The sections spread radially by 10 %, two of them slide along the line joining them in opposite
  // directions, and two twist about their own axes by opposite angles: each of these keeps the best fit
  // where the body is.
  const double slide = 0.01, twist = 0.3;
  for (std::size_t i = 0; i < 3; ++i) x.segment<3>(m.node_dof(start.nodes[i])) = c + 1.1 * a[i];
  x.segment<3>(m.node_dof(start.nodes[0])) += slide * (a[0] - a[1]);
  x.segment<3>(m.node_dof(start.nodes[1])) -= slide * (a[0] - a[1]);
  for (std::size_t i = 0; i < 2; ++i) {
    const Mat3 q = rotation_matrix((i == 0 ? twist : -twist) * Vec3::UnitX());
    const int dof = m.node_dof(start.nodes[i]);
    x.segment<3>(dof + 3) = q * x.segment<3>(dof + 3);
    x.segment<3>(dof + 6) = q * x.segment<3>(dof + 6);
  }
  EXPECT_LT(term.error(0, x), 1e-15);
  EXPECT_LT(term.energy(0, x), 1e-20);
  // An axial shift s of one section alone is not such a motion: it moves the mean by s / 3 and tilts the
  // fit, C_t = (Q a_1) x (s e_x) / 3, a_1 the reference offset.
  const double s = 0.03;
  Eigen::VectorXd y = x;
  y[m.node_dof(start.nodes[1])] += s;
  const double j =
      (a[0].squaredNorm() + a[1].squaredNorm() + a[2].squaredNorm()) / 3.0 + 2.0 * 0.25 * 0.0564 * 0.0564;
  const Vec3 ct = a[1].cross(s * Vec3::UnitX()) / 3.0;  // Q = I: the body has not moved
  EXPECT_NEAR(term.error(0, y), std::sqrt(s * s / 9.0 + ct.squaredNorm() / j), 1e-12);
}

// With the sections fixed anywhere, the body settles (dW = 0 over its six unknowns) at the rigid motion that
// best fits the discs' material points: Kabsch's SVD solution of
// min sum_i |r_i - c - Q a_i|^2 + w_i sum_a |g_ai - Q g_ai0|^2, computed here independently.
TEST(AveragedConditions, BodyRestsAtTheLeastSquaresFitOfItsSections) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {});
  Eigen::VectorXd x = perturbed(m, 9);
  // Turn the end sections well away: a rigid 0.8 rad turn about the axis plus the random scatter.
  const Mat3 turn = rotation_matrix(Vec3(0.8, 0.1, 0.0));
  const RigidBody& body = m.body(1);
  for (int node : body.nodes) {
    const int i = m.node_dof(node);
    x.segment<3>(i) = turn * (x.segment<3>(i) - body.reference_point) + body.reference_point;
    x.segment<3>(i + 3) = turn * x.segment<3>(i + 3);
    x.segment<3>(i + 6) = turn * x.segment<3>(i + 6);
  }
  // Newton on the body's six unknowns with the term's own tangent, from the turn: the conditions also hold
  // at the other stationary points of the fit (flipped by half turns), so the body is started in the basin
  // of the best one, as a run keeps it by continuity.
  const int dof = m.body_dof(1);
  x.segment<3>(dof) = body.reference_point;
  x.segment<3>(dof + 3) = Vec3(0.8, 0.1, 0.0);
  std::vector<int> free_index(static_cast<std::size_t>(m.num_dofs()), -1);
  for (int k = 0; k < 6; ++k) free_index[static_cast<std::size_t>(dof + k)] = k;
  std::vector<std::vector<int>> groups;
  term.couplings(groups);
  for (int it = 0; it < 30; ++it) {
    solver::SparseAssembler assembler(m.dofs().offsets(), free_index, groups);
    assembler.set_zero();
    Eigen::VectorXd r = Eigen::VectorXd::Zero(x.size());
    term.add({x, x}, r, &assembler);
    const Eigen::VectorXd rb = r.segment<6>(dof);
    const Eigen::MatrixXd k(assembler.matrix());
    x.segment<6>(dof) -= k.ldlt().solve(rb);
    if (rb.norm() < 1e-9) break;
  }
  // Kabsch: the centre is the mean; the rotation maximises trace(Q^T H) with H = sum p_i q_i^T.
  Vec3 mean = Vec3::Zero();
  for (int node : body.nodes) mean += x.segment<3>(m.node_dof(node));
  mean /= 3.0;
  Mat3 h = Mat3::Zero();
  const double w = 0.25 * 0.0564 * 0.0564;
  for (int node : body.nodes) {
    const int i = m.node_dof(node);
    h += (x.segment<3>(i) - mean) * (m.reference().segment<3>(i) - body.reference_point).transpose();
    h += w * x.segment<3>(i + 3) * m.reference().segment<3>(i + 3).transpose();
    h += w * x.segment<3>(i + 6) * m.reference().segment<3>(i + 6).transpose();
  }
  Eigen::JacobiSVD<Mat3> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 d = Mat3::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Mat3 q_fit = svd.matrixU() * d * svd.matrixV().transpose();
  EXPECT_LT((x.segment<3>(dof) - mean).norm(), 1e-12);
  EXPECT_LT((rotation_matrix(x.segment<3>(dof + 3)) - q_fit).norm(), 1e-10);
}

TEST(AveragedConditions, ResultantIsTheForceAndMomentOnTheSections) {
  const Model m = yarn();
  AveragedConditionsTerm term(m, {});
  const Eigen::VectorXd x = perturbed(m, 7);
  const Eigen::VectorXd r = residual(term, x);
  for (int b = 0; b < 3; ++b) {
    const BodyResultant res = term.resultant(b, x);
    // Action and reaction: what the sections receive, the body gives (its residual is the support force).
    const int dof = m.body_dof(b);
    EXPECT_LT((res.force - r.segment<3>(dof)).norm(), 1e-9 * (1.0 + res.force.norm()));
    // The moment about c from the work of a small rotation of the sections about c: -dW/d(angle).
    const Vec3 c = x.segment<3>(dof);
    for (int axis = 0; axis < 3; ++axis) {
      const double h = 1e-7;
      auto turned = [&](double angle) {
        Eigen::VectorXd y = x;
        const Mat3 q = rotation_matrix(angle * Vec3::Unit(axis));
        for (int node : m.body(b).nodes) {
          const int i = m.node_dof(node);
          y.segment<3>(i) = c + q * (x.segment<3>(i) - c);
          y.segment<3>(i + 3) = q * x.segment<3>(i + 3);
          y.segment<3>(i + 6) = q * x.segment<3>(i + 6);
        }
        return term.energy(b, y);
      };
      const double moment = -(turned(h) - turned(-h)) / (2 * h);
      EXPECT_NEAR(res.moment[axis], moment, 1e-6 * (1.0 + res.moment.norm())) << "body " << b;
    }
  }
}

}  // namespace
}  // namespace nodus::model
