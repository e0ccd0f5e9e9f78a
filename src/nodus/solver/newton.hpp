#pragma once
/// Newton-Raphson, optionally with a line search on the slope of the energy along the Newton direction.

#include <functional>
#include <optional>
#include <string>

#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/nonlinear_problem.hpp"

namespace nodus::solver {

/// The defaults are those of a scenario file (scenario::SolverSettings takes them from here).
struct NewtonSettings {
  int max_iterations = 25;   ///< iterations per solve
  bool line_search = false;  ///< slower on every verification case so far (docs/model.md)
  int max_line_search_iterations = 6;
  /// The step is accepted once |du . R(u + alpha du)| <= slope_ratio |du . R(u)|.
  double slope_ratio = 0.5;
  /// > 0 (and no line search): from this iteration of each solve on, a full Newton step that does not reduce
  /// |R| by the Armijo fraction 1e-4 is halved, up to `max_backtracks` times, and the step length with the
  /// smallest |R| is taken (the full step where none is smaller). A solve whose contact elements switch
  /// back and forth between stick and slip, or in and out of contact, can cycle with full steps (the same
  /// few |R| over and over); the shorter steps break the cycle. The first iterations of a solve, whose
  /// residual a good Newton step may raise (stiff axial terms), take full steps. 0: never
  /// (docs/model.md, "Backtracking").
  int backtrack_from = 0;
  int max_backtracks = 6;  ///< >= 1
  /// Asked after each iteration: true stops the solve there (NewtonReport::cancelled), as Ctrl-C in Python
  /// does. Empty: never.
  std::function<bool()> cancel;
  /// Keep the factorisation of the tangent across Newton iterations and load steps: each increment is then
  /// solved by GMRES on the current tangent, preconditioned by the last factor, and the tangent is factorised
  /// again only when GMRES does not reach `krylov_tolerance` within `krylov_iterations` (docs/performance.md,
  /// "Fewer iterations, and a factor kept across them"). false: a factorisation per iteration.
  bool reuse_factor = false;
  int krylov_iterations = 20;  ///< GMRES iterations allowed with a lagged factor before refactorising
  /// An increment from GMRES is accepted when |K du + R| <= krylov_tolerance |R|. At 1e-6, Newton took the
  /// same iterations as with exact solves on the 100-element knot (docs/performance.md).
  double krylov_tolerance = 1e-6;
  /// > 0: a solve stops as failed once this many iterations have passed without a residual smaller than the
  /// smallest since the problem last changed (a fixed-point update): a wandering Newton is given up before
  /// max_iterations, and the step is cut back sooner. 0: never (docs/performance.md, "Stagnating Newton").
  int stagnation_iterations = 0;
  /// > 0: a solve stops as failed at iteration k once the smallest |R| of its last `progress_window`
  /// iterations is not below `progress_ratio` times the smallest before them (with at least two iterations
  /// before them, all since the problem last changed): a Newton that swings without converging is given up
  /// sooner, though it finds a new smallest |R| now and then. 0: never (docs/performance.md, "Failing
  /// sooner").
  int progress_window = 0;
  double progress_ratio = 0.1;  ///< in (0, 1)
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  /// The iterations of the longest single Newton solve among `iterations`: a step solved by several Newton
  /// solves (the contact loops) sums them in `iterations`. 0: the same as `iterations`.
  int longest_solve = 0;
  double residual = 0.0;            ///< |R| at the end [residual units]
  double residual_tolerance = 0.0;  ///< the tolerance |R| was compared with at the end [residual units]
  double increment = 0.0;           ///< scaled size of the last increment
  std::string failure;              ///< why it did not converge
  bool cancelled = false;           ///< stopped by NewtonSettings::cancel, not by a failure
};

/// Where Newton's time went, summed over all solves [s].
struct NewtonTimings {
  double evaluation = 0.0;    ///< residual and tangent assembly (problem.evaluate), line search included
  double linear_solve = 0.0;  ///< symbolic analysis, factorisation and solve (GMRES included)
  int iterations = 0;
  int factorizations = 0;     ///< numerical factorisations of the tangent
  int analyses = 0;           ///< symbolic analyses of its pattern (a new pattern after a detection)
  int krylov_iterations = 0;  ///< GMRES iterations on lagged factors, summed
};

/// Where a Newton solve stands after an iteration, for a fixed point solved inside it.
struct NewtonProgress {
  int iteration = 0;
  double residual = 0.0;   ///< |R| after the iteration
  bool converged = false;  ///< by the tolerances, for the problem as it is
};

/// A fixed point solved together with the equilibrium (the contact normals and penalties of loop 3, Sect. 6):
/// called after each iteration; returns true if it changed the problem, which Newton then goes on solving.
/// A solve converges only at a state where the update changes nothing.
using FixedPointUpdate = std::function<bool(const NewtonProgress&)>;

class NewtonSolver {
 public:
  NewtonSolver(LinearSolver& linear_solver, NewtonSettings settings)
      : linear_(&linear_solver), settings_(settings) {}
  /// Iterates from the problem's current unknowns. Convergence needs both |R| <= residual_tolerance and
  /// scaled |du| <= increment_tolerance. The tangent's pattern is analysed again when the problem's
  /// pattern_version() changes, or after reanalyze() (for problems that do not track it).
  /// `loose_residual` > 0: converged as soon as |R| <= loose_residual, whatever the increment (a solve whose
  /// result only serves to update a fixed point, not as a step's answer).
  NewtonReport solve(NonlinearProblem& problem, const FixedPointUpdate& update = {},
                     double loose_residual = 0.0);
  void reanalyze() { analyzed_ = false; }
  /// Starts a new sequence of solves (a load step attempt) as a run resumed there would start it: the
  /// tangent is analysed again if the linear solver's analysis reads the values
  /// (LinearSolver::analysis_reads_values), so that the resumed run repeats the one never stopped.
  void restart() {
    if (linear_->analysis_reads_values()) analyzed_ = false;
  }
  /// Solves with `linear_solver` from now on (a stage's own choice): its analysis and factorisation start
  /// afresh. Unchanged if it is the one in use.
  void set_linear_solver(LinearSolver& linear_solver) {
    if (&linear_solver == linear_) return;
    linear_ = &linear_solver;
    analyzed_ = false;
    factored_ = false;
  }
  /// Damps the updates of later solves by the line search, or not (a stage's own choice).
  void set_line_search(bool on) { settings_.line_search = on; }
  void set_progress_window(int iterations) { settings_.progress_window = iterations; }
  const NewtonTimings& timings() const { return timings_; }

