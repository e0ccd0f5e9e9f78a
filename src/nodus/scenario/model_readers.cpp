#include "nodus/scenario/section_readers.hpp"

#include "nodus/contact/detection_parameters.hpp"
#include "nodus/scenario/declared_keys.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace nodus::scenario {

std::string_view type_name(ConditionType type) {
  switch (type) {
    case ConditionType::clamp:
      return "clamp";
    case ConditionType::motion:
      return "motion";
    case ConditionType::rigid:
      return "rigid";
    case ConditionType::load:
      return "load";
    case ConditionType::bind:
      return "bind";
  }
  return "?";
}

std::string radius_expected(std::string_view pattern, double length) {
  return fmt::format("{}, at most the fibre's length ({})", expected_text(scenario_key(pattern)),
                     format_number(length));
}

long long max_model_elements() {
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return kMaxElements;
  const double bytes = static_cast<double>(pages) * static_cast<double>(page_size);
  return std::min<long long>(kMaxElements, static_cast<long long>(bytes / kBytesPerElement));
}

std::string model_elements_expected(std::string_view pattern, long long before) {
  const long long most = max_model_elements();
  const double gigabytes = static_cast<double>(most) * kBytesPerElement / 1e9;
  return fmt::format(
      "{}, with at most {} elements in the model on this machine (about {:.0f} kB an element to "
      "build, {:.1f} GB of memory here; {} before this one)",
      expected_text(scenario_key(pattern)), most, kBytesPerElement / 1e3, gigabytes, before);
}

TestPoints contact_test_points(const Scenario& s) {
  const ContactSettings& c = s.contact;
  if (!c.enabled) return {};
  const auto in_contact = [&c](int b) {
    return c.beams.empty() || std::find(c.beams.begin(), c.beams.end(), b) != c.beams.end();
  };
  double radius = 0.0;
  for (int b = 0; b < static_cast<int>(s.beams.size()); ++b)
    if (in_contact(b)) radius = std::max(radius, s.beams[static_cast<std::size_t>(b)].radius);
  contact::DetectionParameters given;
  given.proximity_distance = c.proximity_distance;
  given.test_point_spacing = c.test_point_spacing;
  given.self_contact = false;  // only the spacing is wanted here: no checks of the other lengths
  const double spacing = contact::resolve_parameters(given, radius).test_point_spacing;
  TestPoints points{spacing, 0.0};
  for (int b = 0; b < static_cast<int>(s.beams.size()); ++b)
    if (in_contact(b)) points.count += s.beams[static_cast<std::size_t>(b)].length / spacing + 2.0;
  return points;
}

std::string test_points_expected(const TestPoints& points) {
  return fmt::format(
      "{}, with at most {} test points along the contact beams on this machine (their lengths over the "
      "spacing, {:.4g} mm here: {:.3g} points)",
      expected_text(scenario_key("contact.test_point_spacing")), max_test_points(), points.spacing,
      points.count);
}

/// The unit vector orthogonal to `direction` (unit) made from the coordinate axis least parallel to it.
Vec3 default_director(const Vec3& direction) {
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(direction[i]) < std::abs(direction[axis])) axis = i;
  }
  Vec3 director = Vec3::Unit(axis);
  director -= director.dot(direction) * direction;
  return director.normalized();
}

/// |sin| of the angle between two nonzero vectors.
double sin_angle(const Vec3& a, const Vec3& b) {
  return a.cross(b).norm() / (a.norm() * b.norm());
}

std::vector<Material> read_materials(const Reader& reader, const MapView& top, NameTable& names) {
  std::vector<Material> materials;
  for (const Field& item : reader.list(top.require("materials"), true)) {
    const MapView map(reader, item);
    Material material;
    const Field name = map.require("name");
    material.name = reader.name(name);
    names.add(reader, name, material.name, "materials");
    read_keys(reader, map, Material::keys(), material);
    materials.push_back(material);
  }
  return materials;
}

