#pragma once
/// VTK XML files of a state (readable by ParaView): the beams as tubes drawn from the current section
/// directors, so that the section's deformation shows, plus their centrelines; and the .pvd collection that
/// lists the files of a run with their load times.
///
/// Point layout of a picture: first one centreline point per node (point index = global node index), then
/// `tube_sides` ring points per node: ring point j of node n is r + R (cos phi_j g1 + sin phi_j g2) with
/// phi_j = 2 pi j / tube_sides, R the beam radius and g1, g2 the current (not normalised) directors.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/model/model.hpp"
#include "nodus/output/vtk_encoding.hpp"

namespace nodus::output {

/// Points and cells of the picture of one state.
struct TubeMesh {
  Eigen::Matrix3Xd points;                      ///< all points, centreline ones first [mm]
  std::vector<int> point_node;                  ///< global node of each point
  std::vector<std::int64_t> line_connectivity;  ///< one polyline per beam through its node centres
  std::vector<std::int64_t> line_offsets;       ///< end of each polyline in line_connectivity
  std::vector<std::int64_t> poly_connectivity;  ///< quads between consecutive rings, outward normals
  std::vector<std::int64_t> poly_offsets;       ///< end of each quad in poly_connectivity
};

/// Index of ring point `j` (0 .. tube_sides - 1) of global node `node` in TubeMesh::points.
inline std::int64_t ring_point_index(int num_nodes, int tube_sides, int node, int j) {
  return static_cast<std::int64_t>(num_nodes) + static_cast<std::int64_t>(node) * tube_sides + j;
}

/// The picture's geometry for state `x` (nine values per node). Throws std::invalid_argument if x does not
/// fit the model or tube_sides < 3.
TubeMesh tube_mesh(const model::Model& model, const Eigen::VectorXd& x, int tube_sides);

/// Writes the VTK XML PolyData document of state `x` in `encoding` (vtk_xml.hpp): the points and cells of
/// tube_mesh, and per point (ring points take their node's values) the arrays `beam` (Int32 beam index),
/// `node` (Int32 global node), `displacement` (centre displacement from the reference [mm]), `g1`, `g2`
/// (directors [-]) and one Float64 array per strain measure named by beam::strain_name (model.node_strains).
/// `time` [s], if given, is stored as the field TimeValue.
void write_vtp(std::ostream& out, const model::Model& model, const Eigen::VectorXd& x, int tube_sides,
               std::optional<double> time = std::nullopt, VtkEncoding encoding = VtkEncoding::binary);

/// Same into file `path` (temporary file + rename). Throws std::runtime_error naming the path on I/O errors.
void write_vtp(const std::filesystem::path& path, const model::Model& model, const Eigen::VectorXd& x,
               int tube_sides, std::optional<double> time = std::nullopt,
               VtkEncoding encoding = VtkEncoding::binary);

/// One file of a ParaView collection.
struct PvdEntry {
  double time = 0.0;  ///< load time [s]
  std::string file;   ///< path relative to the .pvd file, '/' separated
};

/// The .pvd collection document listing `entries` in order.
std::string pvd_document(const std::vector<PvdEntry>& entries);

/// Writes pvd_document(entries) to `path` (temporary file + rename).
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

/// `text` with the five XML special characters escaped, for attribute values.
std::string xml_escape(const std::string& text);

}  // namespace nodus::output
