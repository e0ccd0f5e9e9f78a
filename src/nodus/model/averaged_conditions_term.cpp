#include "nodus/model/averaged_conditions_term.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "nodus/model/rotation_vector.hpp"
#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::model {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr int kNode = beam::kNodeDofs;
constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace

AveragedConditionsTerm::AveragedConditionsTerm(const Model& model, const std::vector<double>& penalty_factors,
                                               const std::vector<double>& ties) {
  const Eigen::VectorXd& x0 = model.reference();
  for (int b = 0; b < static_cast<int>(model.bodies().size()); ++b) {
    const RigidBody& rb = model.body(b);
    Body body;
    body.dof = model.body_dof(b);
    body.block = rb.block;
    body.c0 = rb.reference_point;
    body.blocks.push_back(rb.block);
    double stiffness = 0.0;  // sum of E A / h
    for (int node : rb.nodes) {
      const beam::Beam& beam = model.beam(model.node_beam(node));
      Section s;
      s.dof = model.node_dof(node);
      s.r0 = x0.segment<3>(s.dof);
      s.a = s.r0 - body.c0;
      s.g1 = x0.segment<3>(s.dof + 3);
      s.g2 = x0.segment<3>(s.dof + 6);
      s.w = 0.25 * beam.radius() * beam.radius();
      body.j += s.a.squaredNorm() + 2.0 * s.w;
      stiffness += beam.definition().material.young_modulus * std::numbers::pi * beam.radius() *
                   beam.radius() / beam.element_length();
      body.sections.push_back(s);
      body.blocks.push_back(node);
    }
    const auto n = static_cast<double>(body.sections.size());
    body.j /= n;
    const double factor = static_cast<std::size_t>(b) < penalty_factors.size() &&
                                  penalty_factors[static_cast<std::size_t>(b)] > 0.0
                              ? penalty_factors[static_cast<std::size_t>(b)]
                              : kDefaultPenalty;
    body.k = factor * stiffness / n;
    const double tie = static_cast<std::size_t>(b) < ties.size() && ties[static_cast<std::size_t>(b)] > 0.0
                           ? ties[static_cast<std::size_t>(b)]
                           : kDefaultTie;
    body.kt = tie * body.k;
    floor_ += 10.0 * kEps * body.k * n * std::sqrt(body.j);
    bodies_.push_back(std::move(body));
  }
}

void AveragedConditionsTerm::couplings(std::vector<std::vector<int>>& groups) const {
  for (const Body& body : bodies_) groups.push_back(body.blocks);
}

void AveragedConditionsTerm::conditions(const Body& body, const Eigen::VectorXd& x, const Mat3& q, Vec3& cc,
                                        Vec3& ct) const {
  const Vec3 c = x.segment<3>(body.dof);
  const auto n = static_cast<double>(body.sections.size());
  cc = c - body.c0;
  ct.setZero();
  for (const Section& s : body.sections) {
    const Vec3 r = x.segment<3>(s.dof);
    cc -= (r - s.r0) / n;
    ct += ((q * s.a).cross(r - c) +
           s.w * ((q * s.g1).cross(x.segment<3>(s.dof + 3)) + (q * s.g2).cross(x.segment<3>(s.dof + 6)))) /
          n;
  }
}

