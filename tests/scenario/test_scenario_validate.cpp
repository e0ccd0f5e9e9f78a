// Tests of validate(): a scenario built or changed in code gets the reader's message minus the line, for
// every declared number and integer key (generated from the declarations, key.hpp) and for checks across
// keys; every declared key is in `nodus keys` and in docs/scenario.md; and the checkpoint fingerprint, a
// canonical serialisation, changes with every value and is the same for a scenario read and one built in
// code.

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <regex>
#include <span>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "nodus/scenario/keys.hpp"
#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {
namespace {

// Every number and integer key of these sections is given, valid, on a line of its own.
constexpr const char* kBase = R"(materials:
  - name: steel
    young_modulus: 200000
    poisson_ratio: 0.3
beams:
  - name: wire
    material: steel
    radius: 0.1
    length: 10
    elements: 4
    bending_factor: 1
conditions:
  - {name: fix, type: clamp, beam: wire, at: start}
  - {name: pull, type: motion, beam: wire, at: end}
stages:
  - name: load
    steps: 2
    duration: 1
    stabilization: 0.1
    stabilization_end: 0.01
    motions:
      pull:
        keyframes:
          - at: 1
            translation: [1, 0, 0]
solver:
  linear_solver: umfpack
  max_newton_iterations: 25
  stagnation_iterations: 0
  progress_window: 0
  progress_ratio: 0.1
  residual_tolerance: 1e-8
  increment_tolerance: 1e-6
  max_cutbacks: 12
  easy_iterations: 4
  backtrack_from: 0
  krylov_iterations: 20
  gauss_points: 2
  fold_stiffness: 0
  fold_barrier: 1
output:
  vtk_every: 1
  tube_sides: 12
  progress_seconds: 1
  checkpoint_every: 0
contact:
  proximity_distance: 0.3
  separation_distance: 1.2
  test_point_spacing: 0.2
  matching_length: 0.4
  element_spacing: 0.1
  penalty: 100
  max_penetration: 0.01
  regularization: 0.001
  friction: 0.1
  max_reversible_slip: 0.005
  max_detections: 4
  max_normal_iterations: 6
  normal_tolerance: 0.001
  normal_pass_residual: 0.01
)";

/// kBase with the value of the first line " LEAF: ..." after the line starting `section` replaced.
std::string with_value(const std::string& section, const std::string& leaf, const std::string& value) {
  std::string text = kBase;
  const std::size_t start = text.find(section);
  EXPECT_NE(start, std::string::npos) << section;
  const std::size_t at = text.find(" " + leaf + ": ", start);
  EXPECT_NE(at, std::string::npos) << leaf;
  const std::size_t begin = at + leaf.size() + 3;
  return text.replace(begin, text.find('\n', begin) - begin, value);
}

/// The reader's message for `yaml` with its line left out: "t.yaml:12: KEY: ..." -> "t.yaml: KEY: ...".
std::string reader_message(const std::string& yaml) {
  try {
    parse_scenario(yaml, "t.yaml");
  } catch (const ScenarioError& error) {
    return std::regex_replace(std::string(error.what()), std::regex("^t\\.yaml:[0-9]+: "), "t.yaml: ");
  }
  return "(accepted)";
}

std::string validate_message(const Scenario& scenario) {
  try {
    validate(scenario);
  } catch (const ScenarioError& error) {
    return error.what();
  }
  return "(accepted)";
}

Scenario base() {
  return parse_scenario(kBase, "t.yaml");
}

/// A value outside the range of `key` (and not auto): the first of a few candidates that fails it.
template <class Owner>
std::optional<double> bad_value(const Key<Owner>& key) {
  for (double v : {-1.0, 0.0, 0.5, 6.0}) {
    if (key.ok != nullptr && !key.ok(v) && !(key.zero_is_auto && v == 0.0)) return v;
  }
  return std::nullopt;
}

/// For each number and integer key of `Owner`: the file with the bad value and the scenario with the same
/// value set in code give the same message, less the line.
template <class Owner>
int check_keys(const std::string& section, const std::function<Owner&(Scenario&)>& owner_of) {
  int checked = 0;
  for (const Key<Owner>& key : Owner::keys()) {
    if (!key.number && !key.integer) continue;
    const auto value = bad_value(key);
    if (!value) {
      ADD_FAILURE() << key.path << ": no out-of-range candidate";
      continue;
    }
    const std::string text = fmt::format("{}", *value);
    const std::string leaf(key.path.substr(key.path.rfind('.') + 1));
    const std::string from_file = reader_message(with_value(section, leaf, text));
    Scenario scenario = base();
    Owner& owner = owner_of(scenario);
    if (key.number) owner.*key.number = *value;
    if (key.integer) owner.*key.integer = static_cast<int>(*value);
    EXPECT_EQ(validate_message(scenario), from_file) << key.path;
    EXPECT_NE(from_file, "(accepted)") << key.path;
    ++checked;
  }
  return checked;
}

