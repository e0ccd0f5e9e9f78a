#pragma once
/// The text of a progress line and its estimate of the wall time left.

#include <limits>
#include <string>
#include <vector>

namespace nodus::output {

/// Where a run stands after a converged step.
struct ProgressInfo {
  std::string stage_name;
  int stage = 0;  ///< index into Scenario::stages (printed one based)
  int num_stages = 0;
  int step = 0;                ///< converged step, 1, 2, ... over the run
  double time = 0.0;           ///< load time reached [s]
  double start_time = 0.0;     ///< load time at the start of the run [s]
  double end_time = 0.0;       ///< load time at the end of the last stage [s]
  int newton_iterations = 0;   ///< of this step
  double residual = 0.0;       ///< at convergence [N]
  double elapsed_seconds = 0;  ///< wall-clock time since the start of the run [s]
  /// Wall time left [s] (RemainingTime); NaN: remaining_seconds(elapsed, start_time, time, end_time).
  double remaining_seconds = std::numeric_limits<double>::quiet_NaN();
};

/// Wall time left [s], extrapolating the rate of load time per wall second so far:
/// elapsed * (end_time - time) / (time - start_time). NaN while no load time has passed; 0 at the end.
/// (The simple estimate; progress lines use RemainingTime.)
double remaining_seconds(double elapsed_seconds, double start_time, double time, double end_time);

/// The wall time left in a run, from the measured cost of its current stage.
///
/// The stages of a run differ in cost per unit of load time by orders of magnitude (the knot's `release`
/// puts 20 steps into 1 s of load time, its `rest` 20 steps into 40 s), so one rate over the whole run swings
/// as the stages change (a branch's estimate fell from 6,086 s to 77 s within two minutes). A stage's cost
/// follows its steps rather than its duration: the user sizes the steps to the difficulty. Progress is
/// therefore counted in nominal steps, the load time of each stage in units of its step duration / steps:
///   u(t) = sum over stages s of steps_s * clamp((t - t0_s) / duration_s, 0, 1),
/// and the estimate is
///   remaining = c * (u_end - u(t)),
/// c the wall seconds per nominal step measured in the current stage, smoothed exponentially over the last
/// kWindow nominal steps (c += (1 - exp(-du / kWindow)) (dw / du - c) after a step of du units that took dw
/// seconds). A new stage starts from the last stage's c. docs/performance.md shows how the estimate tracked
/// the truth on the flagship.
class RemainingTime {
 public:
  /// Nominal steps over which the cost per step is smoothed.
  static constexpr double kWindow = 5.0;

  /// The stages by their end load times [s] (increasing) and nominal steps (>= 1); the run starts at load
  /// time `start_time` (a resumed or branched run starts inside or after some stages).
  RemainingTime(std::vector<double> stage_end_times, std::vector<int> stage_steps, double start_time);
  /// A converged step reached load time `time` [s], `wall_seconds` after the previous one (or the start).
  void step(double time, double wall_seconds);
  /// Wall time left [s]: NaN until a step has been measured, 0 at the end.
  double seconds() const;
  /// Progress u(t) in nominal steps (see above).
  double units(double time) const;

 private:
  std::vector<double> ends_;
  std::vector<int> steps_;
  double time_;
  double cost_ = std::numeric_limits<double>::quiet_NaN();  ///< c [s per nominal step]
};

/// "stage NAME (i/N), step S, load time T / T_end, Newton its K, residual R, elapsed 12.3 s, remaining ~45 s"
/// (one decimal below 10 s; "remaining ~? s" while unknown).
std::string progress_line(const ProgressInfo& info);

}  // namespace nodus::output
