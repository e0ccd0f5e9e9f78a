#include "nodus/output/final_nodes_writer.hpp"

#include <stdexcept>
#include <system_error>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/final_nodes_table.hpp"

namespace nodus::output {

FinalNodesWriter::FinalNodesWriter(std::filesystem::path dir)
    : dir_(std::move(dir)), path_(dir_ / "final_nodes.csv") {}

void FinalNodesWriter::on_finish(const simulation::Simulation& sim,
                                 const simulation::RunSummary& /*summary*/) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw_write_error("create folder", dir_, error.value());
  write_final_nodes(path_, sim.model(), sim.state());
}

}  // namespace nodus::output