TEST(ScenarioValidate, BaseIsValid) {
  EXPECT_NO_THROW(validate(base()));
}

TEST(ScenarioValidate, EveryNumberKeyOutOfRangeGivesTheReadersMessage) {
  int checked = 0;
  checked += check_keys<Material>("materials:", [](Scenario& s) -> Material& { return s.materials[0]; });
  checked += check_keys<BeamSpec>("beams:", [](Scenario& s) -> BeamSpec& { return s.beams[0]; });
  checked += check_keys<StageSpec>("stages:", [](Scenario& s) -> StageSpec& { return s.stages[0]; });
  checked += check_keys<Keyframe>(
      "keyframes:", [](Scenario& s) -> Keyframe& { return s.stages[0].motions[0].keyframes[0]; });
  checked += check_keys<SolverSettings>("solver:", [](Scenario& s) -> SolverSettings& { return s.solver; });
  checked += check_keys<OutputSettings>("output:", [](Scenario& s) -> OutputSettings& { return s.output; });
  checked +=
      check_keys<ContactSettings>("contact:", [](Scenario& s) -> ContactSettings& { return s.contact; });
  // Every number and integer key declared in these structs: 2 + 4 + 4 + 1 + 13 + 4 + 14.
  EXPECT_EQ(checked, 42);
}

TEST(ScenarioValidate, ChecksAcrossKeysGiveTheReadersMessage) {
  {  // the varying friction tangent needs LU
    Scenario s = base();
    s.solver.linear_solver = LinearSolverKind::cholmod;
    s.contact.friction_tangent = FrictionTangent::varying;
    std::string yaml = with_value("solver:", "linear_solver", "cholmod");
    yaml += "  friction_tangent: varying\n";
    EXPECT_EQ(validate_message(s), reader_message(yaml));
    EXPECT_NE(validate_message(s).find("t.yaml: contact.friction_tangent: expected frozen"),
              std::string::npos);
  }
  {  // the linearized normals need LU
    Scenario s = base();
    s.solver.linear_solver = LinearSolverKind::cholmod;
    s.contact.normal_updates = NormalUpdates::linearized;
    std::string yaml = with_value("solver:", "linear_solver", "cholmod");
    yaml += "  normal_updates: linearized\n";
    EXPECT_EQ(validate_message(s), reader_message(yaml));
    EXPECT_NE(validate_message(s).find("t.yaml: contact.normal_updates: expected nested or inside_newton"),
              std::string::npos);
  }
  {  // matching intervals must overlap
    Scenario s = base();
    s.contact.matching_length = 0.1;
    EXPECT_EQ(validate_message(s), reader_message(with_value("contact:", "matching_length", "0.1")));
  }
  {
    Scenario s = base();
    s.contact.separation_distance = 0.3;
    EXPECT_EQ(validate_message(s), reader_message(with_value("contact:", "separation_distance", "0.3")));
  }
  {  // a drag that ends without one at the start
    Scenario s = base();
    s.stages[0].stabilization = 0.0;
    EXPECT_EQ(validate_message(s), reader_message(with_value("stages:", "stabilization", "0")));
  }
  {  // the node of a condition within the beam
    Scenario s = base();
    s.conditions[1].node = 9;
    EXPECT_EQ(validate_message(s), reader_message(with_value("pull, type", "at", "9}")));
  }
  {  // beam elements above the limit
    Scenario s = base();
    s.beams[0].elements = 100'000'001;
    EXPECT_EQ(validate_message(s), reader_message(with_value("beams:", "elements", "100000001")));
  }
  {  // the last keyframe at the stage end
    Scenario s = base();
    s.stages[0].motions[0].keyframes[0].at = 0.5;
    EXPECT_EQ(validate_message(s), reader_message(with_value("keyframes:", "at", "0.5")));
  }
}

