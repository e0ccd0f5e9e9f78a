#pragma once
/// A term of the equilibrium [Durville 2012, Eq. 8]: one contribution to the out-of-balance forces R = f_int
/// - f_ext (beam internal forces, loads, contact-friction, the viscous drag, ...), in the spirit of MFEM's
/// NonlinearFormIntegrator. For the current unknowns a term adds its residual and, when asked, its tangent
/// dR/dx; it names the blocks of unknowns it couples so that the problem can build the sparse pattern once.
/// The problem (simulation/equilibrium_problem.hpp) owns a list of terms and sums them; a new kind of term is
/// one class deriving from Term, registered with EquilibriumProblem::add_term.

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "nodus/solver/ordered_assembly.hpp"

namespace nodus::solver {
class SparseAssembler;
}

namespace nodus::model {

/// The state a term is evaluated at: the current unknowns and load time, and those of the last committed
/// (converged) state, for terms with history (friction) or rates (drag). Unknowns are indexed by the DofMap.
struct TermState {
  const Eigen::VectorXd& x;            ///< current unknowns, all of them (prescribed ones at their values)
  const Eigen::VectorXd& x_committed;  ///< at the last committed state
  double time = 0.0;                   ///< current load time [s]
  double time_committed = 0.0;         ///< load time of the last committed state [s]
  /// The blocks whose rows (residual and tangent) this process computes: all of them, unless the run is
  /// distributed over MPI ranks (docs/parallel.md). A term may then skip the elements that touch none of
  /// them; whatever it adds to other rows is discarded.
  solver::BlockRange blocks{};
};

/// What bounds the accuracy that can be asked of the residual, per term (EquilibriumProblem combines them).
struct ResidualScale {
  double applied = 0.0;  ///< |f_ext| of the term's loads [N]
  double floor = 0.0;  ///< the round-off level of the term's forces, below which no residual can be asked [N]
  double roundoff = 0.0;  ///< round-off of the last evaluation, added to the tolerance [N]
};

class Term {
 public:
  virtual ~Term() = default;
  /// A short name for messages ("beam internal forces").
  virtual std::string_view name() const = 0;
  /// Appends the groups of blocks the term couples (each group: blocks whose unknowns all couple together).
  /// Called when the pattern is rebuilt; a term whose couplings change asks the problem to rebuild it.
  virtual void couplings(std::vector<std::vector<int>>& groups) const = 0;
  /// Adds the term's out-of-balance forces at `state` to `residual` (over all unknowns: at prescribed ones
  /// they are reactions) and, if `tangent` is not null, their derivative to it.
  virtual void add(const TermState& state, Eigen::VectorXd& residual, solver::SparseAssembler* tangent) = 0;
  /// Whether commit() needs the term evaluated at the converged state first.
  virtual bool evaluates_before_commit() const { return false; }
  /// Accepts `state` (just evaluated, if evaluates_before_commit()) as converged: history variables move on.
  virtual void commit(const TermState& /*state*/) {}
  /// The term's scale for the residual tolerance, after the last add().
  virtual ResidualScale residual_scale() const { return {}; }
};

}  // namespace nodus::model
