#include "nodus/output/steps_csv_writer.hpp"

#include <cerrno>
#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/csv.hpp"

namespace nodus::output {

std::string steps_csv_header(const std::vector<std::string>& condition_names,
                             const std::vector<std::string>& body_names) {
  std::string header =
      "step,stage,time,newton_iterations,cutbacks,residual,increment,zones,contact_elements,detections,"
      "normal_iterations,penetration_ratio,normal_force,tangential_force,slipping,stabilization_force,"
      "loops_converged,min_orientation,min_chord,min_clearance";
  for (const std::string& name : condition_names)
    for (const char* component : {"fx", "fy", "fz", "mx", "my", "mz"})
      header += "," + csv_field(name + "_" + component);
  for (const std::string& name : body_names)
    for (const char* component : {"fx", "fy", "fz", "mx", "my", "mz", "error", "tie"})
      header += "," + csv_field(name + "_" + component);
  // What made each step hard: last, so that the other columns keep their positions.
  header += ",step_size,entered,left,to_slip,to_stick,cutback_causes";
  return header;
}

std::string cutback_causes_field(const std::vector<std::string>& causes) {
  return csv_field(fmt::format("{}", fmt::join(causes, " | ")));
}

std::string steps_csv_row(const simulation::StepRecord& record, const std::string& stage_name,
                          int num_conditions, int num_bodies) {
  fmt::memory_buffer row;
  fmt::format_to(std::back_inserter(row), "{},{},{:.10g},{},{},{:.10g},{:.10g},{},{}", record.step,
                 csv_field(stage_name), record.time, record.newton_iterations, record.cutbacks,
                 record.residual, record.increment, record.zones, record.contact_elements);
  fmt::format_to(std::back_inserter(row), ",{},{},{:.10g},{:.10g},{:.10g},{},{:.10g},{}", record.detections,
                 record.normal_iterations, record.penetration_ratio, record.normal_force,
                 record.tangential_force, record.slipping, record.stabilization_force,
                 record.loops_converged ? 1 : 0);
  fmt::format_to(std::back_inserter(row), ",{:.10g},{:.10g},{:.10g}", record.min_orientation,
                 record.min_chord, record.min_clearance);
  for (int c = 0; c < num_conditions; ++c) {
    if (c < static_cast<int>(record.sections.size())) {
      const loading::SectionForce& s = record.sections[static_cast<std::size_t>(c)];
      fmt::format_to(std::back_inserter(row), ",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}", s.force.x(),
                     s.force.y(), s.force.z(), s.moment.x(), s.moment.y(), s.moment.z());
    } else {
      fmt::format_to(std::back_inserter(row), ",,,,,,");
    }
  }
  for (int b = 0; b < num_bodies; ++b) {
    if (b < static_cast<int>(record.bodies.size())) {
      const simulation::BodyRecord& s = record.bodies[static_cast<std::size_t>(b)];
      fmt::format_to(std::back_inserter(row),
                     ",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}", s.force.x(),
                     s.force.y(), s.force.z(), s.moment.x(), s.moment.y(), s.moment.z(), s.error, s.tie);
    } else {
      fmt::format_to(std::back_inserter(row), ",,,,,,,,");
    }
  }
  const contact::RegimeChanges& changes = record.regime_changes;
  fmt::format_to(std::back_inserter(row), ",{:.10g},{},{},{},{},{}", record.step_size, changes.entered,
                 changes.left, changes.to_slip, changes.to_stick,
                 cutback_causes_field(record.cutback_causes));
  return fmt::to_string(row);
}

std::string steps_csv_up_to(std::string_view text, int last_step) {
  std::string out;
  bool header = true;
  std::size_t begin = 0;
  while (begin < text.size()) {
    // The end of the record: the first line end outside double quotes.
    bool quoted = false;
    std::size_t end = begin;
    while (end < text.size() && (quoted || text[end] != '\n')) {
      if (text[end] == '"') quoted = !quoted;
      ++end;
    }
    if (end == text.size()) break;  // a line cut short by a kill
    const std::string_view record = text.substr(begin, end - begin);
    begin = end + 1;
    if (!header) {
      int step = 0;
      const auto [next, error] = std::from_chars(record.data(), record.data() + record.size(), step);
      if (error != std::errc{} || next == record.data() + record.size() || *next != ',' || step > last_step)
        break;
    }
    header = false;
    out.append(record);
    out += '\n';
  }
  return out;
}

CsvRowFile::~CsvRowFile() {
  if (file_) std::fclose(file_);
}

std::string CsvRowFile::open(const std::string& header, bool resume, int last_step) {
  std::error_code error;
  const std::filesystem::path dir = path_.parent_path();
  std::filesystem::create_directories(dir, error);
  if (error) throw_write_error("create folder", dir, error.value());
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (!resume) {
    file_ = std::fopen(path_.c_str(), "w");
    if (!file_) throw_write_error("open", path_, errno);
    write_line(header);
    return header + "\n";
  }
  std::string kept = header + "\n";
  if (std::ifstream in(path_, std::ios::binary); in) {
    std::ostringstream text;
    text << in.rdbuf();
    kept = steps_csv_up_to(text.str(), last_step);
    if (!kept.starts_with(header + "\n"))
      throw std::runtime_error("'" + path_.string() + "' does not start with the header of this scenario");
  }
  write_file_atomically(path_, kept);
  file_ = std::fopen(path_.c_str(), "a");
  if (!file_) throw_write_error("open for appending", path_, errno);
  return kept;
}

void CsvRowFile::write_line(const std::string& line) {
  if (!file_) throw std::runtime_error("'" + path_.string() + "' is not open (on_start not called)");
  if (std::fputs(line.c_str(), file_) < 0 || std::fputc('\n', file_) == EOF || std::fflush(file_) != 0)
    throw_write_error("write", path_, errno);
}

void CsvRowFile::close() {
  if (file_ && std::fclose(file_) != 0) {
    const int error = errno;
    file_ = nullptr;
    throw_write_error("write", path_, error);
  }
  file_ = nullptr;
}

void StepsCsvWriter::on_start(const simulation::Simulation& sim) {
  std::vector<std::string> names;
  for (int c = 0; c < sim.conditions().size(); ++c) names.push_back(sim.conditions().name(c));
  std::vector<std::string> bodies;
  for (const model::RigidBody& b : sim.model().bodies()) bodies.push_back(b.name);
  file_.open(steps_csv_header(names, bodies), sim.start_kind() == simulation::StartKind::resumed,
             sim.steps());
}

void StepsCsvWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  const auto& stages = sim.scenario().stages;
  const std::string stage_name = record.stage >= 0 && record.stage < static_cast<int>(stages.size())
                                     ? stages[static_cast<std::size_t>(record.stage)].name
                                     : "";
  file_.write_line(steps_csv_row(record, stage_name, sim.conditions().size(),
                                 static_cast<int>(sim.model().bodies().size())));
}

void StepsCsvWriter::on_finish(const simulation::Simulation& /*sim*/,
                               const simulation::RunSummary& /*summary*/) {
  file_.close();
}

}  // namespace nodus::output
