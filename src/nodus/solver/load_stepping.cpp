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
  AdvanceResult result;
  const double span = t1 - t0;
  const double eps = 1e-12 * std::max(1.0, std::abs(t1));
  double t = t0;
  double step = std::min(control.nominal_step, span);
  int cutbacks = 0;
  // Secant predictor: the free unknowns move as in the last converged step, scaled to the new step.
  Eigen::VectorXd previous;  // unknowns at the start of the last converged step
  double previous_step = 0.0;
  while (t1 - t > eps) {
    step = std::min(step, t1 - t);
    const Eigen::VectorXd start = problem.unknowns();
    if (previous.size() == start.size() && previous_step > 0)
      problem.set_unknowns(start + (step / previous_step) * (start - previous));
    problem.set_time(t + step);
    NewtonReport report = solve(problem);
    if (!report.converged) {
      problem.restore();
      if (cutbacks >= control.max_cutbacks) {
        result.failure = fmt::format("step from load time {:.9g} to {:.9g} failed after {} cutbacks: {}", t,
                                     t + step, cutbacks, report.failure);
        return result;
      }
      ++cutbacks;
      step *= 0.5;
      spdlog::debug("cutback {} at load time {:.6g}: {}; new step {:.3g}", cutbacks, t, report.failure, step);
      continue;
    }
    t += step;
    if (t1 - t <= eps) t = t1;
    problem.commit();
    ++result.steps;
    on_step({t, step, cutbacks, report});
    previous = start;
    previous_step = step;
    if (report.iterations <= control.easy_iterations)
      step = std::min(control.nominal_step, step * control.growth);
    cutbacks = 0;
  }
  result.completed = true;
  return result;
}

}  // namespace nodus::solver
