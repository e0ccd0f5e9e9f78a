#include "nodus/scenario/validate.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "nodus/scenario/declared_keys.hpp"
#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/section_readers.hpp"
#include "nodus/scenario/yarn.hpp"

namespace nodus::scenario {

namespace {

/// Unit vectors must have a length within this of 1, and director1 be orthogonal to direction within it.
constexpr double kUnitTolerance = 1e-9;

/// Throws "FILE: KEY: expected WHAT, got VALUE".
class Checker {
 public:
  explicit Checker(const Scenario& scenario) : scenario_(scenario) {}

  [[noreturn]] void fail(std::string_view path, std::string_view expected, std::string_view got) const {
    throw ScenarioError(fmt::format("{}: {}: expected {}, got {}", scenario_.path, path, expected, got));
  }
  /// Fails with the expectation of the key table for `pattern`.
  [[noreturn]] void fail_key(std::string_view path, std::string_view pattern, std::string_view got) const {
    fail(path, expected_text(scenario_key(pattern)), got);
  }

  /// Every declared scalar key of `keys` in `owner`; `prefix` replaces the pattern prefix `pattern`
  /// ("beams[2]" for "beams[]").
  template <class Owner>
  void keys(std::span<const Key<Owner>> keys, const Owner& owner, std::string_view pattern,
            std::string_view prefix) const {
    for (const Key<Owner>& key : keys) {
      if (!key.scalar()) continue;
      if (const auto got = inadmissible(key, owner)) {
        fail(std::string(prefix) + std::string(key.path.substr(pattern.size())),
             expected_text(scenario_key(key.path)), *got);
      }
    }
  }

  /// An index into a list of `count` items named `what`.
  void index(std::string_view path, int value, std::size_t count, std::string_view what) const {
    if (value < 0 || static_cast<std::size_t>(value) >= count) {
      fail(path,
           count == 0 ? fmt::format("an index into {} (none defined)", what)
                      : fmt::format("an index into {} (0 .. {})", what, count - 1),
           std::to_string(value));
    }
  }

  /// Names non-empty and unique among `names` (their paths `path(i)`).
  template <class PathOf>
  void names(const std::vector<std::string>& names, PathOf path, std::string_view pattern,
             std::string_view what) const {
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i].empty()) fail_key(path(i), pattern, "\"\"");
      if (const auto found = seen.find(names[i]); found != seen.end()) {
        fail(path(i), fmt::format("a name unique among {} (already used by {})", what, path(found->second)),
             names[i]);
      }
      seen.emplace(names[i], i);
    }
  }

 private:
  const Scenario& scenario_;
};

template <class Item>
std::vector<std::string> names_of(const std::vector<Item>& items) {
  std::vector<std::string> out;
  for (const Item& item : items) out.push_back(item.name);
  return out;
}

/// Checks that every nonzero moment of each load keeps the axis of the first nonzero one.
class AxisCheck {
 public:
  explicit AxisCheck(const Checker& check) : check_(check) {}
  void moment(int condition, const Vec3& moment, const std::string& path) {
    if (moment.squaredNorm() == 0.0) return;
    const auto found = first_.find(condition);
    if (found == first_.end()) {
      first_.emplace(condition, std::pair{moment, path});
      return;
    }
    if (sin_angle(found->second.first, moment) >= kMomentAxisTolerance) {
      check_.fail(path,
                  fmt::format("a moment parallel to {} given at {} (moment axis must stay fixed)",
                              format_vec(found->second.first), found->second.second),
                  format_vec(moment));
    }
  }
  std::optional<Vec3> axis(int condition) const {
    const auto found = first_.find(condition);
    if (found == first_.end()) return std::nullopt;
    return found->second.first.normalized();
  }

 private:
  const Checker& check_;
  std::map<int, std::pair<Vec3, std::string>> first_;
};

