#include "nodus/output/progress_reporter.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <spdlog/spdlog.h>

#include "nodus/output/progress_line.hpp"

namespace nodus::output {

ProgressReporter::ProgressReporter(double min_interval_seconds, std::string label,
                                   const std::filesystem::path& timing, bool named)
    : min_interval_(std::max(0.0, min_interval_seconds)),
      label_(std::move(label)),
      timing_path_(timing),
      timing_named_(named) {
  if (timing.empty()) return;
  try {
    if (named || std::filesystem::exists(timing)) timing_ = read_timing_csv(timing);
  } catch (const std::exception& e) {
    if (named) spdlog::warn("{}{}; the time left is estimated from this run alone", label_, e.what());
  }
}

RemainingTime remaining_time(const scenario::Scenario& scenario, double start_time) {
  std::vector<double> ends;
  std::vector<int> steps;
  for (std::size_t s = 0; s < scenario.stages.size(); ++s) {
    ends.push_back(scenario::stage_end_time(scenario, static_cast<int>(s)));
    steps.push_back(scenario.stages[s].steps);
  }
  return RemainingTime(std::move(ends), std::move(steps), start_time);
}

bool use_timing(RemainingTime& remaining, const scenario::Scenario& scenario,
                const std::vector<TimingRow>& timing) {
  std::set<std::string> names;
  for (const scenario::StageSpec& stage : scenario.stages) names.insert(stage.name);
  std::vector<double> times, walls;
  for (const TimingRow& row : timing) {
    if (!names.contains(row.stage)) return false;
    times.push_back(row.time);
    walls.push_back(row.wall_seconds);
  }
  return remaining.use_profile(times, walls);
}

void ProgressReporter::on_start(const simulation::Simulation& sim) {
  start_ = Clock::now();
  last_line_ = last_step_ = start_;
  start_time_ = sim.time();
  const auto& stages = sim.scenario().stages;
  remaining_.emplace(remaining_time(sim.scenario(), start_time_));
  if (timing_.empty()) return;
  if (use_timing(*remaining_, sim.scenario(), timing_))
    spdlog::info("{}the time left is estimated from the timing of an earlier run ({})", label_,
                 timing_path_.string());
  else if (timing_named_)
    spdlog::warn(
        "{}{} is not the timing of a run of these stages from load time {:.6g} s to {:.6g} s; the time left "
        "is estimated from this run alone",
        label_, timing_path_.string(), start_time_,
        stages.empty() ? start_time_ : sim.stage_end_time(static_cast<int>(stages.size()) - 1));
  timing_.clear();
}

void ProgressReporter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  const Clock::time_point now = Clock::now();
  if (remaining_) remaining_->step(record.time, std::chrono::duration<double>(now - last_step_).count());
  last_step_ = now;
  const double stage_end = sim.stage_end_time(record.stage);
  const bool last_of_stage = record.time >= stage_end - 1e-12 * std::max(1.0, std::abs(stage_end));
  if (!last_of_stage && std::chrono::duration<double>(now - last_line_).count() < min_interval_) return;
  last_line_ = now;

  const auto& stages = sim.scenario().stages;
  const int num_stages = static_cast<int>(stages.size());
  ProgressInfo info;
  info.stage_name = record.stage >= 0 && record.stage < num_stages
                        ? stages[static_cast<std::size_t>(record.stage)].name
                        : "?";
  info.stage = record.stage;
  info.num_stages = num_stages;
  info.step = record.step;
  info.time = record.time;
  info.start_time = start_time_;
  info.end_time = num_stages > 0 ? sim.stage_end_time(num_stages - 1) : record.time;
  info.newton_iterations = record.newton_iterations;
  info.step_size = record.step_size;
  if (record.stage >= 0 && record.stage < num_stages) {
    const scenario::StageSpec& stage = stages[static_cast<std::size_t>(record.stage)];
    if (stage.steps > 0) info.nominal_step = stage.duration / stage.steps;
  }
  info.residual = record.residual;
  info.elapsed_seconds = std::chrono::duration<double>(now - start_).count();
  if (remaining_) info.remaining_seconds = remaining_->seconds();
  spdlog::info("{}{}", label_, progress_line(info));
}

}  // namespace nodus::output
