#include "nodus/simulation/simulation.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/beam/beam_element.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/linear_solver_choice.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/load_stepping.hpp"
#include "nodus/solver/newton.hpp"
#include "nodus/solver/petsc_solver.hpp"

namespace nodus::simulation {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
/// A rigid body's six unknowns by the words of conditions[].dofs (scenario::BodyDof order).
constexpr const char* kBodyDofNames[] = {"x", "y", "z", "rx", "ry", "rz"};

model::Model build_model(const scenario::Scenario& s) {
  model::Model model(s.solver.gauss_points, s.solver.fold_stiffness, s.solver.fold_barrier);
  for (const scenario::BeamSpec& b : s.beams) {
    const scenario::Material& m = s.materials.at(static_cast<std::size_t>(b.material));
    model.add_beam({b.name, b.length, b.radius, b.elements, b.start, b.direction, b.director1,
                    beam::ElasticConstants{m.young_modulus, m.poisson_ratio}, b.bending_factor});
  }
  for (const scenario::BodySpec& b : s.bodies) {
    std::vector<int> nodes;
    for (const scenario::SectionRef& section : b.sections)
      nodes.push_back(model.beam(section.beam).node(section.node));
    model.add_body(b.name, std::move(nodes));
  }
  return model;
}

/// The fixed axis of a load's moment: the direction of its first nonzero value (the reader checked that all
/// values share it, the branches' too, and resolved it).
loading::Vec3 moment_axis(const scenario::Scenario& s, int c) {
  if (s.conditions[static_cast<std::size_t>(c)].moment_axis)
    return *s.conditions[static_cast<std::size_t>(c)].moment_axis;
  if (s.conditions[static_cast<std::size_t>(c)].moment.norm() > 0)
    return s.conditions[static_cast<std::size_t>(c)].moment.normalized();
  for (const scenario::StageSpec& stage : s.stages)
    for (const scenario::LoadTarget& t : stage.loads)
      if (t.condition == c && t.moment.norm() > 0) return t.moment.normalized();
  return loading::Vec3::UnitZ();
}

loading::Conditions build_conditions(const scenario::Scenario& s, const model::Model& model) {
  loading::Conditions conditions;
  for (int c = 0; c < static_cast<int>(s.conditions.size()); ++c) {
    const scenario::ConditionSpec& spec = s.conditions[static_cast<std::size_t>(c)];
    if (!spec.bodies.empty()) {
      std::vector<loading::BodyRef> bodies;
      for (int b : spec.bodies) bodies.push_back({model.body(b).block, model.body_dof(b)});
      if (spec.type == scenario::ConditionType::load) {
        const loading::Vec3 axis = moment_axis(s, c);
        conditions.add_body_load(spec.name, bodies.front(), spec.force, axis, spec.moment.dot(axis));
      } else if (spec.type == scenario::ConditionType::bind) {
        loading::DofMask mask{};
        for (std::size_t d = 0; d < 3; ++d) mask[d] = spec.body_dofs[d];
        conditions.add_body_bind(spec.name, std::move(bodies), mask, 0.0);  // stiffness: the bodies' penalty
      } else {
        loading::DofMask mask{};
        for (std::size_t d = 0; d < spec.body_dofs.size(); ++d) mask[d] = spec.body_dofs[d];
        conditions.add_body_motion(spec.name, std::move(bodies), mask, spec.pivot);
      }
      continue;
    }
    const beam::Beam& beam = model.beam(spec.beam);
    if (spec.type == scenario::ConditionType::rigid) {
      std::vector<int> nodes;
      for (int n = 0; n < beam.num_nodes(); ++n) nodes.push_back(beam.node(n));
      conditions.add_rigid(spec.name, std::move(nodes), spec.pivot);
      continue;
    }
    const int node = beam.node(spec.node);
    if (spec.type == scenario::ConditionType::load) {
      const loading::Vec3 axis = moment_axis(s, c);
      conditions.add_load(spec.name, node, spec.force, axis, spec.moment.dot(axis));
    } else {
      conditions.add_motion(spec.name, node, spec.dofs, spec.pivot);
    }
  }
  return conditions;
}

/// Applies the activations and releases of `stages` to `active` and checks after each stage start that no two
/// conditions active together prescribe the same unknown. `where` names the list in messages ("" or " of
/// branch 'B'").
void check_stages(const scenario::Scenario& s, const model::Model& model,
                  const std::vector<scenario::StageSpec>& stages, std::vector<bool>& active,
                  const std::string& where) {
  for (const scenario::StageSpec& stage : stages) {
    for (int c : stage.release) active[static_cast<std::size_t>(c)] = false;
    for (int c : stage.activate) active[static_cast<std::size_t>(c)] = true;
    std::vector<int> owner(static_cast<std::size_t>(model.num_dofs()), -1);
    for (std::size_t c = 0; c < s.conditions.size(); ++c) {
      const scenario::ConditionSpec& spec = s.conditions[c];
      if (!active[c] || spec.type == scenario::ConditionType::load ||
          spec.type == scenario::ConditionType::bind)
        continue;
      if (!spec.bodies.empty()) {
        for (int b : spec.bodies)
          for (int d = 0; d < 6; ++d) {
            if (!spec.body_dofs[static_cast<std::size_t>(d)]) continue;
            int& o = owner[static_cast<std::size_t>(model.body_dof(b) + d)];
            if (o >= 0)
              throw scenario::ScenarioError(fmt::format(
                  "{}:{}: conditions[{}].dofs: expected no unknown prescribed by two active "
                  "conditions, got '{}' "
                  "and '{}' both prescribing unknown {} of body '{}' in stage '{}'{}",
                  s.path, spec.line, c, s.conditions[static_cast<std::size_t>(o)].name, spec.name,
                  kBodyDofNames[d], s.bodies[static_cast<std::size_t>(b)].name, stage.name, where));
            o = static_cast<int>(c);
          }
        continue;
      }
      const beam::Beam& beam = model.beam(spec.beam);
      const bool rigid = spec.type == scenario::ConditionType::rigid;
      for (int local = rigid ? 0 : spec.node; local <= (rigid ? beam.num_nodes() - 1 : spec.node); ++local)
        for (int d = 0; d < beam::kNodeDofs; ++d) {
          if (!spec.dofs[static_cast<std::size_t>(d)]) continue;
          int& o = owner[static_cast<std::size_t>(model.node_dof(beam.node(local)) + d)];
          if (o >= 0)
            throw scenario::ScenarioError(fmt::format(
                "{}:{}: conditions[{}]{}: expected no unknown prescribed by two active conditions, got '{}' "
                "and '{}' both prescribing unknown {} of node {} of beam '{}' in stage '{}'{}",
                s.path, spec.line, c, rigid ? "" : ".dofs", s.conditions[static_cast<std::size_t>(o)].name,
                spec.name, d, local, s.beams[static_cast<std::size_t>(spec.beam)].name, stage.name, where));
          o = static_cast<int>(c);
        }
    }
  }
}

/// Checks, before anything runs, that no two conditions active together prescribe the same unknown, in the
/// stages and in each branch (whose conditions start as they are at the end of its `from` stage).
void check_activation(const scenario::Scenario& s, const model::Model& model) {
  std::vector<bool> initial(s.conditions.size());
  for (std::size_t c = 0; c < s.conditions.size(); ++c) initial[c] = s.conditions[c].initially_active;
  std::vector<bool> active = initial;
  check_stages(s, model, s.stages, active, "");
  for (const scenario::BranchSpec& branch : s.branches) {
    active = initial;
    const auto from = s.stages.begin() + branch.from + 1;
    check_stages(s, model, {s.stages.begin(), from}, active, "");
    check_stages(s, model, branch.stages, active, fmt::format(" of branch '{}'", branch.name));
  }
}

contact::DetectionParameters resolve_detection(const scenario::Scenario& s, const model::Model& model) {
  const scenario::ContactSettings& c = s.contact;
  contact::DetectionParameters given{c.proximity_distance, c.separation_distance, c.test_point_spacing,
                                     c.matching_length,    c.element_spacing,     c.self_contact};
  given.pairing = c.section_pairing;
  try {
    return contact::resolve_parameters(given, model, c.beams);
  } catch (const std::invalid_argument& e) {
    throw scenario::ScenarioError(fmt::format("{}: {}", s.path, e.what()));
  }
}

/// The contact laws with their defaults resolved (docs/contact.md): R and E the smallest radius and Young's
/// modulus of the contact beams.
ContactLawSettings resolve_laws(const scenario::Scenario& s) {
  const scenario::ContactSettings& c = s.contact;
  double radius = INFINITY, young = INFINITY;
  for (int b = 0; b < static_cast<int>(s.beams.size()); ++b) {
    if (!c.beams.empty() && std::find(c.beams.begin(), c.beams.end(), b) == c.beams.end()) continue;
    const scenario::BeamSpec& beam = s.beams[static_cast<std::size_t>(b)];
    radius = std::min(radius, beam.radius);
    young = std::min(young, s.materials[static_cast<std::size_t>(beam.material)].young_modulus);
  }
  ContactLawSettings laws;
  laws.max_penetration = c.max_penetration > 0.0 ? c.max_penetration : 0.02 * radius;
  laws.regularization = c.regularization > 0.0 ? c.regularization : 0.1 * laws.max_penetration;
  laws.penalty = c.penalty > 0.0 ? c.penalty : young * radius;
  // contact.friction_pairs: a coefficient per pair of beams, where an entry makes one differ.
  const int num_beams = static_cast<int>(s.beams.size());
  bool any_friction = c.friction > 0.0;
  if (!c.friction_pairs.empty()) {
    laws.pair_friction.resize(static_cast<std::size_t>(num_beams * num_beams));
    for (int i = 0; i < num_beams; ++i)
      for (int j = 0; j < num_beams; ++j) {
        const double mu = c.friction_between(i, j);
        laws.pair_friction[static_cast<std::size_t>(i * num_beams + j)] = mu;
        any_friction = any_friction || mu > 0.0;
      }
  }
  if (any_friction)
    laws.friction = contact::FrictionLaw{
        c.friction, c.max_reversible_slip > 0.0 ? c.max_reversible_slip : 0.5 * laws.max_penetration};
  // The friction tangent with R_N varying is not symmetric: the reader accepts it with LU (umfpack, mumps,
  // klu) only.
  laws.friction_normal_coupling = c.friction_tangent == scenario::FrictionTangent::varying;
  laws.facing_particles = c.facing_particles;
  laws.centre_facing = c.centre_facing;
  laws.max_detections = c.max_detections;
  laws.normals_inside_newton = c.normal_updates == scenario::NormalUpdates::inside_newton;
  // Not symmetric either: LU only, as above.
  laws.linearized_normals = c.normal_updates == scenario::NormalUpdates::linearized;
  laws.max_normal_iterations = c.max_normal_iterations;
  laws.normal_tolerance = c.normal_tolerance;
  laws.normal_pass_residual = c.normal_pass_residual;
  laws.crossing_guard = c.crossing_guard;
  return laws;
}

/// `scenario` with solver.linear_solver: auto resolved (a scenario built in code; a file's is resolved when
/// read).
scenario::Scenario with_linear_solver_chosen(scenario::Scenario scenario) {
  scenario::choose_linear_solver(scenario);
  return scenario;
}

/// `symmetric`: whether the tangent is (everything but the varying friction tangent and the linearized
/// normals); MUMPS then factorises one triangle by LDL^T, and the whole matrix by LU otherwise.
solver::LinearSolverKind linear_solver_kind(scenario::LinearSolverKind kind, bool symmetric) {
  switch (kind) {
    case scenario::LinearSolverKind::cholmod:
      return solver::LinearSolverKind::cholmod;
    case scenario::LinearSolverKind::umfpack:
      return solver::LinearSolverKind::umfpack;
    case scenario::LinearSolverKind::mumps:
      return symmetric ? solver::LinearSolverKind::mumps_ldlt : solver::LinearSolverKind::mumps_lu;
    case scenario::LinearSolverKind::klu:
      return solver::LinearSolverKind::klu;
    case scenario::LinearSolverKind::petsc:
      break;  // made by make_petsc_solver
    case scenario::LinearSolverKind::automatic:
      assert(false && "solver.linear_solver: auto is resolved when the Simulation is made");
      break;
  }
  return solver::LinearSolverKind::cholmod;
}

}  // namespace

