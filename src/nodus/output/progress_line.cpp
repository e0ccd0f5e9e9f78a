#include "nodus/output/progress_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

namespace nodus::output {

double remaining_seconds(double elapsed_seconds, double start_time, double time, double end_time) {
  const double done = time - start_time;
  const double left = end_time - time;
  if (left <= 0) return 0.0;
  if (!(done > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(0.0, elapsed_seconds) * left / done;
}

RemainingTime::RemainingTime(std::vector<double> stage_end_times, std::vector<int> stage_steps,
                             double start_time)
    : ends_(std::move(stage_end_times)),
      steps_(std::move(stage_steps)),
      start_(start_time),
      time_(start_time) {}

bool RemainingTime::use_profile(const std::vector<double>& times, const std::vector<double>& wall_seconds) {
  if (times.empty() || times.size() != wall_seconds.size() || ends_.empty()) return false;
  const double end = ends_.back();
  const double tolerance = 1e-9 * std::max(1.0, std::abs(end));
  if (std::abs(times.back() - end) > tolerance || times.front() > start_ + tolerance) return false;
  std::vector<double> u, w;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (i > 0 && (times[i] < times[i - 1] || wall_seconds[i] < wall_seconds[i - 1])) return false;
    u.push_back(units(times[i]));
    w.push_back(wall_seconds[i]);
  }
  profile_u_ = std::move(u);
  profile_wall_ = std::move(w);
  return true;
}

double RemainingTime::profile_wall(double u) const {
  const auto upper = std::upper_bound(profile_u_.begin(), profile_u_.end(), u);
  if (upper == profile_u_.begin()) return profile_wall_.front();
  if (upper == profile_u_.end()) return profile_wall_.back();
  const std::size_t i = static_cast<std::size_t>(upper - profile_u_.begin());
  const double f = (u - profile_u_[i - 1]) / (profile_u_[i] - profile_u_[i - 1]);
  return profile_wall_[i - 1] + f * (profile_wall_[i] - profile_wall_[i - 1]);
}

double RemainingTime::units(double time) const {
  double u = 0.0, t0 = 0.0;
  for (std::size_t s = 0; s < ends_.size(); ++s) {
    const double duration = ends_[s] - t0;
    const double fraction =
        duration > 0.0 ? std::clamp((time - t0) / duration, 0.0, 1.0) : (time >= t0 ? 1.0 : 0.0);
    u += steps_[s] * fraction;
    t0 = ends_[s];
  }
  return u;
}

void RemainingTime::step(double time, double wall_seconds) {
  const double du = units(time) - units(time_);
  time_ = time;
  if (wall_seconds >= 0.0) elapsed_ += wall_seconds;
  if (!(du > 0.0) || !(wall_seconds >= 0.0)) return;
  const double cost = wall_seconds / du;
  if (std::isnan(cost_))
    cost_ = cost;
  else
    cost_ += (1.0 - std::exp(-du / kWindow)) * (cost - cost_);
}

double RemainingTime::seconds() const {
  const double left = (ends_.empty() ? 0.0 : units(ends_.back())) - units(time_);
  if (left <= 1e-12) return 0.0;
  if (!profile_u_.empty()) {
    const double now = profile_wall(units(time_));
    const double done = now - profile_wall(units(start_));
    if (done > 0.0) return elapsed_ / done * (profile_wall_.back() - now);
  }
  return cost_ * left;
}

std::string step_size_text(double step, double nominal) {
  if (!(step > 0.0) || !std::isfinite(step)) return {};
  if (nominal > 0.0 && std::isfinite(nominal) && step < (1.0 - 1e-9) * nominal) {
    const double parts = nominal / step;
    const double whole = std::round(parts);
    if (std::abs(parts - whole) <= 1e-6 * whole) return fmt::format("1/{:.0f} of nominal", whole);
    return fmt::format("{:.3g} of nominal", step / nominal);
  }
  return fmt::format("{:.6g} s", step);
}

std::string progress_line(const ProgressInfo& info) {
  const double remaining =
      std::isnan(info.remaining_seconds)
          ? remaining_seconds(info.elapsed_seconds, info.start_time, info.time, info.end_time)
          : info.remaining_seconds;
  const std::string remaining_text = !std::isfinite(remaining) ? std::string("~? s")
                                     : remaining < 10          ? fmt::format("~{:.1f} s", remaining)
                                                               : fmt::format("~{:.0f} s", remaining);
  const std::string size = step_size_text(info.step_size, info.nominal_step);
  return fmt::format("stage {} ({}/{}), step {}, {}load time {:.6g} / {:.6g}, ", info.stage_name,
                     info.stage + 1, info.num_stages, info.step,
                     size.empty() ? std::string() : "step size " + size + ", ", info.time, info.end_time) +
         fmt::format("Newton its {}, residual {:.3e}, elapsed {:.1f} s, remaining {}", info.newton_iterations,
                     info.residual, info.elapsed_seconds, remaining_text);
}

}  // namespace nodus::output