void check_beams(const Checker& check, const Scenario& s) {
  check.names(
      names_of(s.materials), [](std::size_t i) { return fmt::format("materials[{}].name", i); },
      "materials[].name", "materials");
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    check.keys(Material::keys(), s.materials[m], "materials[]", fmt::format("materials[{}]", m));
  }
  check.names(
      names_of(s.beams), [](std::size_t i) { return fmt::format("beams[{}].name", i); }, "beams[].name",
      "beams");
  long long elements_before = 0;
  for (std::size_t b = 0; b < s.beams.size(); ++b) {
    const BeamSpec& beam = s.beams[b];
    const std::string at = fmt::format("beams[{}]", b);
    check.index(at + ".material", beam.material, s.materials.size(), "materials");
    check.keys(BeamSpec::keys(), beam, "beams[]", at);
    if (beam.elements > kMaxElements) {
      check.fail(at + ".elements",
                 fmt::format("{}, at most {}", expected_text(scenario_key("beams[].elements")), kMaxElements),
                 std::to_string(beam.elements));
    }
    if (elements_before + beam.elements > max_model_elements())
      check.fail(at + ".elements", model_elements_expected("beams[].elements", elements_before),
                 std::to_string(beam.elements));
    elements_before += beam.elements;
    if (beam.radius > beam.length)
      check.fail(at + ".radius", radius_expected("beams[].radius", beam.length), format_number(beam.radius));
    if (!beam.start.allFinite()) check.fail_key(at + ".start", "beams[].start", format_vec(beam.start));
    if (!(beam.direction.stableNorm() > 0.0) || !beam.direction.allFinite())
      check.fail_key(at + ".direction", "beams[].direction", format_vec(beam.direction));
    if (std::abs(beam.direction.norm() - 1.0) > kUnitTolerance)
      check.fail(at + ".direction", "a list of 3 numbers of length 1 (the reader normalises it)",
                 format_vec(beam.direction));
    if (!beam.director1.allFinite() || !(beam.director1.stableNorm() > 0.0) ||
        sin_angle(beam.direction, beam.director1) < kDirectorParallelTolerance)
      check.fail_key(at + ".director1", "beams[].director1", format_vec(beam.director1));
    if (std::abs(beam.director1.norm() - 1.0) > kUnitTolerance ||
        std::abs(beam.director1.dot(beam.direction)) > kUnitTolerance)
      check.fail(at + ".director1",
                 "a list of 3 numbers of length 1 orthogonal to direction (the reader makes it so)",
                 format_vec(beam.director1));
  }
}

void check_bodies(const Checker& check, const Scenario& s) {
  check.names(
      names_of(s.bodies), [](std::size_t i) { return fmt::format("bodies[{}].name", i); }, "bodies[].name",
      "bodies");
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const BodySpec& body = s.bodies[b];
    const std::string at = fmt::format("bodies[{}]", b);
    check.keys(BodySpec::keys(), body, "bodies[]", at);
    if (body.sections.empty()) check.fail_key(at + ".beams", "bodies[].beams", "[]");
    for (std::size_t i = 0; i < body.sections.size(); ++i) {
      const SectionRef& section = body.sections[i];
      const std::string path = fmt::format("{}.beams[{}]", at, i);
      check.index(path, section.beam, s.beams.size(), "beams");
      const int last = 2 * s.beams[static_cast<std::size_t>(section.beam)].elements;
      if (section.node != 0 && section.node != last)
        check.fail(at + ".at", "one of start | end (node 0 or 2 elements of each beam)",
                   std::to_string(section.node));
      for (std::size_t j = 0; j < i; ++j)
        if (body.sections[j].beam == section.beam && body.sections[j].node == section.node)
          check.fail(path, "each section once", s.beams[static_cast<std::size_t>(section.beam)].name);
    }
    for (const ConditionSpec& condition : s.conditions)
      if (condition.name == body.name)
        check.fail(at + ".name", "a name unique among conditions and bodies", body.name);
  }
}

