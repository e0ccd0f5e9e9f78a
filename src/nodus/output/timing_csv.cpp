#include "nodus/output/timing_csv.hpp"

#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

#include "nodus/output/csv.hpp"

namespace nodus::output {
namespace {

/// The fields of one CSV record (RFC 4180 quotes); false if a quote is left open.
bool split_record(const std::string& line, std::vector<std::string>& fields) {
  fields.assign(1, std::string());
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"')
        fields.back() += c;
      else if (i + 1 < line.size() && line[i + 1] == '"')
        fields.back() += line[++i];
      else
        quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return !quoted;
}

template <class T>
bool parse_number(const std::string& text, T& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc{} && end == text.data() + text.size();
}

}  // namespace

std::string timing_csv_row(const TimingRow& row) {
  return fmt::format("{},{},{:.10g},{},{:.10g}", row.step, csv_field(row.stage), row.time,
                     row.newton_iterations, row.wall_seconds);
}

namespace {

/// The rows of `all`, the text of a timing.csv (`path` for messages); see read_timing_csv.
std::vector<TimingRow> parse_timing_csv(const std::string& all, const std::filesystem::path& path) {
  if (all.empty())
    throw std::runtime_error(
        fmt::format("{}:1: expected the header {}, got an empty file", path.string(), kTimingCsvHeader));
  std::vector<TimingRow> rows;
  std::vector<std::string> fields;
  std::size_t begin = 0;
  for (int line = 1; begin < all.size(); ++line) {
    const std::size_t end = all.find('\n', begin);
    if (end == std::string::npos) break;  // a last line cut short by a kill
    const std::string record = all.substr(begin, end - begin);
    begin = end + 1;
    if (line == 1) {
      if (record != kTimingCsvHeader)
        throw std::runtime_error(
            fmt::format("{}:1: expected the header {}, got '{}'", path.string(), kTimingCsvHeader, record));
      continue;
    }
    TimingRow row;
    if (!split_record(record, fields) || fields.size() != 5 || !parse_number(fields[0], row.step) ||
        !parse_number(fields[2], row.time) || !parse_number(fields[3], row.newton_iterations) ||
        !parse_number(fields[4], row.wall_seconds))
      throw std::runtime_error(
          fmt::format("{}:{}: expected {} values, got '{}'", path.string(), line, kTimingCsvHeader, record));
    row.stage = std::move(fields[1]);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::vector<TimingRow> read_timing_csv(const std::filesystem::path& path) {
  return parse_timing_csv(read_text(path), path);
}

void TimingCsvWriter::on_start(const simulation::Simulation& sim) {
  const bool resume = sim.start_kind() == simulation::StartKind::resumed;
  const std::string kept = file_.open(kTimingCsvHeader, resume, sim.steps());
  const double wall_now = sim.counters().wall_seconds;
  if (resume) {
    // Goes on from the wall time of the last row kept.
    const std::vector<TimingRow> rows = parse_timing_csv(kept, file_.path());
    wall_offset_ = wall_now - (rows.empty() ? 0.0 : rows.back().wall_seconds);
    return;
  }
  wall_offset_ = wall_now;
  const auto& stages = sim.scenario().stages;
  const int stage = sim.progress().stage;
  TimingRow start;
  start.step = sim.steps();
  start.stage = stage >= 0 && stage < static_cast<int>(stages.size())
                    ? stages[static_cast<std::size_t>(stage)].name
                    : std::string();
  start.time = sim.time();
  file_.write_line(timing_csv_row(start));
}

void TimingCsvWriter::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  const auto& stages = sim.scenario().stages;
  TimingRow row;
  row.step = record.step;
  row.stage = record.stage >= 0 && record.stage < static_cast<int>(stages.size())
                  ? stages[static_cast<std::size_t>(record.stage)].name
                  : std::string();
  row.time = record.time;
  row.newton_iterations = record.newton_iterations;
  row.wall_seconds = sim.counters().wall_seconds - wall_offset_;
  file_.write_line(timing_csv_row(row));
}

void TimingCsvWriter::on_finish(const simulation::Simulation& /*sim*/,
                                const simulation::RunSummary& /*summary*/) {
  file_.close();
}

}  // namespace nodus::output