TEST(ScenarioValidate, ReferencesAndNamesInCode) {
  {
    Scenario s = base();
    s.beams[0].material = 3;
    EXPECT_EQ(validate_message(s),
              "t.yaml: beams[0].material: expected an index into materials (0 .. 0), got 3");
  }
  {
    Scenario s = base();
    s.conditions[1].name = "fix";
    EXPECT_EQ(validate_message(s),
              "t.yaml: conditions[1].name: expected a name unique among conditions (already used by "
              "conditions[0].name), got fix");
  }
  {
    Scenario s = base();
    s.stages[0].motions[0].condition = 0;  // a clamp
    EXPECT_EQ(
        validate_message(s),
        "t.yaml: stages[0].motions[0].condition: expected a motion or rigid condition, got fix (a clamp "
        "condition)");
  }
  {
    Scenario s = base();
    s.contact.beams = {0, 0};
    EXPECT_EQ(validate_message(s),
              "t.yaml: contact.beams[1]: expected each beam once in contact.beams, got wire");
  }
  {
    Scenario s = base();
    s.beams[0].direction = Vec3(2, 0, 0);
    EXPECT_NE(
        validate_message(s).find("t.yaml: beams[0].direction: expected a list of 3 numbers of length 1"),
        std::string::npos);
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Every key declared next to a struct field: the paths of all keys() lists.
std::vector<std::string> declared_paths() {
  std::vector<std::string> out;
  const auto add = [&out](const auto& keys) {
    for (const auto& key : keys) out.emplace_back(key.path);
  };
  add(Scenario::keys());
  add(Material::keys());
  add(BeamSpec::keys());
  add(YarnSpec::keys());
  add(BodySpec::keys());
  add(ConditionSpec::keys());
  add(StageSpec::keys());
  add(MotionTarget::keys());
  add(Keyframe::keys());
  add(LoadTarget::keys());
  add(SolverSettings::keys());
  add(OutputSettings::keys());
  add(ContactSettings::keys());
  add(BranchSpec::keys());
  return out;
}

TEST(ScenarioValidate, EveryDeclaredKeyIsInNodusKeysAndTheDocs) {
  const std::string docs = read_file(std::string(NODUS_SOURCE_DIR) + "/docs/scenario.md");
  std::string keys;
  {
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(NODUS_BINARY " keys", "r"), pclose);
    ASSERT_TRUE(pipe);
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe.get())) keys += buffer.data();
  }
  const std::vector<std::string> paths = declared_paths();
  EXPECT_EQ(paths.size(), scenario_keys().size());  // the table holds the declarations, nothing else
  for (const std::string& path : paths) {
    EXPECT_NE(keys.find("| `" + path + "` |"), std::string::npos) << path << " missing from nodus keys";
    EXPECT_NE(docs.find("| `" + path + "` |"), std::string::npos) << path << " missing from docs/scenario.md";
  }
}

/// Each declared scalar key of `Owner` changed in code (number: 2 v + 1, integer: + 1, bool: flipped,
/// choice: the next alternative) changes the fingerprint; returns the keys changed.
template <class Owner>
int check_fingerprint(const std::function<Owner&(Scenario&)>& owner_of) {
  const Scenario original = base();
  const std::string fingerprint = state_fingerprint_text(original, 1);
  int checked = 0;
  for (const Key<Owner>& key : Owner::keys()) {
    if (!key.scalar()) continue;
    Scenario changed = original;
    Owner& owner = owner_of(changed);
    if (key.number) owner.*key.number = 2.0 * (owner.*key.number) + 1.0;
    if (key.integer) owner.*key.integer += 1;
    if (key.boolean) owner.*key.boolean = !(owner.*key.boolean);
    if (key.set_choice) key.set_choice(owner, key.get_choice(owner) == 0 ? 1 : 0);
    EXPECT_NE(state_fingerprint_text(changed, 1), fingerprint) << key.path;
    ++checked;
  }
  return checked;
}

TEST(ScenarioFingerprint, KeysAddedLaterAddNoLineAtTheirDefault) {
  // So that the checkpoints written before solver.backtrack_from existed stay valid.
  Scenario s = base();
  EXPECT_EQ(state_fingerprint_text(s, 1).find("backtrack"), std::string::npos);
  s.solver.backtrack_from = 4;
  EXPECT_NE(state_fingerprint_text(s, 1).find("solver.backtrack_from = 4\n"), std::string::npos);
}

