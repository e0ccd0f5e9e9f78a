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
  last_line_ = start_;
  start_time_ = sim.time();
}

void ProgressReporter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  const Clock::time_point now = Clock::now();
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
  spdlog::info("{}{}", label_, progress_line(info));
}

}  // namespace nodus::output