Eigen::VectorXd AveragedConditionsTerm::gradient(const Body& body, const Eigen::VectorXd& x,
                                                 Eigen::MatrixXd* hessian) const {
  const int ns = static_cast<int>(body.sections.size());
  const auto n = static_cast<double>(ns);
  const int m = 6 + kNode * ns;
  const Vec3 c = x.segment<3>(body.dof);
  const RotationDerivatives rd = rotation_derivatives(x.segment<3>(body.dof + 3), hessian != nullptr);
  const Mat3& q = rd.q;
  Vec3 cc, ct;
  conditions(body, x, q, cc, ct);

  // The Jacobians of C_c and C_t over (c, theta, r_i, g_1i, g_2i).
  Eigen::MatrixXd jc = Eigen::MatrixXd::Zero(3, m), jt = Eigen::MatrixXd::Zero(3, m);
  jc.block<3, 3>(0, 0).setIdentity();
  for (int i = 0; i < ns; ++i) {
    const Section& s = body.sections[static_cast<std::size_t>(i)];
    const int col = 6 + kNode * i;
    const Vec3 qa = q * s.a, d = x.segment<3>(s.dof) - c;
    const Vec3 g1 = x.segment<3>(s.dof + 3), g2 = x.segment<3>(s.dof + 6);
    jc.block<3, 3>(0, col) = -Mat3::Identity() / n;
    jt.block<3, 3>(0, 0) -= skew(qa) / n;
    jt.block<3, 3>(0, col) = skew(qa) / n;
    jt.block<3, 3>(0, col + 3) = s.w / n * skew(q * s.g1);
    jt.block<3, 3>(0, col + 6) = s.w / n * skew(q * s.g2);
    for (std::size_t k = 0; k < 3; ++k)
      jt.col(3 + static_cast<int>(k)) +=
          ((rd.first[k] * s.a).cross(d) +
           s.w * ((rd.first[k] * s.g1).cross(g1) + (rd.first[k] * s.g2).cross(g2))) /
          n;
  }
  const double kn = body.k * n;
  Eigen::VectorXd grad = kn * (jc.transpose() * cc + jt.transpose() * ct / body.j);
  if (!hessian) return grad;

  Eigen::MatrixXd& h = *hessian;
  h = kn * (jc.transpose() * jc + jt.transpose() * jt / body.j);
  // lambda . d^2 C_t, lambda = k n C_t / J: C_t is linear in c, r and g for a given Q, so only the pairs
  // (theta, theta) and (theta, anything) remain.
  const Vec3 lambda = kn * ct / body.j;
  for (int i = 0; i < ns; ++i) {
    const Section& s = body.sections[static_cast<std::size_t>(i)];
    const int col = 6 + kNode * i;
    const Vec3 d = x.segment<3>(s.dof) - c;
    const Vec3 g1 = x.segment<3>(s.dof + 3), g2 = x.segment<3>(s.dof + 6);
    for (std::size_t k = 0; k < 3; ++k) {
      const int row = 3 + static_cast<int>(k);
      const Vec3 vr = lambda.cross(rd.first[k] * s.a) / n;  // d/dr_i of lambda . dC_t/dtheta_k
      const Vec3 v1 = s.w / n * lambda.cross(rd.first[k] * s.g1);
      const Vec3 v2 = s.w / n * lambda.cross(rd.first[k] * s.g2);
      h.block<1, 3>(row, col) += vr.transpose();
      h.block<3, 1>(col, row) += vr;
      h.block<1, 3>(row, 0) -= vr.transpose();
      h.block<3, 1>(0, row) -= vr;
      h.block<1, 3>(row, col + 3) += v1.transpose();
      h.block<3, 1>(col + 3, row) += v1;
      h.block<1, 3>(row, col + 6) += v2.transpose();
      h.block<3, 1>(col + 6, row) += v2;
      for (std::size_t l = 0; l < 3; ++l) {
        const Mat3& qkl = rd.second[k][l];
        h(row, 3 + static_cast<int>(l)) +=
            lambda.dot((qkl * s.a).cross(d) + s.w * ((qkl * s.g1).cross(g1) + (qkl * s.g2).cross(g2))) / n;
      }
    }
  }
  return grad;
}

Eigen::VectorXd AveragedConditionsTerm::tie_gradient(const Body& body, const Eigen::VectorXd& x,
                                                     const Eigen::VectorXd& committed,
                                                     Eigen::MatrixXd* hessian) const {
  const int ns = static_cast<int>(body.sections.size());
  const int m = 6 + kNode * ns;
  const Vec3 c = x.segment<3>(body.dof), c_old = committed.segment<3>(body.dof);
  const RotationDerivatives rd = rotation_derivatives(x.segment<3>(body.dof + 3), hessian != nullptr);
  const Mat3 qt = rd.q.transpose(), qt_old = rotation_matrix(committed.segment<3>(body.dof + 3)).transpose();
  Eigen::VectorXd grad = Eigen::VectorXd::Zero(m);
  if (hessian) hessian->setZero(m, m);
  // One misfit v (eps_i or phi_ai) at a time: v = Q^T (y - z) - v0, y the section's unknown (r_i or g_ai) at
  // column `col`, z = c for eps (with_c) and 0 for phi; weight 1 or w_i. Its change since the committed
  // state: the v0 cancel.
  Eigen::MatrixXd jac(3, m);
  auto misfit = [&](int col, const Vec3& y, const Vec3& y_old, bool with_c, double weight) {
    const Vec3 d = with_c ? Vec3(y - c) : y, d_old = with_c ? Vec3(y_old - c_old) : y_old;
    const Vec3 mu = body.kt * weight * (qt * d - qt_old * d_old);
    jac.setZero();
    if (with_c) jac.block<3, 3>(0, 0) = -qt;
    for (std::size_t k = 0; k < 3; ++k) jac.col(3 + static_cast<int>(k)) = rd.first[k].transpose() * d;
    jac.block<3, 3>(0, col) = qt;
    grad += jac.transpose() * mu;
    if (!hessian) return;
    Eigen::MatrixXd& h = *hessian;
    h += body.kt * weight * jac.transpose() * jac;
    for (std::size_t k = 0; k < 3; ++k) {
      const int row = 3 + static_cast<int>(k);
      const Vec3 v = rd.first[k] * mu;  // d/dy of mu . Q_k^T (y - z)
      h.block<1, 3>(row, col) += v.transpose();
      h.block<3, 1>(col, row) += v;
      if (with_c) {
        h.block<1, 3>(row, 0) -= v.transpose();
        h.block<3, 1>(0, row) -= v;
      }
      for (std::size_t l = 0; l < 3; ++l)
        h(row, 3 + static_cast<int>(l)) += mu.dot(rd.second[k][l].transpose() * d);
    }
  };
  for (int i = 0; i < ns; ++i) {
    const Section& s = body.sections[static_cast<std::size_t>(i)];
    const int col = 6 + kNode * i;
    misfit(col, x.segment<3>(s.dof), committed.segment<3>(s.dof), true, 1.0);
    misfit(col + 3, x.segment<3>(s.dof + 3), committed.segment<3>(s.dof + 3), false, s.w);
    misfit(col + 6, x.segment<3>(s.dof + 6), committed.segment<3>(s.dof + 6), false, s.w);
  }
  return grad;
}