 private:
  /// With the full step's residual not reducing |R| = start_norm enough: the residual at u + alpha du for
  /// alpha halved up to max_backtracks times, and the alpha of the smallest |R| (1 where none is smaller).
  /// The problem's unknowns are left at the last alpha tried: the caller sets them. nullopt: the full step
  /// reduces |R| enough (nothing tried, the unknowns untouched).
  std::optional<double> backtrack(NonlinearProblem& problem, const Eigen::VectorXd& u,
                                  const Eigen::VectorXd& du, double start_norm,
                                  const Eigen::VectorXd& full_residual);
  /// Solves `tangent` x = `rhs`: with GMRES on the lagged factor while it serves, else by a new
  /// factorisation. Returns false if the tangent is singular.
  bool solve_linear(const SparseMatrix& tangent, std::uint64_t pattern_version, const Eigen::VectorXd& rhs,
                    Eigen::VectorXd& x);

  LinearSolver* linear_;  ///< never null
  NewtonSettings settings_;
  bool analyzed_ = false;
  std::uint64_t analyzed_version_ = 0;  ///< the problem's pattern_version() at the analysis
  /// The pattern version last handed to the linear solver (by an analysis or a solve on the kept factor).
  std::uint64_t handed_version_ = 0;
  bool factored_ = false;         ///< the linear solver holds a factorisation (perhaps of an earlier pattern)
  Eigen::Index factor_size_ = 0;  ///< the number of unknowns of that factorisation
  NewtonTimings timings_;
};

}  // namespace nodus::solver
