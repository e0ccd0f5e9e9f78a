#pragma once
/// The tables of a contact geometry (contact::ContactGeometry), written as DIR/contact_final.csv (one row
/// per contact element) and DIR/zones_final.csv (one row per proximity zone) at the end of a run, and as
/// DIR/contact/contact_NNNNNN.csv at the VTK output steps (output.contact_csv). With contact forces the
/// element rows also carry the forces of the element's simulation::ContactState.
/// Conventions (docs/output.md): the normal points from the particle on beam I to the particle on beam J;
/// gap = <x_j - x_i, n>, negative when the surfaces overlap; the contact force on J is R_N n + T (on I its
/// opposite), T the friction force on J; zones and elements are numbered from 0 in the order of the geometry.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/model/model.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"

namespace nodus::output {

/// What a contact element does in a state: the `state` column of the contact tables, the `state` cell array
/// of the contact VTK files (the values are those of the VTK array).
enum class ContactStatus {
  open = 0,   ///< R_N = 0: the surfaces are apart, no force
  stick = 1,  ///< R_N > 0, friction below mu R_N (also every closed element without friction)
  slip = 2,   ///< R_N > 0, sliding with friction at mu R_N
};

/// The status of an element in `state`: open if R_N == 0, else slip or stick after ContactState::slip.
ContactStatus contact_status(const simulation::ContactState& state);

/// "open", "stick" or "slip".
std::string_view status_name(ContactStatus status);

/// Throws std::invalid_argument (one line starting with `context`) if `states` is given and does not hold
/// one state per contact element of `geometry`.
void check_contact_states(const contact::ContactGeometry& geometry,
                          const std::vector<simulation::ContactState>* states, std::string_view context);

/// Throws std::invalid_argument (one line starting with `context`) if a zone with contact elements lists
/// elements outside geometry.elements, or an element's zone index is not a zone of the geometry.
void check_contact_geometry(const contact::ContactGeometry& geometry, std::string_view context);

/// The smallest gap among the contact elements of `zone` [mm]; nullopt when it has none. `zone` must be a
/// zone of `geometry` that passed check_contact_geometry.
std::optional<double> smallest_gap(const contact::ContactGeometry& geometry,
                                   const contact::ProximityZone& zone);

/// The beam names of `model`, by beam index.
std::vector<std::string> beam_names(const model::Model& model);

/// One row of the contact element table as numbers: what contact_final_csv writes for one element, before
/// formatting. analysis::contact_table builds its in-memory columns from these rows too, so that the CSV
/// and the in-memory table cannot disagree (beyond the CSV's ten significant digits).
struct ContactRow {
  int zone = 0;                                            ///< zone index (from 0)
  int beam_i = 0;                                          ///< the zone's beam I (model index)
  int beam_j = 0;                                          ///< the zone's beam J (model index)
  double zeta = 0.0;                                       ///< relative abscissa on the zone, in [0, 1]
  double abscissa_i = 0.0;                                 ///< xi3 of the particle on I [mm]
  double abscissa_j = 0.0;                                 ///< xi3 of the particle on J [mm]
  Eigen::Vector2d transverse_i = Eigen::Vector2d::Zero();  ///< (xi1, xi2) of the particle on I [mm]
  Eigen::Vector2d transverse_j = Eigen::Vector2d::Zero();  ///< (xi1, xi2) of the particle on J [mm]
  Eigen::Vector3d position_i = Eigen::Vector3d::Zero();    ///< current position of the particle on I [mm]
  Eigen::Vector3d position_j = Eigen::Vector3d::Zero();    ///< current position of the particle on J [mm]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();       ///< unit normal, from I towards J [-]
  double gap = 0.0;                                        ///< <x_j - x_i, n> [mm]
  bool with_forces = false;                                ///< the four fields below are set
  double normal_force = 0.0;                               ///< R_N [N]
  double tangential_force = 0.0;                           ///< |T| [N]
  Eigen::Vector3d tangential = Eigen::Vector3d::Zero();    ///< friction force T on beam J [N]
  ContactStatus status = ContactStatus::open;              ///< contact_status of the element's state
};

/// Row `k` of the contact element table of `geometry`, with the forces of (*states)[k] when `states` is
/// given. `geometry` must have passed check_contact_geometry and `states` check_contact_states; k must be
/// an element index.
ContactRow contact_row(const contact::ContactGeometry& geometry, std::size_t k,
                       const std::vector<simulation::ContactState>* states);

/// The header line of the contact element table (no line end):
/// `zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,nx,ny,nz,gap`,
/// followed `with_forces` by `normal_force,tangential_force,tx,ty,tz,state`.
std::string contact_csv_header(bool with_forces);

/// The whole contact_final.csv text: contact_csv_header(states != nullptr), then one row per contact element
/// in order: its zone index, the names of the zone's beams I and J (`beam_names` by beam index), zeta [-],
/// the reference arc lengths xi3 of the two particles [mm], their section coordinates (xi1, xi2) [mm], their
/// current positions [mm], the unit normal [-] and the gap [mm]; with `states` (one per element, same order),
/// then the element's R_N [N], |T| [N], the friction force T on beam J [N] and its status_name; numbers with
/// ten significant digits. Throws std::invalid_argument on an inconsistent geometry (check_contact_geometry),
/// a beam index without a name or states that do not match the elements (check_contact_states).
std::string contact_final_csv(const contact::ContactGeometry& geometry,
                              const std::vector<std::string>& beam_names,
                              const std::vector<simulation::ContactState>* states = nullptr);

/// The whole zones_final.csv text: header `zone,beam_i,beam_j,a,b,c,d,contact_elements,min_gap`, then one row
/// per zone in order: its index, the names of beams I and J, the intervals [a, b] on I and [c, d] on J [mm],
/// its number of contact elements and the smallest gap among them [mm] (empty when it has none); numbers with
/// ten significant digits. Throws std::invalid_argument like contact_final_csv.
std::string zones_final_csv(const contact::ContactGeometry& geometry,
                            const std::vector<std::string>& beam_names);

/// Writes contact_final_csv(geometry, beam_names, states) to `path` (temporary file + rename).
void write_contact_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                         const std::vector<std::string>& beam_names,
                         const std::vector<simulation::ContactState>* states = nullptr);

/// Writes zones_final_csv(geometry, beam_names) to `path` (temporary file + rename).
void write_zones_final(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                       const std::vector<std::string>& beam_names);

}  // namespace nodus::output
