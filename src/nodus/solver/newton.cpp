#include "nodus/solver/newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <Eigen/SparseCore>

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

/// Why a solve should stop for too little progress (NewtonSettings::progress_window), or "" while it makes
/// enough. `history`: |R| after each iteration since the problem last changed.
std::string progress_failure(const std::vector<double>& history, int progress_window, double progress_ratio,
                             double tolerance) {
  const auto w = static_cast<std::size_t>(progress_window);
  if (w == 0 || history.size() < w + 2) return {};
  const auto window = history.end() - static_cast<std::ptrdiff_t>(w);
  const double before = *std::min_element(history.begin(), window);
  const double recent = *std::min_element(window, history.end());
  if (recent <= progress_ratio * before) return {};
  return fmt::format(
      "too little progress (smallest |R| {:.3e} in the last {} iterations, {:.3e} before them; tolerance "
      "{:.3e})",
      recent, w, before, tolerance);
}

}  // namespace

bool NewtonSolver::solve_linear(const SparseMatrix& tangent, std::uint64_t pattern_version,
                                const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  // A factor of an earlier pattern (before a detection changed the contact elements) still preconditions the
  // current tangent as long as the unknowns are the same: the new pattern is analysed only when the tangent
  // is factorised again. The policy depends on counts only, never on timings, so that a run gives the same
  // results on any machine and when resumed.
  if (settings_.reuse_factor && factored_ && factor_size_ == tangent.rows()) {
    const KrylovSolve krylov =
        linear_->solve_on_factor(tangent, pattern_version != handed_version_, rhs, settings_.krylov_tolerance,
                                 settings_.krylov_iterations, x);
    handed_version_ = pattern_version;
    timings_.krylov_iterations += krylov.iterations;
    if (krylov.accepted) return true;
    spdlog::debug(
        "newton: GMRES on the lagged factor did not reach {:.1e} of the residual in {} iterations; "
        "refactorising",
        settings_.krylov_tolerance, krylov.iterations);
  }
  if (!analyzed_ || pattern_version != analyzed_version_) {
    linear_->analyze(tangent);
    analyzed_ = true;
    analyzed_version_ = handed_version_ = pattern_version;
    ++timings_.analyses;
  }
  factored_ = linear_->factorize(tangent);
  factor_size_ = tangent.rows();
  ++timings_.factorizations;
  if (!factored_) return false;
  x = linear_->solve(rhs);
  return true;
}

std::optional<double> NewtonSolver::backtrack(NonlinearProblem& problem, const Eigen::VectorXd& u,
                                              const Eigen::VectorXd& du, double start_norm,
                                              const Eigen::VectorXd& full_residual) {
  constexpr double armijo = 1e-4;
  double best_norm = full_residual.allFinite() ? full_residual.norm() : INFINITY;
  if (best_norm <= (1.0 - armijo) * start_norm) return std::nullopt;
  double best_alpha = 1.0;
  double alpha = 1.0;
  Eigen::VectorXd residual;
  for (int k = 0; k < settings_.max_backtracks && !(best_norm <= (1.0 - armijo * best_alpha) * start_norm);
       ++k) {
    alpha *= 0.5;
    problem.set_unknowns(problem.step(u, alpha * du));
    problem.evaluate(residual, false);
    const double norm = residual.allFinite() ? residual.norm() : INFINITY;
    if (norm < best_norm) {
      best_norm = norm;
      best_alpha = alpha;
    }
  }
  return best_alpha;
}

NewtonReport NewtonSolver::solve(NonlinearProblem& problem, const FixedPointUpdate& update,
                                 double loose_residual) {
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
  // The smallest |R| since the problem last changed (a fixed-point update), and its iteration.
  double best = INFINITY;
  int best_at = 0;
  // |R| after each iteration since the problem last changed, for the progress rule.
  std::vector<double> history;
  for (int it = 1; it <= settings_.max_iterations; ++it) {
    ++timings_.iterations;
    Eigen::VectorXd du;
    {
      const Stopwatch watch(timings_.linear_solve);
      if (!solve_linear(problem.tangent(), problem.pattern_version(), residual, du)) {
        report.failure = fmt::format("the tangent is singular (iteration {})", it);
        report.iterations = it;
        report.residual = norm;
        return report;
      }
      du = -du;
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
    Eigen::VectorXd next = problem.step(u, du);  // the unknowns at alpha, as last set
    {
      const Stopwatch watch(timings_.evaluation);
      problem.set_unknowns(next);
      // Without a line search the full step is taken: its tangent is assembled with its residual, in one
      // pass over the terms instead of two.
      problem.evaluate(trial_residual, !settings_.line_search);
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
          next = problem.step(u, alpha * du);
          problem.set_unknowns(next);
          problem.evaluate(trial_residual, false);
          s_alpha = du.dot(trial_residual);
        }
      }
    }
    if (settings_.backtrack_from > 0 && it >= settings_.backtrack_from && !settings_.line_search) {
      const Stopwatch watch(timings_.evaluation);
      if (const std::optional<double> shorter = backtrack(problem, u, du, residual.norm(), trial_residual)) {
        alpha = *shorter;
        next = problem.step(u, alpha * du);
        problem.set_unknowns(next);
        problem.evaluate(trial_residual, true);
      }
    }
    if (!trial_residual.allFinite()) {
      report.failure = fmt::format("the residual became non-finite (iteration {})", it);
      report.iterations = it;
      return report;
    }
    u = std::move(next);
    increment = alpha * problem.scaled_increment(du);
    residual = trial_residual;
    norm = residual.norm();
    report.iterations = it;
    report.residual = norm;
    report.residual_tolerance = problem.residual_tolerance();
    report.increment = increment;
    spdlog::debug("newton {:2d}: |R| = {:.3e} (tol {:.1e}), |du| = {:.3e}, alpha = {}", it, norm,
                  problem.residual_tolerance(), increment, alpha);
    const bool converged =
        (norm <= problem.residual_tolerance() && increment <= problem.increment_tolerance()) ||
        norm <= loose_residual;
    const bool changed = update && update({it, norm, converged});
    if (converged && !changed) {
      report.converged = true;
      return report;
    }
    if (changed) {
      best = INFINITY;
      best_at = it;
      history.clear();
    } else {
      history.push_back(norm);
      if (norm < best) {
        best = norm;
        best_at = it;
      } else if (settings_.stagnation_iterations > 0 && it - best_at >= settings_.stagnation_iterations) {
        report.failure = fmt::format(
            "no progress in {} iterations (|R| = {:.3e}, smallest {:.3e} at iteration {}; tolerance {:.3e})",
            it - best_at, norm, best, best_at, problem.residual_tolerance());
        return report;
      }
      report.failure = progress_failure(history, settings_.progress_window, settings_.progress_ratio,
                                        problem.residual_tolerance());
      if (!report.failure.empty()) return report;
    }
    if (settings_.cancel && settings_.cancel()) {
      report.cancelled = true;
      report.failure = fmt::format("cancelled after iteration {}", it);
      return report;
    }
    if (it < settings_.max_iterations && (settings_.line_search || changed)) {
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
