#include "nodus/output/summary_writer.hpp"

#include <fstream>
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
  data.factorizations = summary.factorizations;
  data.analyses = summary.analyses;
  data.krylov_iterations = summary.krylov_iterations;
  data.failure = summary.failure;
  data.final_time = sim.time();
  data.scenario = sim.scenario().path;
  if (sim.contact() && sim.contact_forces()) data.friction = sim.scenario().contact.friction;
  if (sim.scenario().origin) data.branch = sim.scenario().origin->name;
  data.provenance = this_process(summary.linear_solvers);
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
  j["factorizations"] = data.factorizations;
  j["analyses"] = data.analyses;
  j["krylov_iterations"] = data.krylov_iterations;
  j["beams"] = data.beams;
  j["nodes"] = data.nodes;
  j["elements"] = data.elements;
  j["dofs"] = data.dofs;
  if (data.friction) j["friction"] = *data.friction;
  if (!data.branch.empty()) j["branch"] = data.branch;
  if (!data.branches.empty()) {
    j["branches"] = nlohmann::ordered_json::array();
    for (const BranchOutcome& b : data.branches) {
      nlohmann::ordered_json o;
      o["name"] = b.name;
      o["from"] = b.from;
      o["friction"] = b.friction;
      o["folder"] = b.folder;
      o["converged"] = b.converged;
      o["failure"] = b.failure;
      o["steps"] = b.steps;
      o["final_time"] = b.final_time;
      j["branches"].push_back(std::move(o));
    }
  }
  if (data.provenance) {
    const Provenance& p = *data.provenance;
    nlohmann::ordered_json o;
    o["nodus"] = p.version;
    o["commit"] = p.commit;
    o["processor"] = p.processor;
    o["hardware_threads"] = p.hardware_threads;
    o["threads"] = p.threads;
    o["mpi_ranks"] = p.mpi_ranks;
    o["linear_solvers"] = p.linear_solvers;
    j["provenance"] = std::move(o);
  }
  // Replace rather than throw on invalid UTF-8 in a path or a message.
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

void write_summary(const std::filesystem::path& path, const SummaryData& data) {
  write_file_atomically(path, summary_json(data));
}

SummaryData read_summary(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open '" + path.string() + "'");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    SummaryData data;
    data.scenario = j.value("scenario", "");
    data.converged = j.at("converged").get<bool>();
    data.failure = j.value("failure", "");
    data.steps = j.at("steps").get<int>();
    data.newton_iterations = j.value("newton_iterations", 0);
    data.final_time = j.value("final_time", 0.0);
    data.wall_seconds = j.value("wall_seconds", 0.0);
    data.detection_seconds = j.value("detection_seconds", 0.0);
    data.assembly_seconds = j.value("assembly_seconds", 0.0);
    data.linear_solve_seconds = j.value("linear_solve_seconds", 0.0);
    data.factorizations = j.value("factorizations", 0);
    data.analyses = j.value("analyses", 0);
    data.krylov_iterations = j.value("krylov_iterations", 0);
    data.beams = j.value("beams", 0);
    data.nodes = j.value("nodes", 0);
    data.elements = j.value("elements", 0);
    data.dofs = j.value("dofs", 0);
    data.branch = j.value("branch", "");
    return data;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("cannot read '" + path.string() + "': " + e.what());
  }
}

SummaryWriter::SummaryWriter(std::filesystem::path dir, bool write_at_finish)
    : dir_(std::move(dir)), path_(dir_ / "summary.json"), write_at_finish_(write_at_finish) {}

void SummaryWriter::on_start(const simulation::Simulation& /*sim*/) {
  data_.reset();
  std::error_code error;
  std::filesystem::remove(path_, error);
  if (error) throw std::runtime_error("cannot remove old file '" + path_.string() + "': " + error.message());
}

void SummaryWriter::on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) {
  data_ = summary_data(sim, summary);
  if (!write_at_finish_) return;
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw_write_error("create folder", dir_, error.value());
  write_summary(path_, *data_);
}

}  // namespace nodus::output
