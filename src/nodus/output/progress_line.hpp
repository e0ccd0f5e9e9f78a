#pragma once
/// The text of a progress line and its estimate of the wall time left.

#include <string>

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
};

/// Wall time left [s], extrapolating the rate of load time per wall second so far:
/// elapsed * (end_time - time) / (time - start_time). NaN while no load time has passed; 0 at the end.
double remaining_seconds(double elapsed_seconds, double start_time, double time, double end_time);

/// "stage NAME (i/N), step S, load time T / T_end, Newton its K, residual R, elapsed 12.3 s, remaining ~45 s"
/// (one decimal below 10 s; "remaining ~? s" while unknown).
std::string progress_line(const ProgressInfo& info);

}  // namespace nodus::output