std::vector<BeamSpec> read_beams(const Reader& reader, const MapView& top, const NameTable& materials,
                                 NameTable& names) {
  std::vector<BeamSpec> beams;
  // With yarns, beams is optional and may be empty (read_yarns then wants at least one yarn).
  const bool yarns = top.get("yarns").has_value();
  const auto list = top.get("beams");
  if (!list && yarns) return beams;
  long long elements_before = 0;
  for (const Field& item : reader.list(list ? *list : top.require("beams"), !yarns)) {
    const MapView map(reader, item);
    BeamSpec beam;
    const Field name = map.require("name");
    beam.name = reader.name(name);
    names.add(reader, name, beam.name, "beams");

    const Field material = map.require("material");
    const auto material_index = materials.find(reader.name(material));
    if (!material_index) {
      reader.fail(material, fmt::format("the name of a material ({})", name_list(materials.names)));
    }
    beam.material = *material_index;

    read_keys(reader, map, BeamSpec::keys(), beam);
    const Field elements = map.require("elements");
    if (beam.elements > kMaxElements) {
      reader.fail(elements,
                  fmt::format("{}, at most {}", expected_text(scenario_key(elements.pattern)), kMaxElements));
    }
    if (elements_before + beam.elements > max_model_elements())
      reader.fail(elements, model_elements_expected(elements.pattern, elements_before));
    elements_before += beam.elements;
    if (beam.radius > beam.length) {
      const Field radius = map.require("radius");
      reader.fail(radius, radius_expected(radius.pattern, beam.length));
    }
    if (const auto start = map.get("start")) beam.start = reader.vec(*start);

    if (const auto direction = map.get("direction")) {
      const Vec3 value = reader.vec(*direction);
      const double norm = value.stableNorm();
      if (!(norm > 0.0)) reader.fail(*direction);
      beam.direction = value / norm;
    }
    if (const auto director1 = map.get("director1")) {
      Vec3 value = reader.vec(*director1);
      const double norm = value.stableNorm();
      if (!(norm > 0.0) || sin_angle(beam.direction, value / norm) < kDirectorParallelTolerance) {
        reader.fail(*director1);
      }
      value /= norm;
      value -= value.dot(beam.direction) * beam.direction;
      beam.director1 = value.normalized();
    } else {
      beam.director1 = default_director(beam.direction);
    }
    beams.push_back(beam);
  }
  return beams;
}

