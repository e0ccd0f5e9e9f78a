#include "nodus/scenario/section_readers.hpp"

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/declared_keys.hpp"

#include <fmt/format.h>

namespace nodus::scenario {

void read_units(const Reader& reader, const MapView& top) {
  const auto units = top.get("units");
  if (!units) return;
  const MapView map(reader, *units);
  for (const MapView::Entry& entry : map.entries()) reader.choice(map.field_of(entry));
}

SolverSettings read_solver(const Reader& reader, const MapView& top) {
  SolverSettings solver;
  const auto field = top.get("solver");
  if (!field) return solver;
  const MapView map(reader, *field);
  read_keys(reader, map, SolverSettings::keys(), solver);
  if (const auto options = map.get("petsc_options")) {
    solver.petsc_options = reader.name(*options);
    if (!parallel::well_formed_options(solver.petsc_options)) reader.fail(*options);
  }
  return solver;
}

OutputSettings read_output(const Reader& reader, const MapView& top) {
  OutputSettings output;
  const auto field = top.get("output");
  if (!field) return output;
  const MapView map(reader, *field);
  read_keys(reader, map, OutputSettings::keys(), output);
  return output;
}

ContactSettings read_contact(const Reader& reader, const MapView& top, const NameTable& beam_names) {
  ContactSettings contact;
  const auto field = top.get("contact");
  if (!field) return contact;
  const MapView map(reader, *field);
  contact.enabled = true;
  read_keys(reader, map, ContactSettings::keys(), contact);
  // A list of beam names, each once (`where`: the key, for the message).
  const auto beam_list = [&](const Field& value, std::string_view where) {
    std::vector<int> beams;
    for (const Field& item : reader.list(value, true)) {
      const auto index = beam_names.find(item.node.IsScalar() ? item.node.Scalar() : std::string());
      if (!index) reader.fail(item, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
      if (std::find(beams.begin(), beams.end(), *index) != beams.end())
        reader.fail(item, fmt::format("each beam once in {}", where));
      beams.push_back(*index);
    }
    return beams;
  };
  if (const auto value = map.get("beams")) contact.beams = beam_list(*value, "contact.beams");
  if (const auto value = map.get("friction_pairs")) {
    for (const Field& item : reader.list(*value, false)) {
      const MapView entry(reader, item);
      FrictionPair pair;
      pair.beams = beam_list(entry.require("beams"), "contact.friction_pairs[].beams");
      if (const auto with = entry.get("with")) pair.with = beam_list(*with, "contact.friction_pairs[].with");
      pair.friction = reader.number(entry.require("friction"), [](double v) { return v >= 0.0; });
      contact.friction_pairs.push_back(std::move(pair));
    }
  }

  // Explicit lengths (> 0; 0 is auto) that must be ordered.
  const auto spacing = contact.test_point_spacing;
  if (spacing > 0.0 && contact.matching_length > 0.0 && contact.matching_length < spacing) {
    reader.fail(*map.get("matching_length"), kMatchingLengthExpected);
  }
  if (contact.proximity_distance > 0.0 && contact.separation_distance > 0.0 &&
      contact.separation_distance <= contact.proximity_distance) {
    reader.fail(*map.get("separation_distance"), kSeparationDistanceExpected);
  }
  return contact;
}

}  // namespace nodus::scenario
