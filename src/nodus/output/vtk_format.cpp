#include "nodus/output/vtk_format.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "nodus/beam/strain_measures.hpp"
#include "nodus/output/atomic_file.hpp"
#include "nodus/output/vtk_xml.hpp"

namespace nodus::output {
namespace {

void check_inputs(const model::Model& model, const Eigen::VectorXd& x, int tube_sides) {
  if (x.size() != model.num_dofs())
    throw std::invalid_argument(
        fmt::format("VTK output: state has {} values, the model {} unknowns", x.size(), model.num_dofs()));
  if (tube_sides < 3)
    throw std::invalid_argument(fmt::format("VTK output: tube_sides = {}, must be >= 3", tube_sides));
}

/// A point-data array with `components` values per node (value_of_node(n, values) appends them), repeated for
/// the node's ring points: centreline points first, then the rings (TubeMesh's order).
template <typename T, typename ValueOfNode>
std::vector<T> node_array(int components, int num_nodes, int tube_sides, ValueOfNode value_of_node) {
  std::vector<T> values;
  values.reserve(static_cast<std::size_t>(num_nodes) *
                 static_cast<std::size_t>((1 + tube_sides) * components));
  for (int n = 0; n < num_nodes; ++n) value_of_node(n, values);
  for (int n = 0; n < num_nodes; ++n)
    for (int j = 0; j < tube_sides; ++j) value_of_node(n, values);
  return values;
}

}  // namespace

TubeMesh tube_mesh(const model::Model& model, const Eigen::VectorXd& x, int tube_sides) {
  check_inputs(model, x, tube_sides);
  const int num_nodes = model.num_nodes();
  TubeMesh mesh;
  mesh.points.resize(3, static_cast<Eigen::Index>(num_nodes) * (1 + tube_sides));
  mesh.point_node.resize(static_cast<std::size_t>(mesh.points.cols()));
  std::vector<double> cosines(static_cast<std::size_t>(tube_sides)),
      sines(static_cast<std::size_t>(tube_sides));
  for (int j = 0; j < tube_sides; ++j) {
    const double phi = 2.0 * std::numbers::pi * j / tube_sides;
    cosines[static_cast<std::size_t>(j)] = std::cos(phi);
    sines[static_cast<std::size_t>(j)] = std::sin(phi);
  }
  for (const beam::Beam& b : model.beams()) {
    const double radius = b.radius();
    for (int i = 0; i < b.num_nodes(); ++i) {
      const int n = b.node(i);
      const Eigen::Index first = model.node_dof(n);
      const Eigen::Vector3d r = x.segment<3>(first);
      const Eigen::Vector3d g1 = x.segment<3>(first + 3);
      const Eigen::Vector3d g2 = x.segment<3>(first + 6);
      mesh.points.col(n) = r;
      mesh.point_node[static_cast<std::size_t>(n)] = n;
      for (int j = 0; j < tube_sides; ++j) {
        const std::int64_t p = ring_point_index(num_nodes, tube_sides, n, j);
        mesh.points.col(p) = r + radius * (cosines[static_cast<std::size_t>(j)] * g1 +
                                           sines[static_cast<std::size_t>(j)] * g2);
        mesh.point_node[static_cast<std::size_t>(p)] = n;
      }
    }
    for (int i = 0; i < b.num_nodes(); ++i) mesh.line_connectivity.push_back(b.node(i));
    mesh.line_offsets.push_back(static_cast<std::int64_t>(mesh.line_connectivity.size()));
    // Quad (a_j, a_j+1, b_j+1, b_j): with g1 x g2 along the axis its normal points outwards.
    for (int i = 0; i + 1 < b.num_nodes(); ++i) {
      const int na = b.node(i), nb = b.node(i + 1);
      for (int j = 0; j < tube_sides; ++j) {
        const int k = (j + 1) % tube_sides;
        for (std::int64_t p :
             {ring_point_index(num_nodes, tube_sides, na, j), ring_point_index(num_nodes, tube_sides, na, k),
              ring_point_index(num_nodes, tube_sides, nb, k), ring_point_index(num_nodes, tube_sides, nb, j)})
          mesh.poly_connectivity.push_back(p);
        mesh.poly_offsets.push_back(static_cast<std::int64_t>(mesh.poly_connectivity.size()));
      }
    }
  }
  return mesh;
}

void write_vtp(std::ostream& out, const model::Model& model, const Eigen::VectorXd& x, int tube_sides,
               std::optional<double> time, VtkEncoding encoding) {
  const TubeMesh mesh = tube_mesh(model, x, tube_sides);
  const auto strains = model.node_strains(x);
  const int num_nodes = model.num_nodes();
  std::vector<int> beam_of_node(static_cast<std::size_t>(num_nodes), 0);
  for (int b = 0; b < static_cast<int>(model.beams().size()); ++b)
    for (int i = 0; i < model.beam(b).num_nodes(); ++i)
      beam_of_node[static_cast<std::size_t>(model.beam(b).node(i))] = b;

  vtk_xml::PolyDataWriter w(out, encoding, time,
                            {mesh.points.cols(), static_cast<std::int64_t>(mesh.line_offsets.size()),
                             static_cast<std::int64_t>(mesh.poly_offsets.size())});
  w.open("PointData Scalars=\"beam\" Vectors=\"displacement\"");
  w.array("beam", node_array<std::int32_t>(1, num_nodes, tube_sides, [&](int n, auto& v) {
            v.push_back(beam_of_node[static_cast<std::size_t>(n)]);
          }));
  w.array("node", node_array<std::int32_t>(1, num_nodes, tube_sides, [](int n, auto& v) { v.push_back(n); }));
  const Eigen::VectorXd& ref = model.reference();
  w.array("displacement",
          node_array<double>(3, num_nodes, tube_sides,
                             [&](int n, auto& v) {
                               const Eigen::Index f = model.node_dof(n);
                               for (int c = 0; c < 3; ++c) v.push_back(x[f + c] - ref[f + c]);
                             }),
          3);
  for (int d = 0; d < 2; ++d)
    w.array(d == 0 ? "g1" : "g2",
            node_array<double>(3, num_nodes, tube_sides,
                               [&](int n, auto& v) {
                                 const Eigen::Index f = model.node_dof(n) + 3 + 3 * d;
                                 for (int c = 0; c < 3; ++c) v.push_back(x[f + c]);
                               }),
            3);
  for (int k = 0; k < beam::kNumStrains; ++k)
    w.array(beam::strain_name(k), node_array<double>(1, num_nodes, tube_sides,
                                                     [&](int n, auto& v) { v.push_back(strains(k, n)); }));
  w.close("PointData");

  w.open("Points");
  w.array("Points", std::span<const double>(mesh.points.data(), static_cast<std::size_t>(mesh.points.size())),
          3);
  w.close("Points");
  w.open("Lines");
  w.index_array("connectivity", mesh.line_connectivity);
  w.index_array("offsets", mesh.line_offsets);
  w.close("Lines");
  w.open("Polys");
  w.index_array("connectivity", mesh.poly_connectivity);
  w.index_array("offsets", mesh.poly_offsets);
  w.close("Polys");
  w.finish();
}

void write_vtp(const std::filesystem::path& path, const model::Model& model, const Eigen::VectorXd& x,
               int tube_sides, std::optional<double> time, VtkEncoding encoding) {
  AtomicFile file(path);
  write_vtp(file.stream(), model, x, tube_sides, time, encoding);
  file.commit();
}

std::string xml_escape(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string pvd_document(const std::vector<PvdEntry>& entries) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                 "  <Collection>\n");
  for (const PvdEntry& e : entries)
    fmt::format_to(std::back_inserter(out),
                   "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                   xml_escape(e.file));
  fmt::format_to(std::back_inserter(out), "  </Collection>\n</VTKFile>\n");
  return fmt::to_string(out);
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries) {
  write_file_atomically(path, pvd_document(entries));
}

}  // namespace nodus::output
