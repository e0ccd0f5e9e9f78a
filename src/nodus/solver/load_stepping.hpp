#pragma once
/// Load stepping over a load-time interval with automatic cutback when Newton fails and growth when it
/// converges easily, and a secant predictor.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/solver/newton.hpp"
#include "nodus/solver/nonlinear_problem.hpp"

namespace nodus::solver {

/// A nonlinear problem driven by a load time, whose converged states can be committed and restored.
class SteppedProblem : public NonlinearProblem {
 public:
  /// Sets the loads and prescribed values of load time t (the free unknowns keep their values).
  virtual void set_time(double t) = 0;
  /// Accepts the current state as converged at the current time (updates history variables).
  virtual void commit() = 0;
  /// Returns to the last committed state.
  virtual void restore() = 0;
};

/// The defaults are those of a scenario file (scenario::SolverSettings takes them from here).
struct StepControl {
  double nominal_step = 1.0;  ///< the user's step in load time; steps never grow beyond it
  int max_cutbacks = 12;      ///< successive halvings of a failing step before giving up
  int easy_iterations = 4;    ///< a step converged in at most this many iterations lets the next one grow
  double growth = 2.0;        ///< factor of growth after an easy step
};

struct StepResult {
  double time;   ///< load time at the end of the step
  double step;   ///< load-time size of the converged step
  int cutbacks;  ///< halvings before this step converged
  NewtonReport newton;
  /// Why each attempt of the step before the one that converged failed (NewtonReport::failure), in order:
  /// `cutbacks` entries.
  std::vector<std::string> cutback_causes = {};
};

struct AdvanceResult {
  bool completed = false;  ///< t1 reached
  bool stopped = false;    ///< on_step asked to stop (completed says whether that was at t1), or cancelled
  /// A solve was cancelled (NewtonSettings::cancel): the problem and the stepper state are back at the last
  /// converged step.
  bool cancelled = false;
  int steps = 0;
  std::string failure;
};

/// Where the stepping of an interval stands between two steps: with it, advance() continues an interval
/// exactly as if it had never been left (a saved run resumed).
struct StepperState {
  double time = 0.0;  ///< load time reached (committed)
  double step = 0.0;  ///< size of the next step attempt, after growth
  /// Free unknowns at the start of the last converged step, for the secant predictor; empty: none (no step
  /// converged yet in this interval).
  Eigen::VectorXd previous;
  double previous_step = 0.0;  ///< size of the last converged step (0: none)
  /// Halvings of the step being attempted so far (0 between steps): a StepSolver may read it, for example
  /// to give the last attempt allowed (StepControl::max_cutbacks) Newton's whole budget.
  int cutbacks = 0;
};

/// The state at the start of an interval [t0, t1]: the first step is the nominal one, or the whole interval
/// if that is shorter; no predictor.
StepperState start_stepping(double t0, double t1, const StepControl& control);

/// Solves one step from the problem's current unknowns at its current time (Newton, possibly inside outer
/// fixed-point loops); the report's iterations count every Newton iteration.
using StepSolver = std::function<NewtonReport(SteppedProblem&)>;

/// Advances from `state` to t1, updating `state`. After each converged step the problem is committed,
/// `state` updated, and `on_step` called; it returns false to stop the stepping there.
AdvanceResult advance(SteppedProblem& problem, const StepSolver& solve, double t1, const StepControl& control,
                      StepperState& state, const std::function<bool(const StepResult&)>& on_step);

/// Advances from t0 to t1. After each converged step the problem is committed and `on_step` is called.
AdvanceResult advance(SteppedProblem& problem, const StepSolver& solve, double t0, double t1,
                      const StepControl& control, const std::function<void(const StepResult&)>& on_step);

/// Same, each step solved by `newton` alone.
AdvanceResult advance(SteppedProblem& problem, NewtonSolver& newton, double t0, double t1,
                      const StepControl& control, const std::function<void(const StepResult&)>& on_step);

}  // namespace nodus::solver
