#pragma once
/// Progress lines through spdlog (info level) while a run goes on; see progress_line.hpp for the text.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nodus/output/progress_line.hpp"
#include "nodus/output/timing_csv.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// RemainingTime for a run of `scenario`'s stages from load time `start_time` [s].
RemainingTime remaining_time(const scenario::Scenario& scenario, double start_time);

/// Hands `remaining` (of a run of `scenario`) the timing of an earlier run, timing.csv's rows, if it serves:
/// its steps lie in stages of `scenario` and cover the run (RemainingTime::use_profile). Returns whether it
/// does.
bool use_timing(RemainingTime& remaining, const scenario::Scenario& scenario,
                const std::vector<TimingRow>& timing);

/// Logs a progress line after a converged step at most once per `min_interval_seconds` of wall time, and
/// always after the last step of a stage, with the wall time left estimated by RemainingTime.
class ProgressReporter : public simulation::StepObserver {
 public:
  /// `min_interval_seconds`: least wall time between two lines [s] (0: a line per step). `label`, when not
  /// empty, starts every line (e.g. "branch mu_0.30: ", to tell apart runs that report side by side).
  ///
  /// `timing`: the timing.csv of an earlier run of the same loading program, read now (before this run's
  /// TimingCsvWriter may replace it), for RemainingTime::use_profile; empty: none. It is used if its stages
  /// are this run's and it covers this run; `named`: the user named it, so a file that cannot serve is said
  /// (otherwise it is passed over in silence).
  explicit ProgressReporter(double min_interval_seconds, std::string label = {},
                            const std::filesystem::path& timing = {}, bool named = false);

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
  std::filesystem::path timing_path_;
  std::vector<TimingRow> timing_;  ///< the earlier run's, when read
  bool timing_named_ = false;
};

}  // namespace nodus::output