/// The yarns: their keys, and their fibres and bodies where append_yarn put them, as it makes them.
void check_yarns(const Checker& check, const Scenario& s) {
  check.names(
      names_of(s.yarns), [](std::size_t i) { return fmt::format("yarns[{}].name", i); }, "yarns[].name",
      "yarns");
  for (std::size_t y = 0; y < s.yarns.size(); ++y) {
    const YarnSpec& yarn = s.yarns[y];
    const std::string at = fmt::format("yarns[{}]", y);
    check.keys(YarnSpec::keys(), yarn, "yarns[]", at);
    check.index(at + ".material", yarn.material, s.materials.size(), "materials");
    if (yarn.elements > kMaxElements) {
      check.fail(at + ".elements",
                 fmt::format("{}, at most {}", expected_text(scenario_key("yarns[].elements")), kMaxElements),
                 std::to_string(yarn.elements));
    }
    if (static_cast<long long>(yarn.rovings) * yarn.fibres_per_roving > kMaxYarnFibres) {
      check.fail(
          at + ".fibres_per_roving",
          fmt::format("{}, with rovings x fibres_per_roving at most {} (rovings: {})",
                      expected_text(scenario_key("yarns[].fibres_per_roving")), kMaxYarnFibres, yarn.rovings),
          std::to_string(yarn.fibres_per_roving));
    }
    if (yarn.fibre_radius > yarn.length)
      check.fail(at + ".fibre_radius", radius_expected("yarns[].fibre_radius", yarn.length),
                 format_number(yarn.fibre_radius));
    if (!yarn.start.allFinite()) check.fail_key(at + ".start", "yarns[].start", format_vec(yarn.start));
    if (!yarn.direction.allFinite() || std::abs(yarn.direction.norm() - 1.0) > kUnitTolerance)
      check.fail(at + ".direction", "a list of 3 numbers of length 1 (the reader normalises it)",
                 format_vec(yarn.direction));
    if (yarn.clearance &&
        !(std::isfinite(*yarn.clearance) && representable(*yarn.clearance) && *yarn.clearance >= 0.0))
      check.fail_key(at + ".clearance", "yarns[].clearance", format_number(*yarn.clearance));

    const std::vector<BeamSpec> beams = yarn_beams(yarn);
    const auto beam_at = [&](std::size_t i) { return static_cast<std::size_t>(yarn.first_beam) + i; };
    if (yarn.first_beam < 0 || beam_at(beams.size()) > s.beams.size())
      check.fail(at + ".first_beam",
                 fmt::format("the index of its first fibre in beams, with room for {}", beams.size()),
                 std::to_string(yarn.first_beam));
    for (std::size_t i = 0; i < beams.size(); ++i) {
      const BeamSpec& want = beams[i];
      const BeamSpec& got = s.beams[beam_at(i)];
      if (got.name != want.name || got.material != want.material || got.radius != want.radius ||
          got.length != want.length || got.elements != want.elements || got.start != want.start ||
          got.direction != want.direction || got.director1 != want.director1 ||
          got.bending_factor != want.bending_factor)
        check.fail(fmt::format("beams[{}]", beam_at(i)),
                   fmt::format("fibre {} of yarn {} as append_yarn makes it", want.name, yarn.name),
                   got.name);
    }
    const std::vector<BodySpec> bodies = yarn_bodies(yarn, yarn.first_beam);
    const auto body_at = [&](std::size_t i) { return static_cast<std::size_t>(yarn.first_body) + i; };
    if (yarn.first_body < 0 || body_at(bodies.size()) > s.bodies.size())
      check.fail(at + ".first_body",
                 fmt::format("the index of its first body in bodies, with room for {}", bodies.size()),
                 std::to_string(yarn.first_body));
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const BodySpec& want = bodies[i];
      const BodySpec& got = s.bodies[body_at(i)];
      const bool same_sections = got.sections.size() == want.sections.size() &&
                                 std::equal(got.sections.begin(), got.sections.end(), want.sections.begin(),
                                            [](const SectionRef& a, const SectionRef& b) {
                                              return a.beam == b.beam && a.node == b.node;
                                            });
      if (got.name != want.name || !same_sections || got.tie != want.tie)
        check.fail(fmt::format("bodies[{}]", body_at(i)),
                   fmt::format("body {} of yarn {} as append_yarn makes it", want.name, yarn.name), got.name);
    }
  }
}

