#include "nodus/output/contact_table.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <iterator>
#include <stdexcept>

#include <fmt/format.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/csv.hpp"

namespace nodus::output {
namespace {

/// The CSV field of beam `index`, or std::invalid_argument.
std::string beam_field(const std::vector<std::string>& beam_names, int index, std::string_view context) {
  if (index < 0 || index >= static_cast<int>(beam_names.size()))
    throw std::invalid_argument(
        fmt::format("{}: beam index {}, the model has {} beams", context, index, beam_names.size()));
  return csv_field(beam_names[static_cast<std::size_t>(index)]);
}

}  // namespace

ContactStatus contact_status(const simulation::ContactState& state) {
  if (state.normal_reaction == 0.0) return ContactStatus::open;
  return state.slip ? ContactStatus::slip : ContactStatus::stick;
}

std::string_view status_name(ContactStatus status) {
  switch (status) {
    case ContactStatus::open:
      return "open";
    case ContactStatus::stick:
      return "stick";
    case ContactStatus::slip:
      return "slip";
  }
  return "?";
}

void check_contact_states(const contact::ContactGeometry& geometry,
                          const std::vector<simulation::ContactState>* states, std::string_view context) {
  if (states && states->size() != geometry.elements.size())
    throw std::invalid_argument(fmt::format("{}: {} contact states for {} contact elements", context,
                                            states->size(), geometry.elements.size()));
}

void check_contact_geometry(const contact::ContactGeometry& geometry, std::string_view context) {
  const auto num_elements = static_cast<std::int64_t>(geometry.elements.size());
  for (std::size_t z = 0; z < geometry.zones.size(); ++z) {
    const contact::ProximityZone& zone = geometry.zones[z];
    if (zone.num_elements < 0 ||
        (zone.num_elements > 0 &&
         (zone.first_element < 0 || std::int64_t{zone.first_element} + zone.num_elements > num_elements)))
      throw std::invalid_argument(
          fmt::format("{}: zone {} lists {} elements from element {}, the geometry has {}", context, z,
                      zone.num_elements, zone.first_element, num_elements));
  }
  for (std::size_t e = 0; e < geometry.elements.size(); ++e) {
    const int zone = geometry.elements[e].zone;
    if (zone < 0 || zone >= static_cast<int>(geometry.zones.size()))
      throw std::invalid_argument(fmt::format("{}: element {} belongs to zone {}, the geometry has {} zones",
                                              context, e, zone, geometry.zones.size()));
  }
}

std::optional<double> smallest_gap(const contact::ContactGeometry& geometry,
                                   const contact::ProximityZone& zone) {
  if (zone.num_elements <= 0) return std::nullopt;
  const auto first = geometry.elements.begin() + zone.first_element;
  return std::min_element(
             first, first + zone.num_elements,
             [](const contact::ContactElement& p, const contact::ContactElement& q) { return p.gap < q.gap; })
      ->gap;
}

std::vector<std::string> beam_names(const model::Model& model) {
  std::vector<std::string> names;
  names.reserve(model.beams().size());
  for (const beam::Beam& b : model.beams()) names.push_back(b.name());
  return names;
}

std::string contact_csv_header(bool with_forces) {
  std::string header =
      "zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,"
      "nx,ny,nz,gap";
  if (with_forces) header += ",normal_force,tangential_force,tx,ty,tz,state";
  return header;
}

ContactRow contact_row(const contact::ContactGeometry& geometry, std::size_t k,
                       const std::vector<simulation::ContactState>* states) {
  assert(k < geometry.elements.size());
  const contact::ContactElement& e = geometry.elements[k];
  const contact::ProximityZone& zone = geometry.zones[static_cast<std::size_t>(e.zone)];
  ContactRow row;
  row.zone = e.zone;
  row.beam_i = zone.beam_i;
  row.beam_j = zone.beam_j;
  row.zeta = e.zeta;
  row.abscissa_i = e.particle_i.abscissa;
  row.abscissa_j = e.particle_j.abscissa;
  row.transverse_i = e.particle_i.transverse;
  row.transverse_j = e.particle_j.transverse;
  row.position_i = e.position_i;
  row.position_j = e.position_j;
  row.normal = e.normal;
  row.gap = e.gap;
  if (states) {
    const simulation::ContactState& s = (*states)[k];
    row.with_forces = true;
    row.normal_force = s.normal_reaction;
    row.tangential_force = s.tangential.norm();
    row.tangential = s.tangential;
    row.status = contact_status(s);
  }
  return row;
}

std::string contact_final_csv(const contact::ContactGeometry& geometry,
                              const std::vector<std::string>& beam_names,
                              const std::vector<simulation::ContactState>* states) {
  constexpr std::string_view kContext = "contact element table";
  check_contact_geometry(geometry, kContext);
  check_contact_states(geometry, states, kContext);
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n", contact_csv_header(states != nullptr));
  for (std::size_t k = 0; k < geometry.elements.size(); ++k) {
    const ContactRow r = contact_row(geometry, k, states);
    fmt::format_to(std::back_inserter(out), "{},{},{},{:.10g},{:.10g},{:.10g}", r.zone,
                   beam_field(beam_names, r.beam_i, kContext), beam_field(beam_names, r.beam_j, kContext),
                   r.zeta, r.abscissa_i, r.abscissa_j);
    for (const auto& v : {r.transverse_i, r.transverse_j})
      fmt::format_to(std::back_inserter(out), ",{:.10g},{:.10g}", v.x(), v.y());
    for (const Eigen::Vector3d& v : {r.position_i, r.position_j, r.normal})
      fmt::format_to(std::back_inserter(out), ",{:.10g},{:.10g},{:.10g}", v.x(), v.y(), v.z());
    fmt::format_to(std::back_inserter(out), ",{:.10g}", r.gap);
    if (r.with_forces)
      fmt::format_to(std::back_inserter(out), ",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}", r.normal_force,
                     r.tangential_force, r.tangential.x(), r.tangential.y(), r.tangential.z(),
                     status_name(r.status));
    out.push_back('\n');
  }
  return fmt::to_string(out);
}

std::string zones_final_csv(const contact::ContactGeometry& geometry,
                            const std::vector<std::string>& beam_names) {
  constexpr std::string_view kContext = "zones_final.csv";
  check_contact_geometry(geometry, kContext);
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "zone,beam_i,beam_j,a,b,c,d,contact_elements,min_gap\n");
  for (std::size_t z = 0; z < geometry.zones.size(); ++z) {
    const contact::ProximityZone& zone = geometry.zones[z];
    fmt::format_to(std::back_inserter(out), "{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{},", z,
                   beam_field(beam_names, zone.beam_i, kContext),
                   beam_field(beam_names, zone.beam_j, kContext), zone.a, zone.b, zone.c, zone.d,
                   zone.num_elements);
    if (const std::optional<double> gap = smallest_gap(geometry, zone))
      fmt::format_to(std::back_inserter(out), "{:.10g}", *gap);
    out.push_back('\n');
  }
  return fmt::to_string(out);
}

void write_contact_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                         const std::vector<std::string>& beam_names,
                         const std::vector<simulation::ContactState>* states) {
  write_file_atomically(path, contact_final_csv(geometry, beam_names, states));
}

void write_zones_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       const std::vector<std::string>& beam_names) {
  write_file_atomically(path, zones_final_csv(geometry, beam_names));
}

}  // namespace nodus::output
