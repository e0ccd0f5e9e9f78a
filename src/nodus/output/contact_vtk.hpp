#pragma once
/// VTK XML picture of a contact geometry (contact::ContactGeometry): the intermediate geometry of every
/// proximity zone and the particle pair of every contact element, as line cells of one PolyData document.
///
/// Point layout, for N contact elements: first the intermediate point x_int of each element (point index =
/// element index), then the two particles of each element: position_i of element e is point N + 2 e,
/// position_j point N + 2 e + 1.
/// Cell layout: first one polyline per zone that has contact elements (zones in order), through the
/// intermediate points of its elements in order; then one two-point line per contact element (elements in
/// order), from position_i to position_j.

#include <filesystem>
#include <optional>
#include <ostream>

#include <vector>

#include "nodus/contact/detection.hpp"
#include "nodus/output/vtk_encoding.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::output {

/// Writes the VTK XML PolyData document of `geometry` in `encoding` (vtk_xml.hpp) (cells as above). Cell
/// data, one value per cell: `kind` (Int32: 0 intermediate geometry, 1 contact element), `zone` (Int32 zone
/// index), `beam_i`, `beam_j` (Int32 beam indices of the zone), `gap` [mm] (Float64: the element's gap; for a
/// polyline the smallest gap of its zone), `normal` (Float64, 3 components: the element's unit normal n from
/// I towards J; zeros for a polyline). With `states` (one simulation::ContactState per element, same order),
/// also the contact forces of each element, zero on the polylines: `normal_force` (Float64: R_N [N]), `force`
/// (Float64, 3: the contact force on beam J, R_N n + T [N]; on I it is the opposite), `tangential_force`
/// (Float64, 3: the friction force T on beam J [N]) and `state` (Int32: ContactStatus, 0 open, 1 stick,
/// 2 slip). `time` [s], if given, is stored as the field TimeValue. A geometry without zones gives a valid
/// document with no points and no cells. Throws std::invalid_argument (one line) if a zone's element range or
/// an element's zone index is out of range, or `states` does not hold one state per element.
void write_contact_vtp(std::ostream& out, const contact::ContactGeometry& geometry,
                       std::optional<double> time = std::nullopt,
                       const std::vector<simulation::ContactState>* states = nullptr,
                       VtkEncoding encoding = VtkEncoding::binary);

/// Same into file `path` (temporary file + rename). Throws std::runtime_error naming the path on I/O errors.
void write_contact_vtp(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       std::optional<double> time = std::nullopt,
                       const std::vector<simulation::ContactState>* states = nullptr,
                       VtkEncoding encoding = VtkEncoding::binary);

}  // namespace nodus::output
