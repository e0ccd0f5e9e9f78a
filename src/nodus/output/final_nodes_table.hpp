#pragma once
/// The nodal table of a state: one CSV row per node of every beam with its reference abscissa and its nine
/// unknowns (centre r and directors g1, g2). Written as DIR/final_nodes.csv at the end of a run.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"

namespace nodus::output {

/// The whole CSV text: header `beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z`, then per beam (model order) per
/// local node: beam name, local node index, reference arc length s [mm], r [mm], g1 [-], g2 [-] (twelve
/// significant digits). `x` holds nine values per node (Model numbering). Throws std::invalid_argument on a
/// size mismatch.
std::string final_nodes_csv(const model::Model& model, const Eigen::VectorXd& x);

/// Writes final_nodes_csv(model, x) to `path` through a temporary file and a rename.
void write_final_nodes(const std::filesystem::path& path, const model::Model& model,
                       const Eigen::VectorXd& x);

/// The centreline of one beam read back from a nodal table (final_nodes.csv, stages/NNN_STAGE_nodes.csv).
struct TableCurve {
  std::string beam;
  std::vector<double> s;                ///< reference arc length of each node [mm], increasing
  std::vector<Eigen::Vector3d> points;  ///< the centre of each node [mm]
};

/// Reads the nodes of beam `beam` (empty: the first beam of the file) from a nodal table, in node order.
/// Throws std::invalid_argument with "PATH:LINE: what was expected, got what" on a file that is not such a
/// table (missing columns, a value that is not a number, a node out of order, no such beam, fewer than two
/// nodes).
TableCurve read_table_curve(const std::filesystem::path& path, const std::string& beam = "");

/// The names of the beams of a nodal table, in the order of their first rows. Throws as read_table_curve on a
/// file that is not such a table (no readable file, another header).
std::vector<std::string> read_table_beams(const std::filesystem::path& path);

}  // namespace nodus::output
