#pragma once
/// The tables of a contact geometry (contact::ContactGeometry), written as DIR/contact_final.csv (one row
/// per contact element) and DIR/zones_final.csv (one row per proximity zone) at the end of a run.
/// Conventions (docs/output.md): the normal points from the particle on beam I to the particle on beam J;
/// gap = <x_j - x_i, n>, negative when the surfaces overlap; zones and elements are numbered from 0 in the
/// order of the geometry.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"

namespace nodus::output {

/// Throws std::invalid_argument (one line starting with `context`) if a zone with contact elements lists
/// elements outside geometry.elements, or an element's zone index is not a zone of the geometry.
void check_contact_geometry(const contact::ContactGeometry& geometry, std::string_view context);

/// The smallest gap among the contact elements of `zone` [mm]; nullopt when it has none. `zone` must be a
/// zone of `geometry` that passed check_contact_geometry.
std::optional<double> smallest_gap(const contact::ContactGeometry& geometry,
                                   const contact::ProximityZone& zone);

/// The beam names of `model`, by beam index.
std::vector<std::string> beam_names(const model::Model& model);

/// The whole contact_final.csv text: header
/// `zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,nx,ny,nz,gap`,
/// then one row per contact element in order: its zone index, the names of the zone's beams I and J
/// (`beam_names` by beam index), zeta [-], the reference arc lengths xi3 of the two particles [mm], their
/// section coordinates (xi1, xi2) [mm], their current positions [mm], the unit normal [-] and the gap [mm];
/// numbers with ten significant digits. Throws std::invalid_argument on an inconsistent geometry
/// (check_contact_geometry) or a beam index without a name.
std::string contact_final_csv(const contact::ContactGeometry& geometry,
                              const std::vector<std::string>& beam_names);

/// The whole zones_final.csv text: header `zone,beam_i,beam_j,a,b,c,d,contact_elements,min_gap`, then one row
/// per zone in order: its index, the names of beams I and J, the intervals [a, b] on I and [c, d] on J [mm],
/// its number of contact elements and the smallest gap among them [mm] (empty when it has none); numbers with
/// ten significant digits. Throws std::invalid_argument like contact_final_csv.
std::string zones_final_csv(const contact::ContactGeometry& geometry,
                            const std::vector<std::string>& beam_names);

/// Writes contact_final_csv(geometry, beam_names) to `path` (temporary file + rename).
void write_contact_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                         const std::vector<std::string>& beam_names);

/// Writes zones_final_csv(geometry, beam_names) to `path` (temporary file + rename).
void write_zones_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       const std::vector<std::string>& beam_names);

}  // namespace nodus::output
