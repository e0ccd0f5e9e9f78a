#include "nodus/solver/load_stepping.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace nodus::solver {

AdvanceResult advance(SteppedProblem& problem, NewtonSolver& newton, double t0, double t1,
                      const StepControl& control, const std::function<void(const StepResult&)>& on_step) {
  return advance(
      problem, [&newton](SteppedProblem& p) { return newton.solve(p); }, t0, t1, control, on_step);
}

AdvanceResult advance(SteppedProblem& problem, const StepSolver& solve, double t0, double t1,
                      const StepControl& control, const std::function<void(const StepResult&)>& on_step) {
  StepperState state = start_stepping(t0, t1, control);
  return advance(problem, solve, t1, control, state, [&on_step](const StepResult& r) {
    on_step(r);
    return true;
  });
}

StepperState start_stepping(double t0, double t1, const StepControl& control) {
  StepperState state;
  state.time = t0;
  state.step = std::min(control.nominal_step, t1 - t0);
  return state;
}

namespace {
constexpr double kSliver = 0.01;
}  // namespace

AdvanceResult advance(SteppedProblem& problem, const StepSolver& solve, double t1, const StepControl& control,
                      StepperState& state, const std::function<bool(const StepResult&)>& on_step) {
  AdvanceResult result;
  const double eps = 1e-12 * std::max(1.0, std::abs(t1));
  double& t = state.time;
  double& step = state.step;
  int& cutbacks = state.cutbacks;
  cutbacks = 0;
  double attempted_step = step;     // the size of the step attempt before its cutbacks
  std::vector<std::string> causes;  // why the attempts of the step so far failed
  // Secant predictor: the free unknowns move as in the last converged step, scaled to the new step.
  while (t1 - t > eps) {
    // No sliver at the stage end: a step within 1 % of the remainder takes all of it (a sliver of 1e-7 of
    // a step costs a full Newton solve, and under viscous stabilisation its drag stiffness ~ 1 / dt makes
    // it ill-conditioned).
    if (cutbacks == 0) {
      attempted_step = step;
      causes.clear();
    }
    if (step >= (1.0 - kSliver) * (t1 - t)) step = t1 - t;
    const Eigen::VectorXd start = problem.unknowns();
    if (state.previous.size() == start.size() && state.previous_step > 0)
      problem.set_unknowns(start + (step / state.previous_step) * (start - state.previous));
    problem.set_time(t + step);
    NewtonReport report = solve(problem);
    if (!report.converged) {
      problem.restore();
      if (report.cancelled) {
        step = attempted_step;
        cutbacks = 0;
        result.stopped = result.cancelled = true;
        return result;
      }
      if (cutbacks >= control.max_cutbacks) {
        result.failure = fmt::format("step from load time {:.9g} to {:.9g} failed after {} cutbacks: {}", t,
                                     t + step, cutbacks, report.failure);
        cutbacks = 0;
        return result;
      }
      ++cutbacks;
      causes.push_back(report.failure);
      step *= 0.5;
      spdlog::debug("cutback {} at load time {:.6g}: {}; new step {:.3g}", cutbacks, t, report.failure, step);
      continue;
    }
    const double converged_step = step;
    t += step;
    if (t1 - t <= eps) t = t1;
    problem.commit();
    ++result.steps;
    state.previous = start;
    state.previous_step = converged_step;
    // A step is easy when its hardest Newton solve was: the contact loops solve a step several times (loop 3
    // after each update of the normals, loop 2 after each detection), and their sum counts the updates, not
    // how hard the increment was. With the sum, a knot step (20 to 70 iterations over 4 solves) never counted
    // as easy, and the step never grew back after a cutback.
    // Nor does a step that needed cutbacks let the next one grow: it would retry the size that just failed
    // (in the knot's settle stage every other attempt failed so, 116 cutbacks in 253 steps).
    const int hardest = report.longest_solve > 0 ? report.longest_solve : report.iterations;
    if (hardest <= control.easy_iterations && cutbacks == 0)
      step = std::min(control.nominal_step, step * control.growth);
    const int step_cutbacks = cutbacks;
    cutbacks = 0;
    if (!on_step({t, converged_step, step_cutbacks, report, std::move(causes)})) {
      result.stopped = true;
      result.completed = !(t1 - t > eps);
      return result;
    }
  }
  result.completed = true;
  return result;
}

}  // namespace nodus::solver
