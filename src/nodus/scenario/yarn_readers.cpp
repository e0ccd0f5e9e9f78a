// The reader of `yarns` (docs/yarns.md): each yarn read, checked and expanded into beams and bodies.

#include <fmt/format.h>

#include "nodus/scenario/declared_keys.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yarn.hpp"

namespace nodus::scenario {

void read_yarns(const Reader& reader, const MapView& top, const NameTable& materials, NameTable& beam_names,
                Scenario& scenario) {
  const auto list = top.get("yarns");
  if (!list) return;
  const std::vector<Field> items = reader.list(*list, false);
  if (items.empty() && scenario.beams.empty()) reader.fail(*list, "a non-empty list (there are no beams)");
  NameTable yarn_names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const MapView map(reader, items[i]);
    YarnSpec yarn;
    yarn.line = map.line();
    const Field name = map.require("name");
    yarn.name = reader.name(name);
    yarn_names.add(reader, name, yarn.name, "yarns");

    read_keys(reader, map, YarnSpec::keys(), yarn);
    if (yarn.elements > kMaxElements) {
      const Field elements = map.require("elements");
      reader.fail(elements,
                  fmt::format("{}, at most {}", expected_text(scenario_key(elements.pattern)), kMaxElements));
    }
    if (static_cast<long long>(yarn.rovings) * yarn.fibres_per_roving > kMaxYarnFibres) {
      const Field fibres = map.require("fibres_per_roving");
      reader.fail(fibres,
                  fmt::format("{}, with rovings x fibres_per_roving at most {} (rovings: {})",
                              expected_text(scenario_key(fibres.pattern)), kMaxYarnFibres, yarn.rovings));
    }
    long long elements_before = 0;
    for (const BeamSpec& beam : scenario.beams) elements_before += beam.elements;
    if (elements_before + static_cast<long long>(yarn.rovings) * yarn.fibres_per_roving * yarn.elements >
        max_model_elements()) {
      const Field elements = map.require("elements");
      reader.fail(elements, model_elements_expected(elements.pattern, elements_before));
    }
    if (yarn.fibre_radius > yarn.length) {
      const Field radius = map.require("fibre_radius");
      reader.fail(radius, radius_expected(radius.pattern, yarn.length));
    }

    const Field material = map.require("material");
    const auto material_index = materials.find(reader.name(material));
    if (!material_index) {
      reader.fail(material, fmt::format("the name of a material ({})", name_list(materials.names)));
    }
    yarn.material = *material_index;

    if (const auto start = map.get("start")) yarn.start = reader.vec(*start);
    if (const auto direction = map.get("direction")) {
      const Vec3 value = reader.vec(*direction);
      const double norm = value.stableNorm();
      if (!(norm > 0.0)) reader.fail(*direction);
      yarn.direction = value / norm;
    }
    if (const auto clearance = map.get("clearance"))
      yarn.clearance = reader.number(*clearance, ranges::non_negative);

    // The fibres' names: unique among the beams of the file and of the yarns before.
    for (int k = 0; k < yarn.rovings; ++k) {
      for (int j = 0; j < yarn.fibres_per_roving; ++j) {
        const std::string beam = yarn_beam_name(yarn.name, k, j);
        if (const auto found = beam_names.index_and_line.find(beam);
            found != beam_names.index_and_line.end()) {
          reader.fail(name, fmt::format("a yarn name whose fibres NAME.rK.fJ are unique among beams ({} is "
                                        "already used at line {})",
                                        beam, found->second.second));
        }
        beam_names.add(reader, name, beam, "beams");
      }
    }
    append_yarn(scenario, yarn);
  }
}

}  // namespace nodus::scenario
