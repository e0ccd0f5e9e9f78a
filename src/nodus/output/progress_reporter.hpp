#pragma once
/// Progress lines through spdlog (info level) while a run goes on; see progress_line.hpp for the text.

#include <chrono>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// Logs a progress line after a converged step at most once per `min_interval_seconds` of wall time, and
/// always after the last step of a stage.
class ProgressReporter : public simulation::StepObserver {
 public:
  /// `min_interval_seconds`: least wall time between two lines [s] (0: a line per step).
  explicit ProgressReporter(double min_interval_seconds);

  void on_start(const simulation::Simulation& sim) override;
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override;

 private:
  using Clock = std::chrono::steady_clock;
  double min_interval_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_line_ = start_;
  double start_time_ = 0.0;  ///< load time at on_start [s]
};

}  // namespace nodus::output
