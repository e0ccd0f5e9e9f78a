#include "nodus/scenario/fingerprint.hpp"

#include <algorithm>

#include <fmt/format.h>

#include <span>
#include <string_view>
#include <vector>

#include "nodus/scenario/declared_keys.hpp"
#include "nodus/scenario/linear_solver_choice.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yaml_reader.hpp"

namespace nodus::scenario {

namespace {

/// A number in full precision: equal texts, equal values.
std::string exact(double value) {
  return fmt::format("{:.17g}", value);
}

std::string exact(const Vec3& v) {
  return fmt::format("[{}, {}, {}]", exact(v.x()), exact(v.y()), exact(v.z()));
}

std::string list(const std::vector<int>& items) {
  return fmt::format("[{}]", fmt::join(items, ", "));
}

/// Canonical lines "PATH = VALUE", one per value, in declaration order.
class Canonical {
 public:
  void line(std::string_view path, std::string_view value) {
    text_ += path;
    text_ += " = ";
    text_ += value;
    text_ += '\n';
  }

  /// Every declared scalar key of `owner`; `prefix` replaces the pattern prefix `pattern`.
  template <class Owner>
  void keys(const Owner& owner, std::string_view pattern, std::string_view prefix,
            std::initializer_list<std::string_view> skipped = {}) {
    for (const Key<Owner>& key : Owner::keys()) {
      if (!key.scalar() || std::find(skipped.begin(), skipped.end(), key.path) != skipped.end()) continue;
      line(std::string(prefix) + std::string(key.path.substr(pattern.size())), value_text(key, owner, true));
    }
  }

  void stages(const std::vector<StageSpec>& stages) {
    for (std::size_t k = 0; k < stages.size(); ++k) {
      const StageSpec& stage = stages[k];
      const std::string at = fmt::format("stages[{}]", k);
      line(at + ".name", stage.name);
      // A stage's own line search, linear solver or particles add a line only where it has them: the text of
      // a scenario without is what it was before the keys existed, so that its checkpoints stay valid.
      keys(stage, "stages[]", at,
           {stage.line_search == StageSwitch::solver ? std::string_view("stages[].line_search") : "",
            !stage.linear_solver ? std::string_view("stages[].linear_solver") : "",
            stage.particles == StageParticles::contact ? std::string_view("stages[].particles") : ""});
      line(at + ".activate", list(stage.activate));
      line(at + ".release", list(stage.release));
      line(at + ".contact_off", list(stage.contact_off));
      line(at + ".contact_on", list(stage.contact_on));
      for (std::size_t m = 0; m < stage.motions.size(); ++m) {
        const MotionTarget& motion = stage.motions[m];
        const std::string target = fmt::format("{}.motions[{}]", at, m);
        line(target + ".condition", std::to_string(motion.condition));
        for (std::size_t f = 0; f < motion.keyframes.size(); ++f) {
          const Keyframe& frame = motion.keyframes[f];
          const std::string frame_at = fmt::format("{}.keyframes[{}]", target, f);
          keys(frame, "stages[].motions.<condition>.keyframes[]", frame_at);
          line(frame_at + ".translation", exact(frame.translation));
          line(frame_at + ".rotation", exact(frame.rotation));
        }
      }
      for (std::size_t l = 0; l < stage.loads.size(); ++l) {
        const LoadTarget& load = stage.loads[l];
        const std::string target = fmt::format("{}.loads[{}]", at, l);
        line(target + ".condition", std::to_string(load.condition));
        line(target + ".force", exact(load.force));
        line(target + ".moment", exact(load.moment));
      }
    }
  }

  std::string text() && { return std::move(text_); }

