#include "nodus/output/final_nodes_table.hpp"

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
      const Eigen::Index first = static_cast<Eigen::Index>(model::kDofsPerNode) * b.node(i);
      for (int k = 0; k < model::kDofsPerNode; ++k)
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

}  // namespace nodus::output