std::vector<BodySpec> read_bodies(const Reader& reader, const MapView& top, const NameTable& beam_names,
                                  const std::vector<BeamSpec>& beams, NameTable& names) {
  std::vector<BodySpec> bodies;
  const auto list = top.get("bodies");
  if (!list) return bodies;
  for (const Field& item : reader.list(*list, false)) {
    const MapView map(reader, item);
    BodySpec body;
    body.line = map.line();
    const Field name = map.require("name");
    body.name = reader.name(name);
    names.add(reader, name, body.name, "bodies");
    read_keys(reader, map, BodySpec::keys(), body);
    const Field at = map.require("at");
    const std::string at_text = is_plain_scalar(at.node) ? at.node.Scalar() : std::string();
    if (at_text != "start" && at_text != "end") reader.fail(at, "one of start | end");
    std::vector<int> seen;
    for (const Field& beam : reader.list(map.require("beams"), true)) {
      const auto index = beam_names.find(beam.node.IsScalar() ? beam.node.Scalar() : std::string());
      if (!index) reader.fail(beam, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
      if (std::find(seen.begin(), seen.end(), *index) != seen.end())
        reader.fail(beam, "each beam once in beams");
      seen.push_back(*index);
      body.sections.push_back(
          {*index, at_text == "start" ? 0 : 2 * beams[static_cast<std::size_t>(*index)].elements});
    }
    bodies.push_back(body);
  }
  return bodies;
}

namespace {

/// The six unknowns of a rigid body selected by a list of dof items (BodyDofMask).
BodyDofMask read_body_dofs(const Reader& reader, const Field& field) {
  BodyDofMask mask{};
  constexpr std::string_view kNames[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (const Field& item : reader.list(field, true)) {
    const std::string text = is_plain_scalar(item.node) ? item.node.Scalar() : std::string();
    if (text == "all") {
      mask.fill(true);
    } else if (text == "position") {
      mask[kBodyX] = mask[kBodyY] = mask[kBodyZ] = true;
    } else if (text == "rotation") {
      mask[kBodyRx] = mask[kBodyRy] = mask[kBodyRz] = true;
    } else {
      const auto* found = std::find(std::begin(kNames), std::end(kNames), text);
      if (found == std::end(kNames))
        reader.fail(item, "one of all | position | rotation | x | y | z | rx | ry | rz (on bodies)");
      mask[static_cast<std::size_t>(found - std::begin(kNames))] = true;
    }
  }
  return mask;
}

/// `force` and `moment` of condition number `index` (load conditions only).
void read_load_values(const Reader& reader, const MapView& map, int index, MomentAxes& moment_axes,
                      ConditionSpec& condition) {
  for (const char* key : {"force", "moment"}) {
    const auto value = map.get(key);
    if (!value) continue;
    if (condition.type != ConditionType::load) {
      reader.fail(*value, fmt::format("no {} on a {} condition ({} is for load conditions only)", key,
                                      type_name(condition.type), key));
    }
    if (std::string_view(key) == "force") {
      condition.force = reader.vec(*value);
    } else {
      condition.moment = reader.vec(*value);
      moment_axes.check(reader, index, condition.moment, *value);
    }
  }
}

/// The nine dofs selected by a list of dof items.
DofMask read_dofs(const Reader& reader, const Field& field) {
  DofMask mask{};
  const std::vector<Field> items = reader.list(field, true);
  const std::string expected =
      "one of all | position | directors | x | y | z | g1x | g1y | g1z | g2x | g2y | g2z";
  for (const Field& item : items) {
    const std::string text = is_plain_scalar(item.node) ? item.node.Scalar() : std::string();
    if (text == "all") {
      mask.fill(true);
    } else if (text == "position") {
      mask[kX] = mask[kY] = mask[kZ] = true;
    } else if (text == "directors") {
      for (int dof = kG1x; dof <= kG2z; ++dof) mask[dof] = true;
    } else {
      const auto* found = std::find(std::begin(kDofNames), std::end(kDofNames), text);
      if (found == std::end(kDofNames)) reader.fail(item, expected);
      mask[found - std::begin(kDofNames)] = true;
    }
  }
  return mask;
}

}  // namespace

std::vector<ConditionSpec> read_conditions(const Reader& reader, const MapView& top,
                                           const NameTable& beam_names, const std::vector<BeamSpec>& beams,
                                           const NameTable& body_names, NameTable& names,
                                           MomentAxes& moment_axes) {
  std::vector<ConditionSpec> conditions;
  const auto list = top.get("conditions");
  if (!list) return conditions;
  for (const Field& item : reader.list(*list, false)) {
    const MapView map(reader, item);
    ConditionSpec condition;
    condition.line = map.line();
    const Field name = map.require("name");
    condition.name = reader.name(name);
    names.add(reader, name, condition.name, "conditions");
    if (const auto body = body_names.find(condition.name))
      reader.fail(name, fmt::format("a name unique among conditions and bodies (already used at line {})",
                                    body_names.index_and_line.at(condition.name).second));

    const std::span<const Key<ConditionSpec>> keys = ConditionSpec::keys();
    read_key(reader, map.require("type"), declared(keys, "conditions[].type"), condition);

    if (const auto bodies = map.get("bodies")) {
      if (condition.type == ConditionType::rigid)
        reader.fail(
            *bodies,
            "no bodies on a rigid condition (bodies are for clamp, motion, load and bind conditions)");
      for (const char* key : {"beam", "at"})
        if (const auto value = map.get(key))
          reader.fail(*value, fmt::format("no {} next to bodies (the condition acts on the bodies)", key));
      const std::vector<Field> items = reader.list(*bodies, true);
      for (const Field& body : items) {
        const auto index = body_names.find(body.node.IsScalar() ? body.node.Scalar() : std::string());
        if (!index) reader.fail(body, fmt::format("the name of a body ({})", name_list(body_names.names)));
        if (std::find(condition.bodies.begin(), condition.bodies.end(), *index) != condition.bodies.end())
          reader.fail(body, "each body once in bodies");
        if (condition.type == ConditionType::load && !condition.bodies.empty())
          reader.fail(body, "one body for a load condition");
        condition.bodies.push_back(*index);
      }
      if (condition.type == ConditionType::bind && condition.bodies.size() < 2)
        reader.fail(*bodies, kBindBodiesExpected);
      const auto pivot = map.get("pivot");
      if (pivot) {
        if (condition.type != ConditionType::motion)
          reader.fail(*pivot,
                      fmt::format("no pivot on a {} condition (pivot is for motion and rigid conditions)",
                                  type_name(condition.type)));
        condition.pivot = reader.vec(*pivot);
      }
      const auto dofs = map.get("dofs");
      if (condition.type == ConditionType::load) {
        if (dofs)
          reader.fail(*dofs, "no dofs on a load condition (dofs are for clamp and motion conditions)");
      } else if (condition.type == ConditionType::bind) {
        condition.body_dofs = dofs ? read_body_dofs(reader, *dofs) : BodyDofMask{true, true, true};
        if (dofs &&
            (condition.body_dofs[kBodyRx] || condition.body_dofs[kBodyRy] || condition.body_dofs[kBodyRz]))
          reader.fail(*dofs, kBindDofsExpected);
      } else {
        condition.body_dofs =
            dofs ? read_body_dofs(reader, *dofs) : BodyDofMask{true, true, true, true, true, true};
      }
      if (const auto active = map.get("active"))
        read_key(reader, *active, declared(keys, "conditions[].active"), condition);
      read_load_values(reader, map, static_cast<int>(conditions.size()), moment_axes, condition);
      conditions.push_back(condition);
      continue;
    }

    if (condition.type == ConditionType::bind) reader.fail(map.require("type"), kBindOnBodiesExpected);
    const Field beam = map.require("beam");
    const auto beam_index = beam_names.find(reader.name(beam));
    if (!beam_index) reader.fail(beam, fmt::format("the name of a beam ({})", name_list(beam_names.names)));
    condition.beam = *beam_index;

    const auto pivot = map.get("pivot");
    if (pivot) {
      if (condition.type != ConditionType::motion && condition.type != ConditionType::rigid)
        reader.fail(*pivot,
                    fmt::format("no pivot on a {} condition (pivot is for motion and rigid conditions)",
                                type_name(condition.type)));
      condition.pivot = reader.vec(*pivot);
    }
    if (condition.type == ConditionType::rigid) {  // the whole beam, all dofs
      for (const char* key : {"at", "dofs", "force", "moment"})
        if (const auto value = map.get(key))
          reader.fail(*value,
                      fmt::format("no {} on a rigid condition (it moves every node of its beam)", key));
      condition.dofs.fill(true);
      if (const auto active = map.get("active"))
        read_key(reader, *active, declared(keys, "conditions[].active"), condition);
      conditions.push_back(condition);
      continue;
    }

    const Field at = map.require("at");
    const int last_node = 2 * beams[condition.beam].elements;
    const std::string at_text = is_plain_scalar(at.node) ? at.node.Scalar() : std::string();
    if (at_text == "start") {
      condition.node = 0;
    } else if (at_text == "end") {
      condition.node = last_node;
    } else {
      const auto node = parse_integer(at.node);
      if (!node || *node < 0 || *node > last_node) {
        reader.fail(at, fmt::format("one of start | end | an integer in [0, {}] (beam {}: elements {})",
                                    last_node, beams[condition.beam].name, beams[condition.beam].elements));
      }
      condition.node = static_cast<int>(*node);
    }

    const auto dofs = map.get("dofs");
    if (condition.type == ConditionType::load) {
      if (dofs) reader.fail(*dofs, "no dofs on a load condition (dofs are for clamp and motion conditions)");
    } else {
      condition.dofs =
          dofs ? read_dofs(reader, *dofs) : DofMask{true, true, true, true, true, true, true, true, true};
    }

    if (const auto active = map.get("active"))
      read_key(reader, *active, declared(keys, "conditions[].active"), condition);

    read_load_values(reader, map, static_cast<int>(conditions.size()), moment_axes, condition);
    conditions.push_back(condition);
  }
  return conditions;
}

}  // namespace nodus::scenario