 private:
  std::string text_;
};

/// The canonical serialisation of everything in `s` that makes a state: every value in full precision, in
/// declaration order, names and indices included; not the path, the lines, the output settings, the branches.
std::string canonical_text(const Scenario& s) {
  Canonical out;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const std::string at = fmt::format("materials[{}]", m);
    out.line(at + ".name", s.materials[m].name);
    out.keys(s.materials[m], "materials[]", at);
  }
  for (std::size_t b = 0; b < s.beams.size(); ++b) {
    const BeamSpec& beam = s.beams[b];
    const std::string at = fmt::format("beams[{}]", b);
    out.line(at + ".name", beam.name);
    out.line(at + ".material", std::to_string(beam.material));
    out.keys(beam, "beams[]", at);
    out.line(at + ".start", exact(beam.start));
    out.line(at + ".direction", exact(beam.direction));
    out.line(at + ".director1", exact(beam.director1));
  }
  // Bodies and conditions on bodies add lines only where they exist: the text of a scenario without them
  // is what it was before bodies were added, so its checkpoints stay valid.
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const BodySpec& body = s.bodies[b];
    const std::string at = fmt::format("bodies[{}]", b);
    out.line(at + ".name", body.name);
    out.keys(body, "bodies[]", at);
    std::string sections;
    for (const SectionRef& section : body.sections)
      sections += fmt::format("{}{}:{}", sections.empty() ? "" : ",", section.beam, section.node);
    out.line(at + ".sections", sections);
  }
  for (std::size_t c = 0; c < s.conditions.size(); ++c) {
    const ConditionSpec& condition = s.conditions[c];
    const std::string at = fmt::format("conditions[{}]", c);
    out.line(at + ".name", condition.name);
    out.keys(condition, "conditions[]", at);
    out.line(at + ".beam", std::to_string(condition.beam));
    out.line(at + ".node", std::to_string(condition.node));
    std::string dofs;
    for (bool d : condition.dofs) dofs += d ? '1' : '0';
    out.line(at + ".dofs", dofs);
    if (!condition.bodies.empty()) {
      out.line(at + ".bodies", list(condition.bodies));
      std::string body_dofs;
      for (bool d : condition.body_dofs) body_dofs += d ? '1' : '0';
      out.line(at + ".body_dofs", body_dofs);
    }
    out.line(at + ".force", exact(condition.force));
    out.line(at + ".moment", exact(condition.moment));
    out.line(at + ".pivot", condition.pivot ? exact(*condition.pivot) : std::string("none"));
    out.line(at + ".moment_axis",
             condition.moment_axis ? exact(*condition.moment_axis) : std::string("none"));
  }
  out.stages(s.stages);
  // A key added since checkpoints were first written adds its line only away from its default, so that the
  // checkpoints of the scenarios without it stay valid.
  out.keys(
      s.solver, "solver", "solver",
      {s.solver.backtrack_from == SolverSettings{}.backtrack_from ? std::string_view("solver.backtrack_from")
                                                                  : ""});
  out.line("solver.petsc_options", s.solver.petsc_options);
  out.keys(s.contact, "contact", "contact");
  out.line("contact.beams", list(s.contact.beams));
  // Only where there are any: the fingerprints of the scenarios without them stay as they were.
  for (std::size_t k = 0; k < s.contact.friction_pairs.size(); ++k) {
    const FrictionPair& pair = s.contact.friction_pairs[k];
    const std::string at = fmt::format("contact.friction_pairs[{}]", k);
    out.line(at + ".beams", list(pair.beams));
    out.line(at + ".with", list(pair.with));
    out.line(at + ".friction", exact(pair.friction));
  }
  return std::move(out).text();
}

}  // namespace

std::string state_fingerprint_text(const Scenario& scenario, int stages_run) {
  Scenario made = scenario;
  choose_linear_solver(made);  // a scenario built in code, not yet resolved: as its file would read
  made.path.clear();
  made.output = OutputSettings{};
  made.branches.clear();
  for (ConditionSpec& condition : made.conditions) condition.line = 0;
  if (made.contact.beams.empty()) {  // all beams, as the run resolves it
    for (std::size_t b = 0; b < made.beams.size(); ++b) made.contact.beams.push_back(static_cast<int>(b));
  }
  made.stages.resize(
      static_cast<std::size_t>(std::clamp(stages_run, 0, static_cast<int>(made.stages.size()))));
  std::string suffix;
  if (scenario.origin) {
    // Up to the end of stage `from` the state is the parent's, made with the parent's friction.
    made.contact.friction = scenario.origin->parent_friction;
    if (stages_run > scenario.origin->from + 1) {
      suffix = fmt::format("branch.from = {}\nbranch.contact.friction = {}\n", scenario.origin->from,
                           exact(scenario.contact.friction));
    }
  }
  return canonical_text(made) + suffix;
}

std::uint64_t fingerprint_hash(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace nodus::scenario
