#include "nodus/scenario/section_readers.hpp"

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
  if (const auto value = map.get("linear_solver")) {
    solver.linear_solver =
        reader.choice(*value) == "umfpack" ? LinearSolverKind::umfpack : LinearSolverKind::cholmod;
  }
  const auto at_least = [](int minimum) { return [minimum](int v) { return v >= minimum; }; };
  const auto positive = [](double v) { return v > 0.0; };
  const auto non_negative = [](double v) { return v >= 0.0; };
  if (const auto value = map.get("max_newton_iterations")) {
    solver.max_newton_iterations = reader.integer(*value, at_least(1));
  }
  if (const auto value = map.get("residual_tolerance"))
    solver.residual_tolerance = reader.number(*value, positive);
  if (const auto value = map.get("increment_tolerance")) {
    solver.increment_tolerance = reader.number(*value, positive);
  }
  if (const auto value = map.get("max_cutbacks")) solver.max_cutbacks = reader.integer(*value, at_least(0));
  if (const auto value = map.get("easy_iterations"))
    solver.easy_iterations = reader.integer(*value, at_least(1));
  if (const auto value = map.get("line_search")) solver.line_search = reader.boolean(*value);
  if (const auto value = map.get("gauss_points")) {
    solver.gauss_points = reader.integer(*value, [](int v) { return v >= 1 && v <= 5; });
  }
  if (const auto value = map.get("fold_stiffness"))
    solver.fold_stiffness = reader.number(*value, non_negative);
  return solver;
}

OutputSettings read_output(const Reader& reader, const MapView& top) {
  OutputSettings output;
  const auto field = top.get("output");
  if (!field) return output;
  const MapView map(reader, *field);
  if (const auto value = map.get("vtk_every"))
    output.vtk_every = reader.integer(*value, [](int v) { return v >= 0; });
  if (const auto value = map.get("tube_sides")) {
    output.tube_sides = reader.integer(*value, [](int v) { return v >= 3; });
  }
  if (const auto value = map.get("progress_seconds")) {
    output.progress_seconds = reader.number(*value, [](double v) { return v >= 0.0; });
  }
  if (const auto value = map.get("contact_csv")) output.contact_csv = reader.boolean(*value);
  if (const auto value = map.get("checkpoint_every"))
    output.checkpoint_every = reader.integer(*value, [](int v) { return v >= 0; });
  return output;
}

ContactSettings read_contact(const Reader& reader, const MapView& top, const NameTable& beam_names) {
  ContactSettings contact;
  const auto field = top.get("contact");
  if (!field) return contact;
  const MapView map(reader, *field);
  contact.enabled = true;
  if (const auto value = map.get("enabled")) contact.enabled = reader.boolean(*value);
  if (const auto value = map.get("self_contact")) contact.self_contact = reader.boolean(*value);
  if (const auto value = map.get("beams")) {
    for (const Field& item : reader.list(*value, true)) {
      const auto index = beam_names.find(item.node.IsScalar() ? item.node.Scalar() : std::string());
      if (!index) reader.fail(item, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
      if (std::find(contact.beams.begin(), contact.beams.end(), *index) != contact.beams.end()) {
        reader.fail(item, "each beam once in contact.beams");
      }
      contact.beams.push_back(*index);
    }
  }

  // A length (or the penalty) is > 0, or auto (absent, or the word auto), which leaves it at 0. Returns the
  // field of an explicit value.
  const auto length = [&](std::string_view key, double& out) -> std::optional<Field> {
    const auto value = map.get(key);
    if (!value || (is_plain_scalar(value->node) && value->node.Scalar() == "auto")) return std::nullopt;
    out = reader.number(*value, [](double v) { return v > 0.0; });
    return value;
  };
  const auto proximity = length("proximity_distance", contact.proximity_distance);
  const auto separation = length("separation_distance", contact.separation_distance);
  const auto spacing = length("test_point_spacing", contact.test_point_spacing);
  const auto matching = length("matching_length", contact.matching_length);
  length("element_spacing", contact.element_spacing);
  if (spacing && matching && contact.matching_length < contact.test_point_spacing) {
    reader.fail(*matching, ">= test_point_spacing (successive matching intervals must overlap)");
  }
  if (proximity && separation && contact.separation_distance <= contact.proximity_distance) {
    reader.fail(*separation, "> proximity_distance (neighbouring parts of a beam would be paired)");
  }

  // Contact mechanics (Sect. 5-6).
  if (const auto value = map.get("forces")) contact.forces = reader.boolean(*value);
  length("penalty", contact.penalty);
  length("max_penetration", contact.max_penetration);
  length("regularization", contact.regularization);
  if (const auto value = map.get("friction")) {
    contact.friction = reader.number(*value, [](double v) { return v >= 0.0; });
  }
  length("max_reversible_slip", contact.max_reversible_slip);
  if (const auto value = map.get("friction_tangent")) {
    contact.friction_tangent =
        reader.choice(*value) == "varying" ? FrictionTangent::varying : FrictionTangent::frozen;
  }
  if (const auto value = map.get("particles")) contact.facing_particles = reader.choice(*value) == "facing";
  const auto at_least_one = [](int v) { return v >= 1; };
  if (const auto value = map.get("max_detections")) {
    contact.max_detections = reader.integer(*value, at_least_one);
  }
  if (const auto value = map.get("max_normal_iterations")) {
    contact.max_normal_iterations = reader.integer(*value, at_least_one);
  }
  if (const auto value = map.get("normal_tolerance")) {
    contact.normal_tolerance = reader.number(*value, [](double v) { return v > 0.0; });
  }
  return contact;
}

}  // namespace nodus::scenario