void check_conditions(const Checker& check, const Scenario& s, AxisCheck& axes) {
  check.names(
      names_of(s.conditions), [](std::size_t i) { return fmt::format("conditions[{}].name", i); },
      "conditions[].name", "conditions");
  for (std::size_t c = 0; c < s.conditions.size(); ++c) {
    const ConditionSpec& condition = s.conditions[c];
    const std::string at = fmt::format("conditions[{}]", c);
    check.keys(ConditionSpec::keys(), condition, "conditions[]", at);
    if (!condition.bodies.empty()) {
      for (std::size_t i = 0; i < condition.bodies.size(); ++i) {
        const std::string path = fmt::format("{}.bodies[{}]", at, i);
        check.index(path, condition.bodies[i], s.bodies.size(), "bodies");
        if (std::find(condition.bodies.begin(), condition.bodies.begin() + static_cast<std::ptrdiff_t>(i),
                      condition.bodies[i]) != condition.bodies.begin() + static_cast<std::ptrdiff_t>(i))
          check.fail(path, "each body once in bodies", std::to_string(condition.bodies[i]));
      }
      if (condition.type == ConditionType::rigid)
        check.fail(at + ".bodies",
                   "no bodies on a rigid condition (bodies are for clamp, motion, load and bind conditions)",
                   "a list");
      if (condition.type == ConditionType::load && condition.bodies.size() != 1)
        check.fail(at + ".bodies", "one body for a load condition", std::to_string(condition.bodies.size()));
      if (condition.type == ConditionType::bind && condition.bodies.size() < 2)
        check.fail(at + ".bodies", kBindBodiesExpected, std::to_string(condition.bodies.size()));
      if (condition.type == ConditionType::bind &&
          (condition.body_dofs[kBodyRx] || condition.body_dofs[kBodyRy] || condition.body_dofs[kBodyRz]))
        check.fail(at + ".dofs", kBindDofsExpected, "a rotation");
      if (condition.pivot && condition.type != ConditionType::motion)
        check.fail(at + ".pivot",
                   fmt::format("no pivot on a {} condition on bodies (pivot is for motion conditions)",
                               type_name(condition.type)),
                   format_vec(*condition.pivot));
      if (condition.pivot && !condition.pivot->allFinite())
        check.fail_key(at + ".pivot", "conditions[].pivot", "a non-finite value");
      if (condition.type != ConditionType::load) {
        if (std::none_of(condition.body_dofs.begin(), condition.body_dofs.end(), [](bool d) { return d; }))
          check.fail_key(at + ".dofs", "conditions[].dofs", "[]");
        for (const auto& [key, value] : {std::pair{"force", condition.force}, {"moment", condition.moment}})
          if (value.squaredNorm() != 0.0)
            check.fail(at + "." + key,
                       fmt::format("no {} on a {} condition ({} is for load conditions only)", key,
                                   type_name(condition.type), key),
                       format_vec(value));
      } else {
        if (!condition.force.allFinite())
          check.fail_key(at + ".force", "conditions[].force", format_vec(condition.force));
        if (!condition.moment.allFinite())
          check.fail_key(at + ".moment", "conditions[].moment", format_vec(condition.moment));
        axes.moment(static_cast<int>(c), condition.moment, at + ".moment");
      }
      continue;
    }
    if (condition.type == ConditionType::bind) check.fail(at + ".type", kBindOnBodiesExpected, "bind");
    check.index(at + ".beam", condition.beam, s.beams.size(), "beams");
    const BeamSpec& beam = s.beams[static_cast<std::size_t>(condition.beam)];
    const std::string_view type = type_name(condition.type);
    if (condition.pivot) {
      if (condition.type != ConditionType::motion && condition.type != ConditionType::rigid)
        check.fail(at + ".pivot",
                   fmt::format("no pivot on a {} condition (pivot is for motion and rigid conditions)", type),
                   format_vec(*condition.pivot));
      if (!condition.pivot->allFinite())
        check.fail_key(at + ".pivot", "conditions[].pivot", "a non-finite value");
    }
    if (condition.type == ConditionType::rigid) {
      for (const auto& [key, value] : {std::pair{"force", condition.force}, {"moment", condition.moment}}) {
        if (value.squaredNorm() != 0.0)
          check.fail(at + "." + key,
                     fmt::format("no {} on a rigid condition (it moves every node of its beam)", key),
                     format_vec(value));
      }
      if (!std::all_of(condition.dofs.begin(), condition.dofs.end(), [](bool d) { return d; }))
        check.fail(at + ".dofs", "no dofs on a rigid condition (it moves every node of its beam)",
                   "a subset of the dofs");
      continue;
    }
    const int last_node = 2 * beam.elements;
    if (condition.node < 0 || condition.node > last_node) {
      check.fail(at + ".at",
                 fmt::format("one of start | end | an integer in [0, {}] (beam {}: elements {})", last_node,
                             beam.name, beam.elements),
                 std::to_string(condition.node));
    }
    if (condition.type != ConditionType::load) {
      if (std::none_of(condition.dofs.begin(), condition.dofs.end(), [](bool d) { return d; }))
        check.fail_key(at + ".dofs", "conditions[].dofs", "[]");
      for (const auto& [key, value] : {std::pair{"force", condition.force}, {"moment", condition.moment}}) {
        if (value.squaredNorm() != 0.0)
          check.fail(at + "." + key,
                     fmt::format("no {} on a {} condition ({} is for load conditions only)", key, type, key),
                     format_vec(value));
      }
    } else {
      if (!condition.force.allFinite())
        check.fail_key(at + ".force", "conditions[].force", format_vec(condition.force));
      if (!condition.moment.allFinite())
        check.fail_key(at + ".moment", "conditions[].moment", format_vec(condition.moment));
      axes.moment(static_cast<int>(c), condition.moment, at + ".moment");
    }
  }
}

