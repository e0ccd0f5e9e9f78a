#include "nodus/output/steps_csv_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "nodus/output/csv.hpp"

namespace nodus::output {

std::string steps_csv_header(const std::vector<std::string>& condition_names) {
  std::string header =
      "step,stage,time,newton_iterations,cutbacks,residual,increment,zones,contact_elements,detections,"
      "normal_iterations,penetration_ratio,normal_force,tangential_force,slipping";
  for (const std::string& name : condition_names)
    for (const char* component : {"fx", "fy", "fz", "mx", "my", "mz"})
      header += "," + csv_field(name + "_" + component);
  return header;
}

std::string steps_csv_row(const simulation::StepRecord& record, const std::string& stage_name,
                          int num_conditions) {
  fmt::memory_buffer row;
  fmt::format_to(std::back_inserter(row), "{},{},{:.10g},{},{},{:.10g},{:.10g},{},{}", record.step,
                 csv_field(stage_name), record.time, record.newton_iterations, record.cutbacks,
                 record.residual, record.increment, record.zones, record.contact_elements);
  fmt::format_to(std::back_inserter(row), ",{},{},{:.10g},{:.10g},{:.10g},{}", record.detections,
                 record.normal_iterations, record.penetration_ratio, record.normal_force,
                 record.tangential_force, record.slipping);
  for (int c = 0; c < num_conditions; ++c) {
    if (c < static_cast<int>(record.sections.size())) {
      const loading::SectionForce& s = record.sections[static_cast<std::size_t>(c)];
      fmt::format_to(std::back_inserter(row), ",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}", s.force.x(),
                     s.force.y(), s.force.z(), s.moment.x(), s.moment.y(), s.moment.z());
    } else {
      fmt::format_to(std::back_inserter(row), ",,,,,,");
    }
  }
  return fmt::to_string(row);
}

StepsCsvWriter::StepsCsvWriter(std::filesystem::path dir) : dir_(std::move(dir)), path_(dir_ / "steps.csv") {}

StepsCsvWriter::~StepsCsvWriter() {
  if (file_) std::fclose(file_);
}

void StepsCsvWriter::write_line(const std::string& line) {
  if (!file_)
    throw std::runtime_error("steps.csv: '" + path_.string() + "' is not open (on_start not called)");
  if (std::fputs(line.c_str(), file_) < 0 || std::fputc('\n', file_) == EOF || std::fflush(file_) != 0)
    throw std::runtime_error("error while writing '" + path_.string() + "'");
}

void StepsCsvWriter::on_start(const simulation::Simulation& sim) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw std::runtime_error("cannot create folder '" + dir_.string() + "': " + error.message());
  if (file_) std::fclose(file_);
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot open '" + path_.string() + "' for writing");
  std::vector<std::string> names;
  for (int c = 0; c < sim.conditions().size(); ++c) names.push_back(sim.conditions().name(c));
  write_line(steps_csv_header(names));
}

void StepsCsvWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  const auto& stages = sim.scenario().stages;
  const std::string stage_name = record.stage >= 0 && record.stage < static_cast<int>(stages.size())
                                     ? stages[static_cast<std::size_t>(record.stage)].name
                                     : "";
  write_line(steps_csv_row(record, stage_name, sim.conditions().size()));
}

void StepsCsvWriter::on_finish(const simulation::Simulation& /*sim*/,
                               const simulation::RunSummary& /*summary*/) {
  if (file_ && std::fclose(file_) != 0) {
    file_ = nullptr;
    throw std::runtime_error("error while closing '" + path_.string() + "'");
  }
  file_ = nullptr;
}

}  // namespace nodus::output
