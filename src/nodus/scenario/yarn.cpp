#include "nodus/scenario/yarn.hpp"

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "nodus/model/yarn_layout.hpp"
#include "nodus/scenario/section_readers.hpp"

namespace nodus::scenario {

std::string yarn_beam_name(const std::string& yarn, int roving, int fibre) {
  return fmt::format("{}.r{}.f{}", yarn, roving + 1, fibre + 1);
}

std::string yarn_body_name(const std::string& yarn, int roving, bool at_end) {
  return fmt::format("{}.r{}.{}", yarn, roving + 1, at_end ? "end" : "start");
}

std::vector<BeamSpec> yarn_beams(const YarnSpec& yarn) {
  const model::YarnLayout layout = model::yarn_layout(
      yarn.roving_packing, yarn.rovings, yarn.fibres_per_roving, 2.0 * yarn.fibre_radius + yarn.gap());
  const Vec3 e1 = default_director(yarn.direction);
  const Vec3 e2 = yarn.direction.cross(e1);
  std::vector<BeamSpec> beams;
  for (int k = 0; k < yarn.rovings; ++k) {
    for (int j = 0; j < yarn.fibres_per_roving; ++j) {
      const model::Vec2& p = layout.fibres[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      BeamSpec beam;
      beam.name = yarn_beam_name(yarn.name, k, j);
      beam.material = yarn.material;
      beam.radius = yarn.fibre_radius;
      beam.length = yarn.length;
      beam.elements = yarn.elements;
      beam.start = yarn.start + p.x() * e1 + p.y() * e2;
      beam.direction = yarn.direction;
      beam.director1 = e1;
      beam.bending_factor = yarn.bending_factor;
      beams.push_back(beam);
    }
  }
  return beams;
}

std::vector<BodySpec> yarn_bodies(const YarnSpec& yarn, int first_beam) {
  std::vector<BodySpec> bodies;
  if (!yarn.bodies) return bodies;
  for (int k = 0; k < yarn.rovings; ++k) {
    for (const bool at_end : {false, true}) {
      BodySpec body;
      body.name = yarn_body_name(yarn.name, k, at_end);
      body.line = yarn.line;
      body.tie = yarn.tie;
      for (int j = 0; j < yarn.fibres_per_roving; ++j)
        body.sections.push_back(
            {first_beam + k * yarn.fibres_per_roving + j, at_end ? 2 * yarn.elements : 0});
      bodies.push_back(body);
    }
  }
  return bodies;
}

void append_yarn(Scenario& scenario, YarnSpec yarn) {
  yarn.first_beam = static_cast<int>(scenario.beams.size());
  yarn.first_body = static_cast<int>(scenario.bodies.size());
  for (BeamSpec& beam : yarn_beams(yarn)) scenario.beams.push_back(std::move(beam));
  for (BodySpec& body : yarn_bodies(yarn, yarn.first_beam)) scenario.bodies.push_back(std::move(body));
  scenario.yarns.push_back(std::move(yarn));
}

namespace {

std::vector<bool> made(std::size_t count, const std::vector<YarnSpec>& yarns, bool bodies) {
  std::vector<bool> out(count, false);
  for (const YarnSpec& yarn : yarns) {
    if (bodies && !yarn.bodies) continue;
    const int first = bodies ? yarn.first_body : yarn.first_beam;
    const int size = bodies ? 2 * yarn.rovings : yarn.rovings * yarn.fibres_per_roving;
    for (int i = first; i < first + size; ++i) {
      if (i >= 0 && static_cast<std::size_t>(i) < count) out[static_cast<std::size_t>(i)] = true;
    }
  }
  return out;
}

}  // namespace

std::vector<bool> beams_made_by_yarns(const Scenario& scenario) {
  return made(scenario.beams.size(), scenario.yarns, false);
}

std::vector<bool> bodies_made_by_yarns(const Scenario& scenario) {
  return made(scenario.bodies.size(), scenario.yarns, true);
}

}  // namespace nodus::scenario
