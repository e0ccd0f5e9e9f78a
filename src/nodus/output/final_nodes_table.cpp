#include "nodus/output/final_nodes_table.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/csv.hpp"

namespace nodus::output {

std::string final_nodes_csv(const model::Model& model, const Eigen::VectorXd& x) {
  if (x.size() != model.num_dofs())
    throw std::invalid_argument(fmt::format("final_nodes_csv: state has {} values, the model {} unknowns",
                                            x.size(), model.num_dofs()));
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n");
  for (const beam::Beam& b : model.beams()) {
    const std::string name = csv_field(b.name());
    for (int i = 0; i < b.num_nodes(); ++i) {
      fmt::format_to(std::back_inserter(out), "{},{},{:.12g}", name, i, b.abscissa(i));
      const Eigen::Index first = model.node_dof(b.node(i));
      for (int k = 0; k < beam::kNodeDofs; ++k)
        fmt::format_to(std::back_inserter(out), ",{:.12g}", x[first + k]);
      out.push_back('\n');
    }
  }
  return fmt::to_string(out);
}

void write_final_nodes(const std::filesystem::path& path, const model::Model& model,
                       const Eigen::VectorXd& x) {
  write_file_atomically(path, final_nodes_csv(model, x));
}

namespace {

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

const std::vector<std::string> kTableColumns{"beam", "node", "s", "x", "y", "z"};

[[noreturn]] void fail_table(const std::filesystem::path& path, int line, const std::string& expected,
                             const std::string& got) {
  throw std::invalid_argument(fmt::format("{}:{}: expected {}, got {}", path.string(), line, expected, got));
}

/// Opens a nodal table and reads its header; throws on a missing file or another header.
std::ifstream open_table(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument(
        fmt::format("{}: expected a readable nodal table (final_nodes.csv), got none", path.string()));
  std::string line;
  if (!std::getline(in, line)) fail_table(path, 1, "the header beam,node,s,x,y,z,...", "an empty file");
  const std::vector<std::string> header = split_row(line);
  if (header.size() < kTableColumns.size() ||
      !std::equal(kTableColumns.begin(), kTableColumns.end(), header.begin()))
    fail_table(path, 1, "the header beam,node,s,x,y,z,...",
               "'" + (line.size() > 60 ? line.substr(0, 60) + "...'" : line + "'"));
  return in;
}

}  // namespace

std::vector<std::string> read_table_beams(const std::filesystem::path& path) {
  std::ifstream in = open_table(path);
  std::vector<std::string> beams;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::string name = split_row(line).front();
    if (std::find(beams.begin(), beams.end(), name) == beams.end()) beams.push_back(name);
  }
  return beams;
}

TableCurve read_table_curve(const std::filesystem::path& path, const std::string& beam) {
  std::ifstream in = open_table(path);
  const auto fail = [&](int line, const std::string& expected, const std::string& got) {
    fail_table(path, line, expected, got);
  };
  const std::vector<std::string>& wanted = kTableColumns;
  std::string line;
  TableCurve curve;
  curve.beam = beam;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = split_row(line);
    if (cells.size() < wanted.size()) fail(number, "at least 6 values", std::to_string(cells.size()));
    if (curve.beam.empty()) curve.beam = cells[0];
    if (cells[0] != curve.beam) continue;
    double v[4];
    for (int k = 0; k < 4; ++k) {
      const std::string& cell = cells[static_cast<std::size_t>(2 + k)];
      const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v[k]);
      if (ec != std::errc() || end != cell.data() + cell.size())
        fail(number, "a number in column " + wanted[static_cast<std::size_t>(2 + k)], "'" + cell + "'");
    }
    if (!curve.s.empty() && !(v[0] > curve.s.back()))
      fail(number, fmt::format("s increasing along beam {}", curve.beam),
           fmt::format("{:g} after {:g}", v[0], curve.s.back()));
    curve.s.push_back(v[0]);
    curve.points.emplace_back(v[1], v[2], v[3]);
  }
  if (curve.s.size() < 2)
    fail(number,
         fmt::format("at least two nodes of beam {}", curve.beam.empty() ? std::string("(any)") : curve.beam),
         std::to_string(curve.s.size()));
  return curve;
}

}  // namespace nodus::output
