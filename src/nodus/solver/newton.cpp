#include "nodus/solver/newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace nodus::solver {
namespace {

/// Adds the wall time of its lifetime to `total`.
class Stopwatch {
 public:
  explicit Stopwatch(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

NewtonReport NewtonSolver::solve(NonlinearProblem& problem) {
  NewtonReport report;
  Eigen::VectorXd residual;
  Eigen::VectorXd u = problem.unknowns();
  {
    const Stopwatch watch(timings_.evaluation);
    problem.evaluate(residual, true);
  }
  double norm = residual.norm();
  if (!std::isfinite(norm)) {
    report.failure = "the residual is not finite at the start of the step";
    return report;
  }
  double increment = INFINITY;
  for (int it = 1; it <= settings_.max_iterations; ++it) {
    ++timings_.iterations;
    Eigen::VectorXd du;
    {
      const Stopwatch watch(timings_.linear_solve);
      if (!analyzed_) {
        linear_.analyze(problem.tangent());
        analyzed_ = true;
      }
      if (!linear_.factorize(problem.tangent())) {
        report.failure = fmt::format("the tangent is singular (iteration {})", it);
        report.iterations = it;
        report.residual = norm;
        return report;
      }
      du = -linear_.solve(residual);
    }
    if (!du.allFinite()) {
      report.failure = fmt::format("the linear solve gave a non-finite increment (iteration {})", it);
      report.iterations = it;
      return report;
    }
    // Line search on the slope s(alpha) = du . R(u + alpha du) [Crisfield 1991]: for a conservative problem
    // it minimises the energy along du, and unlike |R| it does not penalise the large out-of-balance forces
    // of stiff axial terms that a good Newton step leaves behind. The full step is kept when |s(1)| is at
    // most `slope_ratio` |s(0)|, or when du is not a descent direction (indefinite tangent).
    double alpha = 1.0;
    Eigen::VectorXd trial_residual;
    {
      const Stopwatch watch(timings_.evaluation);
      problem.set_unknowns(u + du);
      problem.evaluate(trial_residual, false);
      const double s0 = du.dot(residual);
      if (settings_.line_search && s0 < 0.0) {
        double lo = 0.0, s_lo = s0;        // s < 0 at lo
        double hi = INFINITY, s_hi = 0.0;  // s > 0 (or not finite) at hi, once found
        double s_alpha = du.dot(trial_residual);
        for (int k = 0; k < settings_.max_line_search_iterations; ++k) {
          if (std::isfinite(s_alpha) && std::abs(s_alpha) <= settings_.slope_ratio * std::abs(s0)) break;
          if (!std::isfinite(s_alpha) || s_alpha > 0.0) {
            hi = alpha;
            s_hi = s_alpha;
          } else {
            lo = alpha;
            s_lo = s_alpha;
          }
          if (!std::isfinite(hi))
            alpha = 2.0 * alpha;  // still descending at the longest step tried
          else if (!std::isfinite(s_hi))
            alpha = 0.5 * (lo + hi);
          else  // regula falsi inside the bracket, kept away from its ends
            alpha =
                std::clamp(lo - s_lo * (hi - lo) / (s_hi - s_lo), lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo));
          problem.set_unknowns(u + alpha * du);
          problem.evaluate(trial_residual, false);
          s_alpha = du.dot(trial_residual);
        }
      }
    }
    if (!trial_residual.allFinite()) {
      report.failure = fmt::format("the residual became non-finite (iteration {})", it);
      report.iterations = it;
      return report;
    }
    u += alpha * du;
    increment = alpha * problem.scaled_increment(du);
    residual = trial_residual;
    norm = residual.norm();
    report.iterations = it;
    report.residual = norm;
    report.increment = increment;
    spdlog::debug("newton {:2d}: |R| = {:.3e} (tol {:.1e}), |du| = {:.3e}, alpha = {}", it, norm,
                  problem.residual_tolerance(), increment, alpha);
    if (norm <= problem.residual_tolerance() && increment <= problem.increment_tolerance()) {
      report.converged = true;
      return report;
    }
    if (settings_.cancel && settings_.cancel()) {
      report.cancelled = true;
      report.failure = fmt::format("cancelled after iteration {}", it);
      return report;
    }
    if (it < settings_.max_iterations) {
      const Stopwatch tangent_watch(timings_.evaluation);
      problem.evaluate(residual, true);
    }
  }
  report.failure =
      fmt::format("no convergence in {} iterations (|R| = {:.3e}, tolerance {:.3e}; |du| = {:.3e})",
                  settings_.max_iterations, norm, problem.residual_tolerance(), increment);
  return report;
}

}  // namespace nodus::solver