/// A list of condition indices of a stage: valid, each once.
void check_condition_list(const Checker& check, const Scenario& s, const std::vector<int>& list,
                          const std::string& at, std::string_view list_name) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("{}.{}[{}]", at, list_name, i);
    check.index(path, list[i], s.conditions.size(), "conditions");
    if (std::find(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(i), list[i]) !=
        list.begin() + static_cast<std::ptrdiff_t>(i))
      check.fail(path, fmt::format("each condition once in {}", list_name), std::to_string(list[i]));
  }
}

void check_contact_list(const Checker& check, const Scenario& s, const std::vector<int>& list,
                        const std::string& at, std::string_view list_name) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("{}.{}[{}]", at, list_name, i);
    if (!s.contact.enabled)
      check.fail(fmt::format("{}.{}", at, list_name),
                 "no contact_off or contact_on without a contact section", "a list");
    check.index(path, list[i], s.beams.size(), "beams");
    const auto& beams = s.contact.beams;
    if (!beams.empty() && std::find(beams.begin(), beams.end(), list[i]) == beams.end())
      check.fail(path, "a beam listed in contact.beams", s.beams[static_cast<std::size_t>(list[i])].name);
    if (std::find(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(i), list[i]) !=
        list.begin() + static_cast<std::ptrdiff_t>(i))
      check.fail(path, fmt::format("each beam once in {}", list_name),
                 s.beams[static_cast<std::size_t>(list[i])].name);
  }
}