double AveragedConditionsTerm::tie_force(int b, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& committed) const {
  const Body& body = bodies_.at(static_cast<std::size_t>(b));
  const Eigen::VectorXd g = tie_gradient(body, x, committed, nullptr);
  double squared = 0.0;
  for (std::size_t i = 0; i < body.sections.size(); ++i)
    squared += g.segment<kNode>(6 + kNode * static_cast<int>(i)).squaredNorm();
  return std::sqrt(squared);
}

void AveragedConditionsTerm::add(const TermState& state, Eigen::VectorXd& residual,
                                 solver::SparseAssembler* tangent) {
  roundoff_ = 0.0;
  tie_forces_.assign(bodies_.size(), 0.0);
  resultants_.assign(bodies_.size(), BodyResultant{});
  Eigen::MatrixXd h, h_tie;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const Body& body = bodies_[b];
    Eigen::VectorXd g = gradient(body, state.x, tangent ? &h : nullptr);
    const Eigen::VectorXd tie = tie_gradient(body, state.x, state.x_committed, tangent ? &h_tie : nullptr);
    tie_forces_[b] = tie.tail(tie.size() - 6).norm();
    g += tie;
    resultants_[b] = section_resultant(body, state.x, g);
    if (tangent) h += h_tie;
    residual.segment<6>(body.dof) += g.head<6>();
    double moved = (state.x.segment<3>(body.dof) - body.c0).norm();
    for (std::size_t i = 0; i < body.sections.size(); ++i) {
      const Section& s = body.sections[i];
      residual.segment<kNode>(s.dof) += g.segment<kNode>(6 + kNode * static_cast<int>(i));
      moved = std::max(moved, (state.x.segment<3>(s.dof) - s.r0).norm());
    }
    roundoff_ += kEps * body.k * static_cast<double>(body.sections.size()) * moved;
    if (tangent) tangent->add(body.blocks, h);
  }
}

double AveragedConditionsTerm::energy(int b, const Eigen::VectorXd& x) const {
  const Body& body = bodies_.at(static_cast<std::size_t>(b));
  Vec3 cc, ct;
  conditions(body, x, rotation_matrix(x.segment<3>(body.dof + 3)), cc, ct);
  return 0.5 * body.k * static_cast<double>(body.sections.size()) *
         (cc.squaredNorm() + ct.squaredNorm() / body.j);
}

double AveragedConditionsTerm::error(int b, const Eigen::VectorXd& x) const {
  const Body& body = bodies_.at(static_cast<std::size_t>(b));
  Vec3 cc, ct;
  conditions(body, x, rotation_matrix(x.segment<3>(body.dof + 3)), cc, ct);
  return std::sqrt(cc.squaredNorm() + ct.squaredNorm() / body.j);
}

BodyResultant AveragedConditionsTerm::resultant(int b, const Eigen::VectorXd& x) const {
  const Body& body = bodies_.at(static_cast<std::size_t>(b));
  return section_resultant(body, x, gradient(body, x, nullptr));
}

BodyResultant AveragedConditionsTerm::section_resultant(const Body& body, const Eigen::VectorXd& x,
                                                        const Eigen::VectorXd& g) const {
  const Vec3 c = x.segment<3>(body.dof);
  BodyResultant out;
  for (std::size_t i = 0; i < body.sections.size(); ++i) {
    const Section& s = body.sections[i];
    const int col = 6 + kNode * static_cast<int>(i);
    const Vec3 f = -g.segment<3>(col);  // the force on the section is -dW/dr_i
    out.force += f;
    out.moment += (x.segment<3>(s.dof) - c).cross(f) - x.segment<3>(s.dof + 3).cross(g.segment<3>(col + 3)) -
                  x.segment<3>(s.dof + 6).cross(g.segment<3>(col + 6));
  }
  return out;
}

}  // namespace nodus::model
