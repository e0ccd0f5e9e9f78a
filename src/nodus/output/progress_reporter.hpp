#pragma once
/// Progress lines through spdlog (info level) while a run goes on; see progress_line.hpp for the text.

#include <chrono>
#include <optional>
#include <string>

#include "nodus/output/progress_line.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// Logs a progress line after a converged step at most once per `min_interval_seconds` of wall time, and
/// always after the last step of a stage, with the wall time left estimated by RemainingTime.
class ProgressReporter : public simulation::StepObserver {
 public:
  /// `min_interval_seconds`: least wall time between two lines [s] (0: a line per step). `label`, when not
  /// empty, starts every line (e.g. "branch mu_0.30: ", to tell apart runs that report side by side).
  explicit ProgressReporter(double min_interval_seconds, std::string label = {});

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;

 private:
  using Clock = std::chrono::steady_clock;
  double min_interval_;
  std::string label_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_line_ = start_;
  Clock::time_point last_step_ = start_;
  double start_time_ = 0.0;  ///< load time at on_start [s]
  std::optional<RemainingTime> remaining_;
};

}  // namespace nodus::output
