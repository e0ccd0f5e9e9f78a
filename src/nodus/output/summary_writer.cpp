#include "nodus/output/summary_writer.hpp"

#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

#include "nodus/output/atomic_file.hpp"

namespace nodus::output {

SummaryData summary_data(const simulation::Simulation& sim, const simulation::RunSummary& summary) {
  SummaryData data;
  data.dofs = sim.model().num_dofs();
  data.nodes = sim.model().num_nodes();
  data.elements = sim.model().num_elements();
  data.beams = static_cast<int>(sim.model().beams().size());
  data.steps = summary.steps;
  data.newton_iterations = summary.newton_iterations;
  data.converged = summary.converged;
  data.wall_seconds = summary.wall_seconds;
  data.detection_seconds = summary.detection_seconds;
  data.assembly_seconds = summary.assembly_seconds;
  data.linear_solve_seconds = summary.linear_solve_seconds;
  data.failure = summary.failure;
  data.final_time = sim.time();
  data.scenario = sim.scenario().path;
  return data;
}

std::string summary_json(const SummaryData& data) {
  nlohmann::ordered_json j;
  j["scenario"] = data.scenario;
  j["converged"] = data.converged;
  j["failure"] = data.failure;
  j["steps"] = data.steps;
  j["newton_iterations"] = data.newton_iterations;
  j["final_time"] = data.final_time;
  j["wall_seconds"] = data.wall_seconds;
  j["detection_seconds"] = data.detection_seconds;
  j["assembly_seconds"] = data.assembly_seconds;
  j["linear_solve_seconds"] = data.linear_solve_seconds;
  j["beams"] = data.beams;
  j["nodes"] = data.nodes;
  j["elements"] = data.elements;
  j["dofs"] = data.dofs;
  // Replace rather than throw on invalid UTF-8 in a path or a message.
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

void write_summary(const std::filesystem::path& path, const SummaryData& data) {
  write_file_atomically(path, summary_json(data));
}

SummaryWriter::SummaryWriter(std::filesystem::path dir)
    : dir_(std::move(dir)), path_(dir_ / "summary.json") {}

void SummaryWriter::on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw std::runtime_error("cannot create folder '" + dir_.string() + "': " + error.message());
  write_summary(path_, summary_data(sim, summary));
}

}  // namespace nodus::output
