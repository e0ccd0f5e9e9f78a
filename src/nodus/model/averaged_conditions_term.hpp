#pragma once
/// Averaged kinematic conditions that bind each rigid body to its beam sections [Durville 2012, Sect. 7.3.1:
/// "so that given twistings can be prescribed to the global assembly, while allowing the elementary fibres
/// to rearrange themselves"], as a term of the equilibrium. docs/bodies.md derives it.
///
/// A body (c, Q = Q(theta)) is bound to n sections i (centre r_i, directors g_1i, g_2i; in the reference
/// state r_i0, g_ai0; radius R_i). With a_i = r_i0 - c0 (c0 the mean of the r_i0, so sum a_i = 0) and
/// w_i = R_i^2 / 4 (the mean of xi_a^2 over the disc), the rigid motion that best fits the material points
/// of the n end discs in the least-squares sense minimises
///
///   Phi(c, Q) = (1/n) sum_i [ |r_i - c - Q a_i|^2 + w_i sum_a |g_ai - Q g_ai0|^2 ].
///
/// The body is held at that best fit: Phi is stationary in c and in Q (spin omega, dQ = [omega]x Q),
///
///   C_c = (c - c0) - (1/n) sum_i (r_i - r_i0) = 0                                   [mm]
///   C_t = (1/n) sum_i [ (Q a_i) x (r_i - c) + w_i sum_a (Q g_ai0) x g_ai ] = 0       [mm^2]
///
/// six conditions per body. They hold for any rigid motion of the body with its sections, and leave every
/// motion of the sections that keeps the best fit where the body is free: the fibres rearrange at no cost.
/// They are enforced by the penalty energy
///
///   W = (k n / 2) (|C_c|^2 + |C_t|^2 / J),   J = (1/n) sum_i (|a_i|^2 + 2 w_i)   [mm^2],
///
/// k = factor * (mean E A / h of the bound sections, A = pi R^2) [N/mm]. sqrt(|C_c|^2 + |C_t|^2 / J) [mm] is
/// the error the penalty leaves (error()).
///
/// What the conditions leave free costs nothing, and a section held by nothing else (a fibre that touches no
/// other yet) then makes the tangent singular: n sections spreading radially, or turning about their own
/// axes by opposite angles. A tie resists the part of each step's motion that rearranges the sections
/// relative to the body, measured in the body's frame, eps_i = Q^T (r_i - c) - a_i, phi_ai = Q^T g_ai -
/// g_ai0, against their values at the last converged state:
///
///   D = (k_t / 2) sum_i [ |eps_i - eps_i*|^2 + w_i sum_a |phi_ai - phi_ai*|^2 ],   k_t = tie * k.
///
/// It is zero for any rigid motion and at rest, like a drag on the rearrangement within a step; its force
/// is reported (tie_force()). Residual and tangent are exact (Q's second derivatives included).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"
#include "nodus/model/term.hpp"

namespace nodus::model {

/// The force and moment a body exerts on its bound sections [N, N mm], the moment about the body's point c.
struct BodyResultant {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

class AveragedConditionsTerm final : public Term {
 public:
  /// The conditions of every body of `model`; penalty factor and tie per body (<= 0 or missing: the
  /// defaults).
  AveragedConditionsTerm(const Model& model, const std::vector<double>& penalty_factors,
                         const std::vector<double>& ties = {});

  static constexpr double kDefaultPenalty = 1e3;
  static constexpr double kDefaultTie = 1e-10;

  std::string_view name() const override { return "averaged conditions of rigid bodies"; }
  void couplings(std::vector<std::vector<int>>& groups) const override;
  void add(const TermState& state, Eigen::VectorXd& residual, solver::SparseAssembler* tangent) override;
  /// Round-off of C_c and C_t, which are formed from displacements: 10 eps k n sqrt(J) per body, summed.
  ResidualScale residual_scale() const override { return {0.0, floor_, roundoff_}; }

  /// The penalty energy W [N mm] of body b at x.
  double energy(int b, const Eigen::VectorXd& x) const;
  /// sqrt(|C_c|^2 + |C_t|^2 / J) of body b at x [mm]: how far the penalty lets the body stray from the best
  /// fit of its sections.
  double error(int b, const Eigen::VectorXd& x) const;
  /// The force and moment body b exerts on its sections at x through the conditions (the tie left out).
  BodyResultant resultant(int b, const Eigen::VectorXd& x) const;
  /// The force and moment body b exerted on its sections at the last add(), conditions and tie (in a run:
  /// at the converged state of the last step).
  BodyResultant last_resultant(int b) const {
    return static_cast<std::size_t>(b) < resultants_.size() ? resultants_[static_cast<std::size_t>(b)]
                                                            : BodyResultant{};
  }
  /// k of body b [N/mm].
  double penalty(int b) const { return bodies_[static_cast<std::size_t>(b)].k; }
  /// |force of the tie| over the sections of body b at x, the last converged state being `committed` [N].
  double tie_force(int b, const Eigen::VectorXd& x, const Eigen::VectorXd& committed) const;
  /// The same at the last add() (in a run: the converged state of the last step) [N].
  double last_tie_force(int b) const {
    return static_cast<std::size_t>(b) < tie_forces_.size() ? tie_forces_[static_cast<std::size_t>(b)] : 0.0;
  }

 private:
  struct Section {
    int dof = 0;                ///< first unknown of its node
    Eigen::Vector3d a, g1, g2;  ///< a_i, g_1i0, g_2i0
    Eigen::Vector3d r0;         ///< r_i0
    double w = 0.0;             ///< R_i^2 / 4 [mm^2]
  };
  struct Body {
    int dof = 0;  ///< first of its six unknowns
    int block = 0;
    Eigen::Vector3d c0;
    std::vector<Section> sections;
    std::vector<int> blocks;  ///< its own block, then its sections' nodes
    double k = 0.0, j = 0.0;
    double kt = 0.0;  ///< k_t [N/mm]
  };
  /// C_c and C_t of body b at x.
  void conditions(const Body& body, const Eigen::VectorXd& x, const Eigen::Matrix3d& q, Eigen::Vector3d& cc,
                  Eigen::Vector3d& ct) const;
  /// d W / d q over the body's unknowns (c, theta, then r, g1, g2 of each section).
  Eigen::VectorXd gradient(const Body& body, const Eigen::VectorXd& x, Eigen::MatrixXd* hessian) const;
  /// d D / d q, the same way; `committed`: the last converged state.
  Eigen::VectorXd tie_gradient(const Body& body, const Eigen::VectorXd& x, const Eigen::VectorXd& committed,
                               Eigen::MatrixXd* hessian) const;

  std::vector<Body> bodies_;
  std::vector<double> tie_forces_;         ///< per body, at the last add()
  std::vector<BodyResultant> resultants_;  ///< per body, at the last add()
  /// The force and moment on the sections of the body's gradient g (over its unknowns) at x.
  BodyResultant section_resultant(const Body& body, const Eigen::VectorXd& x, const Eigen::VectorXd& g) const;
  double floor_ = 0.0, roundoff_ = 0.0;
};

}  // namespace nodus::model