void check_stages(const Checker& check, const Scenario& s, const std::vector<StageSpec>& stages,
                  std::string_view prefix, AxisCheck& axes) {
  check.names(
      names_of(stages), [&](std::size_t i) { return fmt::format("{}[{}].name", prefix, i); }, "stages[].name",
      "stages");
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const StageSpec& stage = stages[k];
    const std::string at = fmt::format("{}[{}]", prefix, k);
    check.keys(StageSpec::keys(), stage, "stages[]", at);
    // The written value of one of the stage's keys, for a message.
    const auto value_of = [&stage](std::string_view path) {
      const auto keys = StageSpec::keys();
      return value_text(*std::find_if(keys.begin(), keys.end(),
                                      [path](const Key<StageSpec>& key) { return key.path == path; }),
                        stage);
    };
    if (const std::string_view expected = stage_solver_expected(stage, s); !expected.empty())
      check.fail(at + ".linear_solver", expected, value_of("stages[].linear_solver"));
    if (stage.stabilization_end > 0.0 && stage.stabilization == 0.0)
      check.fail(at + ".stabilization_end", kStabilizationEndExpected,
                 format_number(stage.stabilization_end));
    if (stage.particles != StageParticles::contact && !s.contact.enabled)
      check.fail(at + ".particles", kStageParticlesExpected, value_of("stages[].particles"));
    check_condition_list(check, s, stage.activate, at, "activate");
    check_condition_list(check, s, stage.release, at, "release");
    for (std::size_t i = 0; i < stage.release.size(); ++i) {
      const std::string path = fmt::format("{}.release[{}]", at, i);
      const ConditionSpec& condition = s.conditions[static_cast<std::size_t>(stage.release[i])];
      if (std::find(stage.activate.begin(), stage.activate.end(), stage.release[i]) != stage.activate.end())
        check.fail(path, "a condition that is not also in activate of the same stage", condition.name);
      if (condition.type == ConditionType::rigid)
        check.fail(
            path,
            "a condition that is not rigid (a tool beam stays where its motion puts it; take it out of "
            "contact with contact_off)",
            condition.name);
      if (condition.type == ConditionType::bind) check.fail(path, kReleaseBindExpected, condition.name);
      if (condition.bodies.size() > 1 && condition.type != ConditionType::load)
        check.fail(path, kReleaseOnSeveralBodiesExpected, condition.name);
    }
    check_contact_list(check, s, stage.contact_off, at, "contact_off");
    check_contact_list(check, s, stage.contact_on, at, "contact_on");
    for (std::size_t i = 0; i < stage.contact_off.size(); ++i) {
      if (std::find(stage.contact_on.begin(), stage.contact_on.end(), stage.contact_off[i]) !=
          stage.contact_on.end())
        check.fail(fmt::format("{}.contact_off[{}]", at, i),
                   "a beam that is not also in contact_on of the same stage",
                   s.beams[static_cast<std::size_t>(stage.contact_off[i])].name);
    }
    for (std::size_t m = 0; m < stage.motions.size(); ++m) {
      const MotionTarget& motion = stage.motions[m];
      const std::string path = fmt::format("{}.motions[{}]", at, m);
      check.index(path + ".condition", motion.condition, s.conditions.size(), "conditions");
      const ConditionSpec& condition = s.conditions[static_cast<std::size_t>(motion.condition)];
      if (condition.type != ConditionType::motion && condition.type != ConditionType::rigid)
        check.fail(path + ".condition", "a motion or rigid condition",
                   fmt::format("{} (a {} condition)", condition.name, type_name(condition.type)));
      const std::string frames = fmt::format("{}.motions.{}.keyframes", at, condition.name);
      if (motion.keyframes.empty()) check.fail_key(frames, "stages[].motions.<condition>.keyframes", "[]");
      double previous = 0.0;
      for (std::size_t f = 0; f < motion.keyframes.size(); ++f) {
        const Keyframe& frame = motion.keyframes[f];
        const std::string frame_at = fmt::format("{}[{}]", frames, f);
        check.keys(Keyframe::keys(), frame, "stages[].motions.<condition>.keyframes[]", frame_at);
        if (!(frame.at > previous))
          check.fail(frame_at + ".at",
                     fmt::format("a number in ({}, 1]: greater than the at of the previous keyframe",
                                 format_number(previous)),
                     format_number(frame.at));
        if (f + 1 == motion.keyframes.size() && frame.at != 1.0)
          check.fail(frame_at + ".at", "1 for the last keyframe", format_number(frame.at));
        if (!frame.translation.allFinite() || !frame.rotation.allFinite())
          check.fail_key(frame_at + ".translation", "stages[].motions.<condition>.keyframes[].translation",
                         "a non-finite value");
        previous = frame.at;
      }
    }
    for (std::size_t l = 0; l < stage.loads.size(); ++l) {
      const LoadTarget& load = stage.loads[l];
      const std::string path = fmt::format("{}.loads[{}]", at, l);
      check.index(path + ".condition", load.condition, s.conditions.size(), "conditions");
      const ConditionSpec& condition = s.conditions[static_cast<std::size_t>(load.condition)];
      if (condition.type != ConditionType::load)
        check.fail(path + ".condition", "a load condition",
                   fmt::format("{} (a {} condition)", condition.name, type_name(condition.type)));
      const std::string values = fmt::format("{}.loads.{}", at, condition.name);
      if (!load.force.allFinite())
        check.fail_key(values + ".force", "stages[].loads.<condition>.force", format_vec(load.force));
      if (!load.moment.allFinite())
        check.fail_key(values + ".moment", "stages[].loads.<condition>.moment", format_vec(load.moment));
      axes.moment(load.condition, load.moment, values + ".moment");
    }
  }
}