Simulation::Simulation(scenario::Scenario scenario)
    : scenario_(with_linear_solver_chosen(std::move(scenario))),
      model_(build_model(scenario_)),
      conditions_(build_conditions(scenario_, model_)) {
  check_activation(scenario_, model_);
  for (int c = 0; c < conditions_.size(); ++c)
    if (scenario_.conditions[static_cast<std::size_t>(c)].initially_active)
      conditions_.activate(c, 0.0, model_.reference());
  problem_ = std::make_unique<EquilibriumProblem>(
      model_, conditions_,
      Tolerances{scenario_.solver.residual_tolerance, scenario_.solver.increment_tolerance},
      scenario_.solver.director_update);
  if (!model_.bodies().empty()) {
    std::vector<double> penalties, ties;
    for (const scenario::BodySpec& b : scenario_.bodies) {
      penalties.push_back(b.penalty);
      ties.push_back(b.tie);
    }
    averaged_ = static_cast<model::AveragedConditionsTerm*>(
        &problem_->add_term(std::make_unique<model::AveragedConditionsTerm>(model_, penalties, ties)));
    // A bind's stiffness is the mean of its bodies' penalty stiffness k (docs/bodies.md).
    for (int c = 0; c < conditions_.size(); ++c) {
      const scenario::ConditionSpec& spec = scenario_.conditions[static_cast<std::size_t>(c)];
      if (spec.type != scenario::ConditionType::bind) continue;
      double k = 0.0;
      for (int b : spec.bodies) k += averaged_->penalty(b) / static_cast<double>(spec.bodies.size());
      conditions_.set_bind_stiffness(c, k);
    }
  }
  if (scenario_.contact.enabled) {
    contact_enabled_ = true;
    contact_beams_ = scenario_.contact.beams;
    if (contact_beams_.empty())
      for (int b = 0; b < static_cast<int>(model_.beams().size()); ++b) contact_beams_.push_back(b);
    detection_ = resolve_detection(scenario_, model_);
    contact_forces_ = scenario_.contact.forces;
    laws_ = resolve_laws(scenario_);
    detect_contact();
    counters_.detection_seconds = detection_seconds_;
  }
}