TEST(ScenarioFingerprint, EveryValueChangesIt) {
  int checked = 0;
  checked += check_fingerprint<Material>([](Scenario& s) -> Material& { return s.materials[0]; });
  checked += check_fingerprint<BeamSpec>([](Scenario& s) -> BeamSpec& { return s.beams[0]; });
  checked += check_fingerprint<ConditionSpec>([](Scenario& s) -> ConditionSpec& { return s.conditions[0]; });
  checked += check_fingerprint<StageSpec>([](Scenario& s) -> StageSpec& { return s.stages[0]; });
  checked += check_fingerprint<Keyframe>(
      [](Scenario& s) -> Keyframe& { return s.stages[0].motions[0].keyframes[0]; });
  checked += check_fingerprint<SolverSettings>([](Scenario& s) -> SolverSettings& { return s.solver; });
  checked += check_fingerprint<ContactSettings>([](Scenario& s) -> ContactSettings& { return s.contact; });
  // Scalar keys: Material 2, BeamSpec 4, ConditionSpec 2, StageSpec 6, Keyframe 1, SolverSettings 17,
  // ContactSettings 22.
  EXPECT_EQ(checked, 55);

  // Structural values, and a change in the last digit of a number.
  const Scenario original = base();
  const std::string fingerprint = state_fingerprint_text(original, 1);
  const auto differs = [&](const std::function<void(Scenario&)>& change) {
    Scenario changed = original;
    change(changed);
    return state_fingerprint_text(changed, 1) != fingerprint;
  };
  EXPECT_TRUE(differs([](Scenario& s) { s.beams[0].radius = std::nextafter(s.beams[0].radius, 1.0); }));
  EXPECT_TRUE(differs([](Scenario& s) { s.beams[0].start.z() = 1e-12; }));
  EXPECT_TRUE(differs([](Scenario& s) { s.beams[0].name = "rod"; }));
  EXPECT_TRUE(differs([](Scenario& s) { s.conditions[0].dofs[kG2z] = false; }));
  EXPECT_TRUE(differs([](Scenario& s) { s.conditions[0].node = 1; }));
  EXPECT_TRUE(differs([](Scenario& s) { s.stages[0].motions[0].keyframes[0].translation.x() = 2.0; }));
  EXPECT_TRUE(differs([](Scenario& s) { s.contact.beams = {0}; }) == false);  // all beams, resolved
  EXPECT_TRUE(differs([](Scenario& s) { s.stages[0].activate = {0}; }));
  // What does not make the state does not change it.
  EXPECT_FALSE(differs([](Scenario& s) { s.path = "elsewhere.yaml"; }));
  EXPECT_FALSE(differs([](Scenario& s) { s.output.vtk_every = 7; }));
  EXPECT_FALSE(differs([](Scenario& s) { s.conditions[0].line = 99; }));
}

TEST(ScenarioFingerprint, SameForTheFileAndTheScenarioBuiltInCode) {
  Scenario made;
  made.path = "in code";
  made.materials.push_back({"steel", 200000.0, 0.3});
  BeamSpec beam;
  beam.name = "wire";
  beam.radius = 0.1;
  beam.length = 10.0;
  beam.elements = 4;
  made.beams.push_back(beam);
  ConditionSpec fix;
  fix.name = "fix";
  fix.dofs.fill(true);
  ConditionSpec pull = fix;
  pull.name = "pull";
  pull.type = ConditionType::motion;
  pull.node = 8;
  made.conditions = {fix, pull};
  StageSpec stage;
  stage.name = "load";
  stage.steps = 2;
  stage.stabilization = 0.1;
  stage.stabilization_end = 0.01;
  stage.motions.push_back({1, {Keyframe{1.0, Vec3(1, 0, 0), Vec3::Zero()}}});
  made.stages.push_back(stage);
  made.solver.linear_solver = LinearSolverKind::umfpack;
  ContactSettings& contact = made.contact;
  contact.enabled = true;
  contact.proximity_distance = 0.3;
  contact.separation_distance = 1.2;
  contact.test_point_spacing = 0.2;
  contact.matching_length = 0.4;
  contact.element_spacing = 0.1;
  contact.penalty = 100.0;
  contact.max_penetration = 0.01;
  contact.regularization = 0.001;
  contact.friction = 0.1;
  contact.max_reversible_slip = 0.005;
  contact.normal_pass_residual = 0.01;
  EXPECT_NO_THROW(validate(made));
  EXPECT_EQ(state_fingerprint_text(made, 1), state_fingerprint_text(base(), 1));
  // The canonical text holds no echo wording: one "PATH = VALUE" line per value.
  const std::string text = state_fingerprint_text(made, 1);
  EXPECT_EQ(text.find('#'), std::string::npos);
  // Numbers in full precision: each reads back as the same double.
  const std::string key = "\nsolver.residual_tolerance = ";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_EQ(std::strtod(text.c_str() + at + key.size(), nullptr), 1e-8);
  const std::string radius = "\nbeams[0].radius = ";
  EXPECT_EQ(std::strtod(text.c_str() + text.find(radius) + radius.size(), nullptr), 0.1);
}

}  // namespace
}  // namespace nodus::scenario