void check_contact(const Checker& check, const Scenario& s) {
  const ContactSettings& contact = s.contact;
  check.keys(ContactSettings::keys(), contact, "contact", "contact");
  // Indices of beams, each once.
  const auto check_beams = [&](const std::vector<int>& beams, const std::string& at, std::string_view where) {
    for (std::size_t i = 0; i < beams.size(); ++i) {
      const std::string path = fmt::format("{}[{}]", at, i);
      check.index(path, beams[i], s.beams.size(), "beams");
      if (std::find(beams.begin(), beams.begin() + static_cast<std::ptrdiff_t>(i), beams[i]) !=
          beams.begin() + static_cast<std::ptrdiff_t>(i))
        check.fail(path, fmt::format("each beam once in {}", where),
                   s.beams[static_cast<std::size_t>(beams[i])].name);
    }
  };
  check_beams(contact.beams, "contact.beams", "contact.beams");
  for (std::size_t k = 0; k < contact.friction_pairs.size(); ++k) {
    const FrictionPair& pair = contact.friction_pairs[k];
    const std::string at = fmt::format("contact.friction_pairs[{}]", k);
    if (pair.beams.empty()) check.fail_key(at + ".beams", "contact.friction_pairs[].beams", "[]");
    check_beams(pair.beams, at + ".beams", "contact.friction_pairs[].beams");
    check_beams(pair.with, at + ".with", "contact.friction_pairs[].with");
    if (!(std::isfinite(pair.friction) && pair.friction >= 0.0))
      check.fail_key(at + ".friction", "contact.friction_pairs[].friction", format_number(pair.friction));
  }
  if (contact.test_point_spacing > 0.0 && contact.matching_length > 0.0 &&
      contact.matching_length < contact.test_point_spacing)
    check.fail("contact.matching_length", kMatchingLengthExpected, format_number(contact.matching_length));
  if (contact.proximity_distance > 0.0 && contact.separation_distance > 0.0 &&
      contact.separation_distance <= contact.proximity_distance)
    check.fail("contact.separation_distance", kSeparationDistanceExpected,
               format_number(contact.separation_distance));
  if (contact.friction_tangent == FrictionTangent::varying &&
      s.solver.linear_solver == LinearSolverKind::cholmod)
    check.fail("contact.friction_tangent", kFrictionTangentExpected, "varying");
  if (contact.normal_updates == NormalUpdates::linearized &&
      s.solver.linear_solver == LinearSolverKind::cholmod)
    check.fail("contact.normal_updates", kLinearizedNormalsExpected, "linearized");
  if (const TestPoints points = contact_test_points(s); points.count > max_test_points())
    check.fail("contact.test_point_spacing", test_points_expected(points),
               s.contact.test_point_spacing > 0.0 ? format_number(s.contact.test_point_spacing) : "auto");
}

/// Whether a branch name can be a folder name: letters, digits, '_', '.', '-', not starting with '.'.
bool is_folder_name(const std::string& name) {
  return !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == '-';
  });
}

}  // namespace

void validate(const Scenario& s) {
  const Checker check(s);
  if (s.materials.empty()) check.fail_key("materials", "materials", "[]");
  if (s.beams.empty()) check.fail_key("beams", "beams", "[]");
  if (s.stages.empty()) check.fail_key("stages", "stages", "[]");
  check_beams(check, s);
  check_yarns(check, s);  // before the bodies: a yarn's body is reported as the yarn's
  check_bodies(check, s);
  AxisCheck axes(check);
  check_conditions(check, s, axes);
  check_contact(check, s);
  check_stages(check, s, s.stages, "stages", axes);
  check.keys(SolverSettings::keys(), s.solver, "solver", "solver");
  check.keys(OutputSettings::keys(), s.output, "output", "output");
  check.names(
      names_of(s.branches), [](std::size_t i) { return fmt::format("branches[{}].name", i); },
      "branches[].name", "branches");
  for (std::size_t b = 0; b < s.branches.size(); ++b) {
    const BranchSpec& branch = s.branches[b];
    const std::string at = fmt::format("branches[{}]", b);
    if (!is_folder_name(branch.name))
      check.fail(at + ".name",
                 "a name of letters, digits, _ . - not starting with . (it names the output folder "
                 "DIR/branches/NAME)",
                 branch.name);
    check.index(at + ".from", branch.from, s.stages.size(), "stages");
    if (branch.friction && !(std::isfinite(*branch.friction) && *branch.friction >= 0.0))
      check.fail_key(at + ".contact.friction", "branches[].contact.friction",
                     format_number(*branch.friction));
    if (branch.stages.empty()) check.fail_key(at + ".stages", "branches[].stages", "[]");
    check_stages(check, s, branch.stages, at + ".stages", axes);
  }
  // The axis of each load's moment, as the reader sets it: the direction of its first nonzero moment.
  for (std::size_t c = 0; c < s.conditions.size(); ++c) {
    if (s.conditions[c].type != ConditionType::load) continue;
    const auto axis = axes.axis(static_cast<int>(c));
    const auto& given = s.conditions[c].moment_axis;
    if (axis.has_value() != given.has_value() || (axis && (*axis - *given).norm() > kUnitTolerance)) {
      check.fail(fmt::format("conditions[{}].moment_axis", c),
                 axis ? fmt::format("the direction of its first nonzero moment, {}", format_vec(*axis))
                      : std::string("none (it has no nonzero moment)"),
                 given ? format_vec(*given) : std::string("none"));
    }
  }
}

}  // namespace nodus::scenario
