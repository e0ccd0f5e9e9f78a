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
  /// Load-time size of this step [s] and the nominal step of its stage (duration / steps) [s]; NaN: unknown
  /// (the line leaves the step size out).
  double step_size = std::numeric_limits<double>::quiet_NaN();
  double nominal_step = std::numeric_limits<double>::quiet_NaN();
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
///
/// No run's past shows what its later stages will cost (the knot's `settle` costs 3 s a nominal step after
/// `pull`'s 0.3 s). Given the timing of an earlier run of the same loading program (use_profile: its wall
/// time W at each of its steps, timing.csv), the estimate follows that run's cost instead:
///   remaining = k * (W(u_end) - W(u(t))),   k = elapsed / (W(u(t)) - W(u(t_start))),
/// W interpolated linearly in nominal steps u, k this run's wall time over the earlier run's for the same
/// progress (the ratio of the two machines' speeds when the runs take the same steps).
class RemainingTime {
 public:
  /// Nominal steps over which the cost per step is smoothed.
  static constexpr double kWindow = 5.0;

  /// The stages by their end load times [s] (increasing) and nominal steps (>= 1); the run starts at load
  /// time `start_time` (a resumed or branched run starts inside or after some stages).
  RemainingTime(std::vector<double> stage_end_times, std::vector<int> stage_steps, double start_time);
  /// Estimates from an earlier run's timing (see above): its load times [s] (non-decreasing) and its wall
  /// time at each [s]. Used only if it covers this run, from its start to the end of its last stage (within
  /// 1e-9 of the end time); returns whether it is used.
  bool use_profile(const std::vector<double>& times, const std::vector<double>& wall_seconds);
  /// A converged step reached load time `time` [s], `wall_seconds` after the previous one (or the start).
  void step(double time, double wall_seconds);
  /// Wall time left [s]: NaN until a step has been measured, 0 at the end.
  double seconds() const;
  /// Progress u(t) in nominal steps (see above).
  double units(double time) const;

 private:
  /// The earlier run's wall time at progress u (linear between its steps) [s].
  double profile_wall(double u) const;

  std::vector<double> ends_;
  std::vector<int> steps_;
  double start_;
  double time_;
  double cost_ = std::numeric_limits<double>::quiet_NaN();  ///< c [s per nominal step]
  double elapsed_ = 0.0;                                    ///< wall time of this run so far [s]
  std::vector<double> profile_u_, profile_wall_;            ///< the earlier run's timing, by progress u
};

/// The size of a step for a progress line: below the nominal step, as a fraction of it ("1/8 of nominal"
/// where the nominal step is a whole multiple of it, to 1e-6, as after cutbacks; else "0.375 of nominal",
/// three significant digits); otherwise (or without a nominal step) in load time ("0.125 s"). Empty if `step`
/// is not a positive number.
std::string step_size_text(double step, double nominal);

/// "stage NAME (i/N), step S, step size Z, load time T / T_end, Newton its K, residual R, elapsed 12.3 s,
/// remaining ~45 s" (Z: step_size_text, left out with its label when the step size is unknown; one decimal
/// below 10 s; "remaining ~? s" while unknown).
std::string progress_line(const ProgressInfo& info);

}  // namespace nodus::output
