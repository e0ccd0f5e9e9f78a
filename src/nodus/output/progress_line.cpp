#include "nodus/output/progress_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace nodus::output {

double remaining_seconds(double elapsed_seconds, double start_time, double time, double end_time) {
  const double done = time - start_time;
  const double left = end_time - time;
  if (left <= 0) return 0.0;
  if (!(done > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(0.0, elapsed_seconds) * left / done;
}

std::string progress_line(const ProgressInfo& info) {
  const double remaining = remaining_seconds(info.elapsed_seconds, info.start_time, info.time, info.end_time);
  const std::string remaining_text = !std::isfinite(remaining) ? std::string("~? s")
                                     : remaining < 10          ? fmt::format("~{:.1f} s", remaining)
                                                               : fmt::format("~{:.0f} s", remaining);
  return fmt::format("stage {} ({}/{}), step {}, load time {:.6g} / {:.6g}, ", info.stage_name,
                     info.stage + 1, info.num_stages, info.step, info.time, info.end_time) +
         fmt::format("Newton its {}, residual {:.3e}, elapsed {:.1f} s, remaining {}", info.newton_iterations,
                     info.residual, info.elapsed_seconds, remaining_text);
}

}  // namespace nodus::output
