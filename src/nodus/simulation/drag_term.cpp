#include "nodus/simulation/drag_term.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nodus/solver/sparse_assembler.hpp"

namespace nodus::simulation {

double Stabilization::at(double t) const {
  if (start <= 0.0 || t1 <= t0) return 0.0;
  const double u = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
  if (end > 0.0) return start * std::pow(end / start, u);
  return u >= 1.0 - 1e-12 ? 0.0 : start * std::pow(1e-6, u);
}

DragTerm::DragTerm(const model::Model& model) : model_(model) {
  // Each quadratic element of length h gives h/6, 2h/3, h/6 to its nodes (Simpson's rule): the weights of a
  // beam add up to its length.
  // The drag on the directors is that of the section's points averaged over the disc: <xi_a xi_b> = R^2/4
  // delta_ab, so each director takes R^2/4 times the weight of the centre.
  const auto nodes = static_cast<std::size_t>(model_.num_nodes());
  node_length_.assign(nodes, 0.0);
  node_director_length_.assign(nodes, 0.0);
  for (const beam::Beam& b : model_.beams())
    for (int e = 0; e < b.num_elements(); ++e) {
      const double h = b.element_length(), spread = 0.25 * b.radius() * b.radius();
      const double weights[3] = {h / 6.0, 2.0 * h / 3.0, h / 6.0};
      for (int k = 0; k < 3; ++k) {
        const auto n = static_cast<std::size_t>(b.node(2 * e + k));
        node_length_[n] += weights[k];
        node_director_length_[n] += spread * weights[k];
      }
    }
}

void DragTerm::couplings(std::vector<std::vector<int>>& groups) const {
  for (int n = 0; n < model_.num_nodes(); ++n) groups.push_back({n});
}

void DragTerm::add(const model::TermState& state, Eigen::VectorXd& residual,
                   solver::SparseAssembler* tangent) {
  constexpr int kNode = beam::kNodeDofs;
  force_ = 0.0;
  roundoff_ = 0.0;
  const double dt = state.time - state.time_committed;
  const double eta = stabilization_.at(state.time);
  if (eta <= 0.0 || dt <= 0.0) return;
  double squared = 0.0, roundoff = 0.0;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  Eigen::Matrix<double, kNode, kNode> k;
  for (std::size_t n = 0; n < node_length_.size(); ++n) {
    const double c = eta * node_length_[n] / dt, c_directors = eta * node_director_length_[n] / dt;
    const int i = model_.node_dof(static_cast<int>(n));
    // Prescribed nodes feel the drag too: their supports carry it (a tool dragged through the same medium).
    Eigen::Matrix<double, kNode, 1> weight;
    weight << Eigen::Vector3d::Constant(c), Eigen::Matrix<double, 6, 1>::Constant(c_directors);
    const auto drag =
        (weight.array() * (state.x.segment<kNode>(i) - state.x_committed.segment<kNode>(i)).array())
            .matrix()
            .eval();
    residual.segment<kNode>(i) += drag;
    squared += drag.squaredNorm();
    roundoff += (kEps * weight.array() * state.x.segment<kNode>(i).array().abs()).matrix().squaredNorm();
    if (tangent) {
      k = weight.asDiagonal();
      const int block[1] = {static_cast<int>(n)};
      tangent->add(block, k);
    }
  }
  force_ = std::sqrt(squared);
  roundoff_ = std::sqrt(roundoff);
}

}  // namespace nodus::simulation
