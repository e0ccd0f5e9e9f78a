#include "nodus/output/progress_reporter.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <spdlog/spdlog.h>

#include "nodus/output/progress_line.hpp"

namespace nodus::output {

ProgressReporter::ProgressReporter(double min_interval_seconds, std::string label)
    : min_interval_(std::max(0.0, min_interval_seconds)), label_(std::move(label)) {}

void ProgressReporter::on_start(const simulation::Simulation& sim) {
  start_ = Clock::now();
  last_line_ = last_step_ = start_;
  start_time_ = sim.time();
  std::vector<double> ends;
  std::vector<int> steps;
  for (std::size_t s = 0; s < sim.scenario().stages.size(); ++s) {
    ends.push_back(sim.stage_end_time(static_cast<int>(s)));
    steps.push_back(sim.scenario().stages[s].steps);
  }
  remaining_.emplace(std::move(ends), std::move(steps), start_time_);
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
  info.residual = record.residual;
  info.elapsed_seconds = std::chrono::duration<double>(now - start_).count();
  if (remaining_) info.remaining_seconds = remaining_->seconds();
  spdlog::info("{}{}", label_, progress_line(info));
}

}  // namespace nodus::output
