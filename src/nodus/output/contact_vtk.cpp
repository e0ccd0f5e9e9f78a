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

/// The values of one cell-data array, `value_of_cell(c, values)` appending those of cell c.
template <typename T, typename ValueOfCell>
std::vector<T> cell_array(const std::vector<Cell>& cells, int components, ValueOfCell value_of_cell) {
  std::vector<T> values;
  values.reserve(cells.size() * static_cast<std::size_t>(components));
  for (const Cell& c : cells) value_of_cell(c, values);
  return values;
}

void append(std::vector<double>& values, const contact::Vec3& v) {
  values.insert(values.end(), {v.x(), v.y(), v.z()});
}

}  // namespace

void write_contact_vtp(std::ostream& out, const contact::ContactGeometry& geometry,
                       std::optional<double> time, const std::vector<simulation::ContactState>* states,
                       VtkEncoding encoding) {
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

  std::vector<double> points;
  points.reserve(static_cast<std::size_t>(9 * num_elements));
  for (const contact::ContactElement& element : geometry.elements) append(points, element.intermediate);
  for (const contact::ContactElement& element : geometry.elements) {
    append(points, element.position_i);
    append(points, element.position_j);
  }

  vtk_xml::PolyDataWriter w(out, encoding, time,
                            {3 * num_elements, static_cast<std::int64_t>(cells.size()), 0});
  w.open("CellData Scalars=\"kind\" Vectors=\"normal\"");
  w.array("kind", cell_array<std::int32_t>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.kind); }));
  w.array("zone", cell_array<std::int32_t>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.zone); }));
  w.array("beam_i",
          cell_array<std::int32_t>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.beam_i); }));
  w.array("beam_j",
          cell_array<std::int32_t>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.beam_j); }));
  w.array("gap", cell_array<double>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.gap); }));
  w.array("normal", cell_array<double>(cells, 3, [](const Cell& c, auto& v) { append(v, c.normal); }), 3);
  if (states) {
    w.array("normal_force",
            cell_array<double>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.normal_force); }));
    w.array("force", cell_array<double>(cells, 3, [](const Cell& c, auto& v) { append(v, c.force); }), 3);
    w.array("tangential_force",
            cell_array<double>(cells, 3, [](const Cell& c, auto& v) { append(v, c.tangential); }), 3);
    w.array("state",
            cell_array<std::int32_t>(cells, 1, [](const Cell& c, auto& v) { v.push_back(c.state); }));
  }
  w.close("CellData");
  w.open("Points");
  w.array("Points", points, 3);
  w.close("Points");
  w.open("Lines");
  w.index_array("connectivity", connectivity);
  w.index_array("offsets", offsets);
  w.close("Lines");
  w.finish();
}

void write_contact_vtp(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       std::optional<double> time, const std::vector<simulation::ContactState>* states,
                       VtkEncoding encoding) {
  AtomicFile file(path);
  write_contact_vtp(file.stream(), geometry, time, states, encoding);
  file.commit();
}

}  // namespace nodus::output
