#include "nodus/output/contact_vtk.hpp"

#include <cstdint>
#include <vector>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_table.hpp"
#include "nodus/output/vtk_xml.hpp"

namespace nodus::output {
namespace {

/// One line cell and the values of its cell data.
struct Cell {
  int kind = 0;  ///< 0 intermediate geometry, 1 contact element
  int zone = 0;
  int beam_i = 0;
  int beam_j = 0;
  double gap = 0.0;
  contact::Vec3 normal = contact::Vec3::Zero();
  double normal_force = 0.0;                         ///< R_N [N]
  contact::Vec3 force = contact::Vec3::Zero();       ///< R_N n + T, on beam J [N]
  contact::Vec3 tangential = contact::Vec3::Zero();  ///< T, on beam J [N]
  int state = 0;                                     ///< ContactStatus
};

/// A CellData array with one value per cell.
template <typename ValueOfCell>
void cell_array(vtk_xml::ChunkedWriter& w, const char* type, const char* name, int components,
                const std::vector<Cell>& cells, ValueOfCell value_of_cell) {
  vtk_xml::begin_data_array(w, type, name, components);
  for (const Cell& c : cells) {
    value_of_cell(c);
    w.print("\n");
  }
  vtk_xml::end_data_array(w);
}

}  // namespace

void write_contact_vtp(std::ostream& out, const contact::ContactGeometry& geometry,
                       std::optional<double> time, const std::vector<simulation::ContactState>* states) {
  check_contact_geometry(geometry, "contact VTK output");
  check_contact_states(geometry, states, "contact VTK output");
  const auto num_elements = static_cast<std::int64_t>(geometry.elements.size());

  std::vector<Cell> cells;
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets;
  for (std::size_t z = 0; z < geometry.zones.size(); ++z) {
    const contact::ProximityZone& zone = geometry.zones[z];
    if (zone.num_elements == 0) continue;
    for (int k = 0; k < zone.num_elements; ++k) connectivity.push_back(zone.first_element + k);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    Cell cell;
    cell.kind = 0;
    cell.zone = static_cast<int>(z);
    cell.beam_i = zone.beam_i;
    cell.beam_j = zone.beam_j;
    cell.gap = *smallest_gap(geometry, zone);
    cells.push_back(cell);
  }
  for (std::int64_t e = 0; e < num_elements; ++e) {
    const contact::ContactElement& element = geometry.elements[static_cast<std::size_t>(e)];
    const contact::ProximityZone& zone = geometry.zones[static_cast<std::size_t>(element.zone)];
    connectivity.push_back(num_elements + 2 * e);
    connectivity.push_back(num_elements + 2 * e + 1);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    Cell cell;
    cell.kind = 1;
    cell.zone = element.zone;
    cell.beam_i = zone.beam_i;
    cell.beam_j = zone.beam_j;
    cell.gap = element.gap;
    cell.normal = element.normal;
    if (states) {
      const simulation::ContactState& state = (*states)[static_cast<std::size_t>(e)];
      cell.normal_force = state.normal_reaction;
      cell.tangential = state.tangential;
      cell.force = state.normal_reaction * element.normal + state.tangential;
      cell.state = static_cast<int>(contact_status(state));
    }
    cells.push_back(cell);
  }

  vtk_xml::ChunkedWriter w(out);
  vtk_xml::begin_polydata(w, time, {3 * num_elements, static_cast<std::int64_t>(cells.size()), 0});

  w.print("      <CellData Scalars=\"kind\" Vectors=\"normal\">\n");
  cell_array(w, "Int32", "kind", 1, cells, [&](const Cell& c) { w.print("{}", c.kind); });
  cell_array(w, "Int32", "zone", 1, cells, [&](const Cell& c) { w.print("{}", c.zone); });
  cell_array(w, "Int32", "beam_i", 1, cells, [&](const Cell& c) { w.print("{}", c.beam_i); });
  cell_array(w, "Int32", "beam_j", 1, cells, [&](const Cell& c) { w.print("{}", c.beam_j); });
  cell_array(w, "Float64", "gap", 1, cells, [&](const Cell& c) { w.print("{:.12g}", c.gap); });
  auto print_vector = [&](const contact::Vec3& v) {
    w.print("{:.12g} {:.12g} {:.12g}", v.x(), v.y(), v.z());
  };
  cell_array(w, "Float64", "normal", 3, cells, [&](const Cell& c) { print_vector(c.normal); });
  if (states) {
    cell_array(w, "Float64", "normal_force", 1, cells,
               [&](const Cell& c) { w.print("{:.12g}", c.normal_force); });
    cell_array(w, "Float64", "force", 3, cells, [&](const Cell& c) { print_vector(c.force); });
    cell_array(w, "Float64", "tangential_force", 3, cells,
               [&](const Cell& c) { print_vector(c.tangential); });
    cell_array(w, "Int32", "state", 1, cells, [&](const Cell& c) { w.print("{}", c.state); });
  }
  w.print("      </CellData>\n");

  vtk_xml::points(w, 3 * num_elements, [&](std::int64_t p) -> const contact::Vec3& {
    if (p < num_elements) return geometry.elements[static_cast<std::size_t>(p)].intermediate;
    const std::int64_t q = p - num_elements;
    const contact::ContactElement& element = geometry.elements[static_cast<std::size_t>(q / 2)];
    return q % 2 == 0 ? element.position_i : element.position_j;
  });
  vtk_xml::cells(w, "Lines", connectivity, offsets);
  vtk_xml::end_polydata(w);
}

void write_contact_vtp(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       std::optional<double> time, const std::vector<simulation::ContactState>* states) {
  AtomicFile file(path);
  write_contact_vtp(file.stream(), geometry, time, states);
  file.commit();
}

}  // namespace nodus::output
