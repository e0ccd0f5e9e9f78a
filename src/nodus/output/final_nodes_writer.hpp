#pragma once
/// DIR/final_nodes.csv: the last converged state, node by node (see final_nodes_table.hpp for the format).

#include <filesystem>

#include "nodus/simulation/simulation.hpp"

namespace nodus::output {

/// Writes DIR/final_nodes.csv when the run finishes (converged or not: the last converged state).
class FinalNodesWriter : public simulation::StepObserver {
 public:
  /// `dir`: output folder, created if missing.
  explicit FinalNodesWriter(std::filesystem::path dir);

  void on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) override;

  /// DIR/final_nodes.csv.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path path_;
};

}  // namespace nodus::output
