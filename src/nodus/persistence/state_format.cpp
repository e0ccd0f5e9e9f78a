#include "nodus/persistence/state_format.hpp"

#include <sstream>
#include <tuple>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "nodus/persistence/binary_codec.hpp"

namespace nodus::persistence {
namespace {

// Mirrors of the structures the format stores field by field: a field added to one of them changes its size
// (as a rule), and the build stops here until the format stores it too.
struct ParticleFields {
  int beam, element;
  double local, abscissa;
  Eigen::Vector2d transverse;
};
struct ZoneFields {
  int beam_i, beam_j;
  double a, b, c, d;
  int first_element, num_elements;
};
struct ElementFields {
  int zone;
  double zeta;
  Eigen::Vector3d intermediate;
  contact::Particle particle_i, particle_j;
  Eigen::Vector3d position_i, position_j, normal;
  double gap, parallel_weight;
};
struct ContactStateFields {
  double gap, normal_reaction;
  Eigen::Vector3d tangential, reversible;
  bool slip;
};
struct StepperFields {
  double time, step;
  Eigen::VectorXd previous;
  double previous_step;
  int cutbacks;  // not stored: 0 between steps, where every checkpoint is taken
};
struct ProgressFields {
  int stage;
  bool stage_begun;
  double stage_start_time;
  solver::StepperState stepper;
};
struct CountersFields {
  int steps, newton_iterations;
  double wall_seconds, detection_seconds, assembly_seconds, linear_solve_seconds;
  int factorizations, analyses, krylov_iterations;
};
struct ProblemFields {
  Eigen::VectorXd x;
  double time;
  contact::ContactGeometry contact;
  std::vector<double> penalty;
  std::vector<Eigen::Vector3d> reversible;
  std::vector<simulation::ContactState> contact_states;
};
struct ConditionFields {
  bool active;
  std::vector<loading::NodeVector> anchors;
  loading::Vec3 pivot;
  loading::Path<loading::Vec3> translation, rotation, force;
  loading::Path<loading::NodeVector> director_force;
  loading::Path<double> moment;
  loading::Vec3 axis;
  int director;
  std::optional<loading::AxisAngle::State> angle;
};
struct AngleFields {
  loading::Vec3 axis, b1, b2;
  double committed;
};
struct StateFields {
  simulation::RunProgress progress;
  simulation::RunCounters counters;
  double time;
  simulation::ProblemState problem;
  std::vector<loading::ConditionState> conditions;
  std::vector<int> contact_beams;
  contact::ContactGeometry contact;
  std::vector<simulation::ContactState> contact_states;
};
static_assert(sizeof(contact::Particle) == sizeof(ParticleFields), "store the new field of Particle");
static_assert(sizeof(contact::ProximityZone) == sizeof(ZoneFields), "store the new field of ProximityZone");
static_assert(sizeof(contact::ContactElement) == sizeof(ElementFields),
              "store the new field of ContactElement");
static_assert(sizeof(simulation::ContactState) == sizeof(ContactStateFields),
              "store the new field of ContactState");
static_assert(sizeof(solver::StepperState) == sizeof(StepperFields), "store the new field of StepperState");
static_assert(sizeof(simulation::RunProgress) == sizeof(ProgressFields),
              "store the new field of RunProgress");
static_assert(sizeof(simulation::RunCounters) == sizeof(CountersFields),
              "store the new field of RunCounters");
static_assert(sizeof(simulation::ProblemState) == sizeof(ProblemFields),
              "store the new field of ProblemState");
static_assert(sizeof(loading::ConditionState) == sizeof(ConditionFields),
              "store the new field of ConditionState");
static_assert(sizeof(loading::AxisAngle::State) == sizeof(AngleFields),
              "store the new field of AxisAngle::State");
static_assert(sizeof(simulation::SimulationState) == sizeof(StateFields),
              "store the new field of SimulationState");

std::uint64_t fnv1a(std::string_view bytes) {
  return scenario::fingerprint_hash(bytes);
}

// ---- the state, field by field ----

template <class Value>
void put_path(Encoder& e, const loading::Path<Value>& path) {
  e.count(path.times().size());
  for (std::size_t k = 0; k < path.times().size(); ++k) {
    e.f64(path.times()[k]);
    if constexpr (std::is_same_v<Value, double>) {
      e.f64(path.values()[k]);
    } else {
      e.matrix(path.values()[k]);
    }
  }
}

template <class Value>
loading::Path<Value> get_path(Decoder& d) {
  const std::size_t n = d.count(16);
  if (n == 0) d.damaged();
  std::vector<double> times(n);
  std::vector<Value> values(n);
  for (std::size_t k = 0; k < n; ++k) {
    times[k] = d.f64();
    if (k > 0 && !(times[k] >= times[k - 1])) d.damaged();
    if constexpr (std::is_same_v<Value, double>) {
      values[k] = d.f64();
    } else {
      values[k] = d.matrix<Value>();
    }
  }
  return loading::Path<Value>(std::move(times), std::move(values));
}

void put_particle(Encoder& e, const contact::Particle& p) {
  e.i32(p.beam);
  e.i32(p.element);
  e.f64(p.local);
  e.f64(p.abscissa);
  e.matrix(p.transverse);
}

contact::Particle get_particle(Decoder& d) {
  contact::Particle p;
  p.beam = d.i32();
  p.element = d.i32();
  p.local = d.f64();
  p.abscissa = d.f64();
  p.transverse = d.matrix<Eigen::Vector2d>();
  return p;
}

void put_geometry(Encoder& e, const contact::ContactGeometry& g) {
  e.count(g.zones.size());
  for (const contact::ProximityZone& z : g.zones) {
    e.i32(z.beam_i);
    e.i32(z.beam_j);
    e.f64(z.a);
    e.f64(z.b);
    e.f64(z.c);
    e.f64(z.d);
    e.i32(z.first_element);
    e.i32(z.num_elements);
  }
  e.count(g.elements.size());
  for (const contact::ContactElement& x : g.elements) {
    e.i32(x.zone);
    e.f64(x.zeta);
    e.matrix(x.intermediate);
    put_particle(e, x.particle_i);
    put_particle(e, x.particle_j);
    e.matrix(x.position_i);
    e.matrix(x.position_j);
    e.matrix(x.normal);
    e.f64(x.gap);
    e.f64(x.parallel_weight);
  }
}

contact::ContactGeometry get_geometry(Decoder& d) {
  contact::ContactGeometry g;
  g.zones.resize(d.count(48));
  for (contact::ProximityZone& z : g.zones) {
    z.beam_i = d.i32();
    z.beam_j = d.i32();
    z.a = d.f64();
    z.b = d.f64();
    z.c = d.f64();
    z.d = d.f64();
    z.first_element = d.i32();
    z.num_elements = d.i32();
  }
  g.elements.resize(d.count(200));
  for (contact::ContactElement& x : g.elements) {
    x.zone = d.i32();
    x.zeta = d.f64();
    x.intermediate = d.matrix<Eigen::Vector3d>();
    x.particle_i = get_particle(d);
    x.particle_j = get_particle(d);
    x.position_i = d.matrix<Eigen::Vector3d>();
    x.position_j = d.matrix<Eigen::Vector3d>();
    x.normal = d.matrix<Eigen::Vector3d>();
    x.gap = d.f64();
    x.parallel_weight = d.f64();
  }
  // The indices between zones and elements must hold (the outputs and the contact loops rely on them).
  for (const contact::ProximityZone& z : g.zones)
    if (z.first_element < 0 || z.num_elements < 0 ||
        static_cast<std::size_t>(z.first_element) + static_cast<std::size_t>(z.num_elements) >
            g.elements.size())
      d.damaged();
  for (const contact::ContactElement& x : g.elements)
    if (x.zone < 0 || static_cast<std::size_t>(x.zone) >= g.zones.size()) d.damaged();
  return g;
}

void put_contact_states(Encoder& e, const std::vector<simulation::ContactState>& states) {
  e.count(states.size());
  for (const simulation::ContactState& s : states) {
    e.f64(s.gap);
    e.f64(s.normal_reaction);
    e.matrix(s.tangential);
    e.matrix(s.reversible);
    e.boolean(s.slip);
  }
}

std::vector<simulation::ContactState> get_contact_states(Decoder& d) {
  std::vector<simulation::ContactState> states(d.count(65));
  for (simulation::ContactState& s : states) {
    s.gap = d.f64();
    s.normal_reaction = d.f64();
    s.tangential = d.matrix<Eigen::Vector3d>();
    s.reversible = d.matrix<Eigen::Vector3d>();
    s.slip = d.boolean();
  }
  return states;
}

void put_condition(Encoder& e, const loading::ConditionState& c) {
  e.boolean(c.active);
  e.count(c.anchors.size());
  for (const loading::NodeVector& a : c.anchors) e.matrix(a);
  e.matrix(c.pivot);
  put_path(e, c.translation);
  put_path(e, c.rotation);
  put_path(e, c.force);
  put_path(e, c.director_force);
  put_path(e, c.moment);
  e.matrix(c.axis);
  e.i32(c.director);
  e.boolean(c.angle.has_value());
  if (c.angle) {
    e.matrix(c.angle->axis);
    e.matrix(c.angle->b1);
    e.matrix(c.angle->b2);
    e.f64(c.angle->committed);
  }
}

loading::ConditionState get_condition(Decoder& d) {
  loading::ConditionState c;
  c.active = d.boolean();
  c.anchors.resize(d.count(72));
  for (loading::NodeVector& a : c.anchors) a = d.matrix<loading::NodeVector>();
  c.pivot = d.matrix<loading::Vec3>();
  c.translation = get_path<loading::Vec3>(d);
  c.rotation = get_path<loading::Vec3>(d);
  c.force = get_path<loading::Vec3>(d);
  c.director_force = get_path<loading::NodeVector>(d);
  c.moment = get_path<double>(d);
  c.axis = d.matrix<loading::Vec3>();
  c.director = d.i32();
  if (c.director != 0 && c.director != 1) d.damaged();
  if (d.boolean()) {
    loading::AxisAngle::State a;
    a.axis = d.matrix<loading::Vec3>();
    a.b1 = d.matrix<loading::Vec3>();
    a.b2 = d.matrix<loading::Vec3>();
    a.committed = d.f64();
    c.angle = a;
  }
  return c;
}

int stages_run(const simulation::RunProgress& progress) {
  return progress.stage + (progress.stage_begun ? 1 : 0);
}

/// The first line where two texts differ, for the message of a foreign checkpoint.
std::string first_difference(const std::string& here, const std::string& there) {
  std::istringstream a(here), b(there);
  std::string line_a, line_b;
  for (int line = 1;; ++line) {
    const bool has_a = static_cast<bool>(std::getline(a, line_a));
    const bool has_b = static_cast<bool>(std::getline(b, line_b));
    if (!has_a && !has_b) return "no difference in the settings, but a different hash";
    if (!has_a) line_a = "(nothing)";
    if (!has_b) line_b = "(nothing)";
    if (!has_a || !has_b || line_a != line_b) {
      const auto trim = [](std::string s) {
        s.erase(0, s.find_first_not_of(' '));
        return s.size() > 70 ? s.substr(0, 67) + "..." : s;
      };
      return fmt::format("line {} of the fingerprint is '{}' in the checkpoint, '{}' in the scenario", line,
                         trim(line_b), trim(line_a));
    }
  }
}

/// Reads the magic, version and header.
CheckpointInfo read_header(Decoder& d, const std::filesystem::path& path, std::uint64_t& hash,
                           std::string& fingerprint) {
  std::string magic;
  for (std::size_t k = 0; k < kCheckpointMagic.size(); ++k) {
    std::uint8_t c = 0;
    try {
      c = d.u8();
    } catch (const scenario::ScenarioError&) {
      break;
    }
    magic.push_back(static_cast<char>(c));
  }
  if (magic != kCheckpointMagic)
    damaged_file(path, "a nodus state file (starting with NODUS-STATE)", "a file of another kind");
  const std::uint32_t version = d.u32();
  if (version != kCheckpointVersion)
    bad_file(path, fmt::format("format version {}", kCheckpointVersion), fmt::format("version {}", version));
  hash = d.u64();
  fingerprint = d.text();
  CheckpointInfo info;
  info.path = path;
  info.steps = d.i32();
  info.stage = d.i32();
  info.stage_begun = d.boolean();
  info.time = d.f64();
  if (info.steps < 0 || info.stage < 0) d.damaged();
  return info;
}

}  // namespace

std::string encode_checkpoint(const scenario::Scenario& scenario, const simulation::SimulationState& state) {
  const simulation::RunProgress& progress = state.progress;
  const std::string fingerprint = scenario::state_fingerprint_text(scenario, stages_run(progress));
  Encoder e;
  e.raw(kCheckpointMagic);
  e.u32(kCheckpointVersion);
  // header
  e.u64(scenario::fingerprint_hash(fingerprint));
  e.text(fingerprint);
  e.i32(state.counters.steps);
  e.i32(progress.stage);
  e.boolean(progress.stage_begun);
  e.f64(state.time);
  // progress
  e.f64(progress.stage_start_time);
  e.f64(progress.stepper.time);
  e.f64(progress.stepper.step);
  e.f64(progress.stepper.previous_step);
  e.vector(progress.stepper.previous);
  // counters
  e.i32(state.counters.newton_iterations);
  e.f64(state.counters.wall_seconds);
  e.f64(state.counters.detection_seconds);
  e.f64(state.counters.assembly_seconds);
  e.f64(state.counters.linear_solve_seconds);
  e.i32(state.counters.factorizations);
  e.i32(state.counters.analyses);
  e.i32(state.counters.krylov_iterations);
  // the equilibrium problem
  e.vector(state.problem.x);
  e.f64(state.problem.time);
  put_geometry(e, state.problem.contact);
  e.count(state.problem.penalty.size());
  for (const double k : state.problem.penalty) e.f64(k);
  e.count(state.problem.reversible.size());
  for (const Eigen::Vector3d& g : state.problem.reversible) e.matrix(g);
  put_contact_states(e, state.problem.contact_states);
  // the conditions
  e.count(state.conditions.size());
  for (const loading::ConditionState& c : state.conditions) put_condition(e, c);
  // contact as the simulation sees it
  e.count(state.contact_beams.size());
  for (const int b : state.contact_beams) e.i32(b);
  put_geometry(e, state.contact);
  put_contact_states(e, state.contact_states);
  e.u64(fnv1a(e.bytes()));
  return e.bytes();
}

simulation::SimulationState decode_checkpoint(std::string_view bytes, const scenario::Scenario& scenario,
                                              const std::filesystem::path& path) {
  Decoder d(bytes, path);
  std::uint64_t hash = 0;
  std::string fingerprint;
  const CheckpointInfo info = read_header(d, path, hash, fingerprint);
  if (bytes.size() < 8) d.damaged();
  Decoder tail(bytes.substr(bytes.size() - 8), path);
  if (tail.u64() != fnv1a(bytes.substr(0, bytes.size() - 8))) d.damaged();

  simulation::SimulationState state;
  state.progress.stage = info.stage;
  state.progress.stage_begun = info.stage_begun;
  const int num_stages = static_cast<int>(scenario.stages.size());
  const int run = stages_run(state.progress);
  if (run > num_stages || (!info.stage_begun && info.stage > num_stages))
    bad_file(path, fmt::format("a state of this scenario ({} stages)", num_stages),
             fmt::format("a state after {} stages", run));
  const std::string expected = scenario::state_fingerprint_text(scenario, run);
  if (hash != scenario::fingerprint_hash(expected) || fingerprint != expected)
    bad_file(
        path,
        fmt::format("a state of this scenario (fingerprint {:016x})", scenario::fingerprint_hash(expected)),
        fmt::format("one of another scenario (fingerprint {:016x}; {})", hash,
                    first_difference(expected, fingerprint)));

  state.counters.steps = info.steps;
  state.time = info.time;
  state.progress.stage_start_time = d.f64();
  state.progress.stepper.time = d.f64();
  state.progress.stepper.step = d.f64();
  state.progress.stepper.previous_step = d.f64();
  state.progress.stepper.previous = d.vector();
  state.counters.newton_iterations = d.i32();
  state.counters.wall_seconds = d.f64();
  state.counters.detection_seconds = d.f64();
  state.counters.assembly_seconds = d.f64();
  state.counters.linear_solve_seconds = d.f64();
  state.counters.factorizations = d.i32();
  state.counters.analyses = d.i32();
  state.counters.krylov_iterations = d.i32();
  state.problem.x = d.vector();
  state.problem.time = d.f64();
  state.problem.contact = get_geometry(d);
  state.problem.penalty.resize(d.count(8));
  for (double& k : state.problem.penalty) k = d.f64();
  state.problem.reversible.resize(d.count(24));
  for (Eigen::Vector3d& g : state.problem.reversible) g = d.matrix<Eigen::Vector3d>();
  state.problem.contact_states = get_contact_states(d);
  state.conditions.resize(d.count(1));
  for (loading::ConditionState& c : state.conditions) c = get_condition(d);
  state.contact_beams.resize(d.count(4));
  for (int& b : state.contact_beams) b = d.i32();
  state.contact = get_geometry(d);
  state.contact_states = get_contact_states(d);
  if (d.position() + 8 != bytes.size()) d.damaged();
  return state;
}

CheckpointInfo read_checkpoint_header(std::string_view bytes, const std::filesystem::path& path) {
  Decoder d(bytes, path);
  std::uint64_t hash = 0;
  std::string fingerprint;
  return read_header(d, path, hash, fingerprint);
}

}  // namespace nodus::persistence