void Simulation::detect_contact() {
  if (!contact_enabled_) return;
  const auto start = std::chrono::steady_clock::now();
  contact_ = contact_beams_.empty() ? contact::ContactGeometry{}
                                    : contact::detect(model_, problem_->committed_state(), detection_,
                                                      contact_beams_, &contact_);
  detection_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Simulation::~Simulation() = default;

const std::vector<ContactState>& Simulation::contact_states() const {
  return contact_states_;
}

const Eigen::VectorXd& Simulation::state() const {
  return problem_->committed_state();
}

double Simulation::stage_end_time(int stage) const {
  return scenario::stage_end_time(scenario_, stage);
}

SimulationState Simulation::snapshot() const {
  SimulationState state;
  state.progress = progress_;
  state.counters = counters_;
  state.time = time_;
  state.problem = problem_->saved_state();
  for (int c = 0; c < conditions_.size(); ++c) state.conditions.push_back(conditions_.state(c));
  state.contact_beams = contact_beams_;
  state.contact = contact_;
  state.contact_states = contact_states_;
  return state;
}

void Simulation::restore(SimulationState state, StartKind kind) {
  const int num_stages = static_cast<int>(scenario_.stages.size());
  if (state.progress.stage < 0 || state.progress.stage > num_stages ||
      (state.progress.stage_begun && state.progress.stage == num_stages))
    throw std::invalid_argument(
        fmt::format("restore: stage {} of a scenario with {} stages", state.progress.stage, num_stages));
  if (static_cast<int>(state.conditions.size()) != conditions_.size())
    throw std::invalid_argument(fmt::format("restore: {} conditions saved, the scenario has {}",
                                            state.conditions.size(), conditions_.size()));
  for (int b : state.contact_beams)
    if (b < 0 || b >= static_cast<int>(model_.beams().size()))
      throw std::invalid_argument(fmt::format("restore: no beam {} in contact", b));
  for (int c = 0; c < conditions_.size(); ++c)
    conditions_.restore(c, state.conditions[static_cast<std::size_t>(c)]);
  problem_->restore_state(std::move(state.problem));
  progress_ = std::move(state.progress);
  counters_ = state.counters;
  time_ = state.time;
  contact_beams_ = std::move(state.contact_beams);
  contact_ = std::move(state.contact);
  contact_states_ = std::move(state.contact_states);
  start_kind_ = kind;
}

RunSummary Simulation::run(const std::vector<StepObserver*>& observers, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const RunCounters base = counters_;  // what a restored state brought
  const double detection_before = detection_seconds_;
  RunSummary summary;
  summary.steps = counters_.steps;
  summary.newton_iterations = counters_.newton_iterations;
  const bool symmetric = !laws_.friction_normal_coupling && !laws_.linearized_normals;
  const bool petsc = scenario_.solver.linear_solver == scenario::LinearSolverKind::petsc;
  // On several ranks the petsc solver takes each rank's own rows, so the evaluation is distributed, with the
  // kept factor too: its GMRES runs in PETSc on the distributed matrix (docs/parallel.md).
  problem_->distribute(petsc);
  // A stage may take its own serial solver (stages[].linear_solver): a new one at each change, as a run
  // resumed in that stage starts with, so that the resumed run repeats the one never stopped.
  scenario::LinearSolverKind linear_kind = scenario_.solver.linear_solver;
  auto linear = petsc ? solver::make_petsc_solver(symmetric, scenario_.solver.petsc_options,
                                                  [this] { return problem_->local_rows(); })
                      : solver::make_linear_solver(linear_solver_kind(linear_kind, symmetric));
  solver::NewtonSettings newton_settings;
  newton_settings.max_iterations = scenario_.solver.max_newton_iterations;
  newton_settings.stagnation_iterations = scenario_.solver.stagnation_iterations;
  newton_settings.progress_window = scenario_.solver.progress_window;
  newton_settings.progress_ratio = scenario_.solver.progress_ratio;
  newton_settings.line_search = scenario_.solver.line_search;
  newton_settings.backtrack_from = scenario_.solver.backtrack_from;
  newton_settings.reuse_factor = scenario_.solver.reuse_factor;
  newton_settings.krylov_iterations = scenario_.solver.krylov_iterations;
  newton_settings.cancel = options.cancel;
  solver::NewtonSolver newton(*linear, newton_settings);
  std::optional<ContactLoops> loops;
  if (contact_enabled_ && contact_forces_)
    loops.emplace(model_, *problem_, newton, detection_, contact_beams_, laws_);
  // A converged state in which a section has turned into the orientation barrier (det[g1, g2, r'] below its
  // threshold 1/2: the axis shortened to half its length or sheared by 60 degrees) is no state of the beam
  // model (docs/model.md); the step is cut back. In the knot pulled at 3.6 N, with `particles: facing`, a
  // step of 1e-10 s of load time converged so, with 16,500 N of contact force and 3,200 N of drag against a
  // pull of 3.6 N, and the run went on from it.
  // The fold check of the converged state, which the step's record reports once the step is accepted.
  model::FoldCheck folds;
  const solver::StepSolver solve_step = [&](solver::SteppedProblem& p) {
    // The changes of regime of the contact elements that steps.csv reports are those of this attempt: a
    // failed one before a cutback does not count into the step.
    problem_->contact().reset_regime_changes();
    // The last attempt a step is allowed gets Newton's whole budget: giving up early there would end the run
    // (solver.progress_window; docs/performance.md, "Failing sooner").
    newton.set_progress_window(
        progress_.stepper.cutbacks < scenario_.solver.max_cutbacks ? scenario_.solver.progress_window : 0);
    solver::NewtonReport report = loops ? loops->solve() : newton.solve(p);
    if (report.converged) {
      folds = model_.fold_check(problem_->state());
      if (model_.fold_barrier() > 0.0 && folds.min_orientation < beam::kOrientationThreshold) {
        report.converged = false;
        report.failure = fmt::format(
            "a section of element {} turned into the orientation barrier (det[g1, g2, r'] = {:.6g}, below "
            "{:g})",
            folds.orientation_element, folds.min_orientation, beam::kOrientationThreshold);
      }
    }
    // A converged step in which two axes passed through each other: the knot pulled at 3.5 N went from a
    // trefoil to an unknot within one step of 61 Newton iterations, to a state where the strands lie apart
    // and no contact element or clearance sees anything wrong (docs/contact.md, "The crossing guard").
    if (report.converged && loops)
      if (const std::optional<contact::Crossing> c = loops->crossing()) {
        report.converged = false;
        report.failure = fmt::format(
            "the axes of beams '{}' at s = {:.6g} mm and '{}' at s = {:.6g} mm passed through each other at "
            "{:.3g} of the step",
            model_.beam(c->beam_i).name(), c->s_i, model_.beam(c->beam_j).name(), c->s_j, c->instant);
      }
    return report;
  };
  // The counters of the run so far: those restored plus this call's.
  const auto update_counters = [&] {
    counters_.steps = summary.steps;
    counters_.newton_iterations = summary.newton_iterations;
    counters_.wall_seconds =
        base.wall_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    counters_.detection_seconds = base.detection_seconds + (detection_seconds_ - detection_before) +
                                  (loops ? loops->detection_seconds() : 0.0);
    counters_.assembly_seconds = base.assembly_seconds + newton.timings().evaluation;
    counters_.linear_solve_seconds = base.linear_solve_seconds + newton.timings().linear_solve;
    counters_.factorizations = base.factorizations + newton.timings().factorizations;
    counters_.analyses = base.analyses + newton.timings().analyses;
    counters_.krylov_iterations = base.krylov_iterations + newton.timings().krylov_iterations;
  };
  for (StepObserver* o : observers) o->on_start(*this);
  // Each solver once, with what it says of itself last (CHOLMOD names the MUMPS it fell back to, if it did).
  std::vector<std::pair<std::string, std::string>> solvers_used;
  const auto note_linear_solver = [&solvers_used](const solver::LinearSolver& used) {
    const auto same = [&used](const auto& entry) { return entry.first == used.name(); };
    const auto at = std::find_if(solvers_used.begin(), solvers_used.end(), same);
    if (at == solvers_used.end())
      solvers_used.emplace_back(used.name(), used.package());
    else
      at->second = used.package();
  };

  for (int s = progress_.stage; s < static_cast<int>(scenario_.stages.size()); ++s) {
    const scenario::StageSpec& stage = scenario_.stages[static_cast<std::size_t>(s)];
    const solver::StepControl control{stage.duration / stage.steps, scenario_.solver.max_cutbacks,
                                      scenario_.solver.easy_iterations};
    if (const scenario::LinearSolverKind kind = scenario::stage_linear_solver(stage, scenario_.solver);
        !petsc && kind != linear_kind) {
      note_linear_solver(*linear);  // what it says of itself at the end of its stages
      auto next = solver::make_linear_solver(linear_solver_kind(kind, symmetric));
      newton.set_linear_solver(*next);
      linear = std::move(next);
      linear_kind = kind;
    }
    linear_solver_name_ = linear->name();
    note_linear_solver(*linear);
    if (!progress_.stage_begun) {
      const double t0 = time_, t1 = time_ + stage.duration;
      if (!stage.release.empty()) {
        Eigen::VectorXd residual;
        problem_->restore();  // evaluate the support forces at the committed state
        problem_->evaluate(residual, false);
        for (int c : stage.release) conditions_.release(c, t0, problem_->full_residual(), t1);
      }
      for (int c : stage.activate) conditions_.activate(c, t0, problem_->committed_state());
      if (!stage.contact_off.empty() || !stage.contact_on.empty()) {
        for (int b : stage.contact_off) std::erase(contact_beams_, b);
        for (int b : stage.contact_on)
          if (std::find(contact_beams_.begin(), contact_beams_.end(), b) == contact_beams_.end())
            contact_beams_.push_back(b);
        std::sort(contact_beams_.begin(), contact_beams_.end());
        if (loops) loops->set_beams(contact_beams_);
      }
      conditions_.hold_until(t0);
      for (const scenario::MotionTarget& m : stage.motions)
        for (const scenario::Keyframe& k : m.keyframes)
          conditions_.add_motion_keyframe(m.condition, t0 + k.at * stage.duration, k.translation,
                                          kDegree * k.rotation);
      for (const scenario::LoadTarget& l : stage.loads) {
        const int c = l.condition;
        conditions_.add_load_keyframe(c, t1, l.force, l.moment.dot(moment_axis(scenario_, c)));
      }
      try {
        problem_->update_free_set();
      } catch (const std::exception& e) {
        summary.failure = "stage '" + stage.name + "': " + e.what();
        break;
      }
      progress_.stage = s;
      progress_.stage_begun = true;
      progress_.stage_start_time = t0;
      progress_.stepper = solver::start_stepping(t0, t1, control);
      newton.reanalyze();
      // Rank 0 alone logs, but a distributed evaluation needs every rank.
      if (parallel::root_value(spdlog::should_log(spdlog::level::debug))) {
        Eigen::VectorXd residual;
        problem_->set_time(t0);
        problem_->evaluate(residual, false);
        spdlog::debug("stage '{}' starts with |R| = {:.3e} over {} free unknowns", stage.name,
                      residual.norm(), residual.size());
      }
    }
    const double t1 = progress_.stage_start_time + stage.duration;
    problem_->set_stabilization(
        {progress_.stage_start_time, t1, stage.stabilization, stage.stabilization_end});
    newton.set_line_search(stage.line_search == scenario::StageSwitch::solver
                               ? scenario_.solver.line_search
                               : stage.line_search == scenario::StageSwitch::on);
    // A stage's own particles (stages[].particles), also when a run resumes inside the stage.
    if (loops) {
      const auto [facing, centres] = scenario::stage_particles(stage, scenario_.contact);
      loops->set_particles(facing, centres);
    }
    bool warned_capped = false;  // a step of this stage ended a contact loop at its cap (warned once)
    for (StepObserver* o : observers) o->on_stage(*this, s);

    const solver::AdvanceResult result = solver::advance(
        *problem_, solve_step, t1, control, progress_.stepper, [&](const solver::StepResult& r) {
          time_ = r.time;
          StepRecord record;
          record.step = ++summary.steps;
          record.stage = s;
          record.time = r.time;
          record.newton_iterations = r.newton.iterations;
          record.cutbacks = r.cutbacks;
          record.residual = r.newton.residual;
          record.residual_tolerance = r.newton.residual_tolerance;
          record.increment = r.newton.increment;
          record.ends_stage = r.time == t1;
          record.step_size = r.step;
          record.cutback_causes = r.cutback_causes;
          summary.newton_iterations += r.newton.iterations;
          ++summary.new_steps;
          if (loops) {
            contact_ = problem_->contact_geometry();
            contact_states_ = problem_->contact_states();  // of the committed state
            const ContactStepStats& c = loops->stats();
            record.detections = c.detections;
            record.normal_iterations = c.normal_iterations;
            record.penetration_ratio = c.penetration_ratio;
            record.normal_force = c.normal_force;
            record.tangential_force = c.tangential_force;
            const contact::Clearance clearance = loops->clearance();
            record.min_clearance = clearance.value;
            if (clearance.beam_i >= 0)
              spdlog::debug(
                  "smallest clearance {:.4g} mm, between beams '{}' at s = {:.6g} mm and '{}' at s = {:.6g} "
                  "mm",
                  clearance.value, model_.beam(clearance.beam_i).name(), clearance.s_i,
                  model_.beam(clearance.beam_j).name(), clearance.s_j);
            record.slipping = c.slipping;
            record.regime_changes = problem_->contact().regime_changes();
            record.loops_converged = c.loops_converged();
            if (!record.loops_converged && !warned_capped) {
              warned_capped = true;
              const std::string loop2 = fmt::format(
                  "loop 2 (detections) stopped at contact.max_detections = {} before meeting its criterion",
                  laws_.max_detections);
              const std::string loop3 = fmt::format(
                  "loop 3 (normal directions) stopped at contact.max_normal_iterations = {} before meeting "
                  "its "
                  "criterion",
                  laws_.max_normal_iterations);
              const std::string capped = c.detections_capped && c.normals_capped ? loop2 + ", and " + loop3
                                         : c.detections_capped                   ? loop2
                                                                                 : loop3;
              spdlog::warn(
                  "stage '{}', step {}: contact {} (steps.csv: loops_converged = 0; not repeated for later "
                  "steps "
                  "of this stage)",
                  stage.name, record.step, capped);
            }
          } else {
            detect_contact();
          }
          record.stabilization_force = problem_->stabilization_force();
          record.min_orientation = folds.min_orientation;
          record.min_chord = folds.min_chord;
          record.zones = static_cast<int>(contact_.zones.size());
          record.contact_elements = static_cast<int>(contact_.elements.size());
          for (int c = 0; c < conditions_.size(); ++c)
            record.sections.push_back(
                conditions_.section_force(c, r.time, problem_->committed_state(), problem_->full_residual()));
          for (int b = 0; b < static_cast<int>(model_.bodies().size()); ++b) {
            const model::BodyResultant res = averaged_->last_resultant(b);
            record.bodies.push_back({res.force, res.moment, averaged_->error(b, problem_->committed_state()),
                                     averaged_->last_tie_force(b)});
          }
          update_counters();
          for (StepObserver* o : observers) o->on_step(*this, record);
          if (options.cancel && options.cancel()) {
            summary.cancelled = true;
            return false;
          }
          if (options.stop_when && options.stop_when(record)) return false;
          return options.stop_after_steps <= 0 || summary.new_steps < options.stop_after_steps;
        });
    if (!result.completed && !result.stopped) {
      summary.failure = "stage '" + stage.name + "': " + result.failure;
      break;
    }
    if (result.completed) {
      progress_.stage = s + 1;
      progress_.stage_begun = false;
      progress_.stage_start_time = t1;
      progress_.stepper = solver::StepperState{};
      update_counters();
      for (StepObserver* o : observers) o->on_stage_end(*this, s);
    }
    if (result.stopped) {
      summary.interrupted = true;
      summary.cancelled = summary.cancelled || result.cancelled;
      summary.failure = summary.cancelled
                            ? fmt::format("cancelled after {} steps", summary.new_steps)
                            : fmt::format("stopped after {} steps, as asked", summary.new_steps);
      break;
    }
  }
  // A run cancelled inside a step is back at its last converged state, counters included: the work of the
  // abandoned attempt is done again by the run that goes on from there (a resumed one counts it then).
  if (!summary.cancelled) update_counters();
  summary.converged = summary.failure.empty();
  summary.wall_seconds = counters_.wall_seconds;
  summary.detection_seconds = counters_.detection_seconds;
  summary.assembly_seconds = counters_.assembly_seconds;
  summary.linear_solve_seconds = counters_.linear_solve_seconds;
  summary.factorizations = counters_.factorizations;
  summary.analyses = counters_.analyses;
  summary.krylov_iterations = counters_.krylov_iterations;
  if (!solvers_used.empty()) note_linear_solver(*linear);
  for (const auto& [name, package] : solvers_used) summary.linear_solvers.push_back(name + ": " + package);
  if (!summary.interrupted)
    for (StepObserver* o : observers) o->on_finish(*this, summary);
  return summary;
}

}  // namespace nodus::simulation
