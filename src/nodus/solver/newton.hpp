#pragma once
/// Newton-Raphson, optionally with a line search on the slope of the energy along the Newton direction.

#include <functional>
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
  /// Asked after each iteration: true stops the solve there (NewtonReport::cancelled), as Ctrl-C in Python
  /// does. Empty: never.
  std::function<bool()> cancel;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  /// The iterations of the longest single Newton solve among `iterations`: a step solved by several Newton
  /// solves (the contact loops) sums them in `iterations`. 0: the same as `iterations`.
  int longest_solve = 0;
  double residual = 0.0;   ///< |R| at the end [residual units]
  double increment = 0.0;  ///< scaled size of the last increment
  std::string failure;     ///< why it did not converge
  bool cancelled = false;  ///< stopped by NewtonSettings::cancel, not by a failure
};

/// Where Newton's time went, summed over all solves [s].
struct NewtonTimings {
  double evaluation = 0.0;    ///< residual and tangent assembly (problem.evaluate), line search included
  double linear_solve = 0.0;  ///< symbolic analysis, factorisation and solve
  int iterations = 0;
};

class NewtonSolver {
 public:
  NewtonSolver(LinearSolver& linear_solver, NewtonSettings settings)
      : linear_(linear_solver), settings_(settings) {}
  /// Iterates from the problem's current unknowns. Convergence needs both |R| <= residual_tolerance and
  /// scaled |du| <= increment_tolerance. Call reanalyze() when the tangent pattern changes.
  NewtonReport solve(NonlinearProblem& problem);
  void reanalyze() { analyzed_ = false; }
  const NewtonTimings& timings() const { return timings_; }

 private:
  LinearSolver& linear_;
  NewtonSettings settings_;
  bool analyzed_ = false;
  NewtonTimings timings_;
};

}  // namespace nodus::solver
