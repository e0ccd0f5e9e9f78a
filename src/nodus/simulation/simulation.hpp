#pragma once
/// The global algorithm of a quasi-static run [Durville 2012, Sect. 6]: the loading program's stages, each
/// divided into load steps, each solved by Newton-Raphson. Contact is detected in every converged state (its
/// forces and loops come with the contact mechanics). Between two steps the complete state of a run can be
/// taken (Simulation::snapshot) and a run continued from it (Simulation::restore) exactly as if it had not
/// stopped: checkpoints, `nodus run --resume` and branches rest on that.

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/averaged_conditions_term.hpp"
#include "nodus/model/model.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/contact_loops.hpp"
#include "nodus/simulation/equilibrium_problem.hpp"
#include "nodus/solver/load_stepping.hpp"

namespace nodus::simulation {

/// A rigid body in a converged state (model/averaged_conditions_term.hpp).
struct BodyRecord {
  loading::Vec3 force = loading::Vec3::Zero();   ///< exerted on its bound sections [N]
  loading::Vec3 moment = loading::Vec3::Zero();  ///< about its point c [N mm]
  double error = 0.0;  ///< how far the penalty lets it stray from the best fit of its sections [mm]
  double tie = 0.0;    ///< |force of the rearrangement tie| on its sections in the step [N]
};

/// One converged load step.
struct StepRecord {
  int step = 0;       ///< 1, 2, ... over the whole run
  int stage = 0;      ///< index into Scenario::stages
  double time = 0.0;  ///< load time at the end of the step [s]
  int newton_iterations = 0;
  int cutbacks = 0;       ///< halvings of the step before it converged
  double residual = 0.0;  ///< |R| over the free unknowns at convergence [N]
  /// The tolerance |R| was compared with at the end of the step's last Newton solve [N].
  double residual_tolerance = 0.0;
  double increment = 0.0;                       ///< scaled size of the last Newton increment [-]
  std::vector<loading::SectionForce> sections;  ///< per condition (Scenario::conditions order)
  std::vector<BodyRecord> bodies;               ///< per rigid body (Scenario::bodies order)
  int zones = 0;                                ///< proximity zones detected in the converged state
  int contact_elements = 0;                     ///< contact elements along them
  int detections = 0;                           ///< contact loop 2 iterations (0 without contact forces)
  int normal_iterations = 0;                    ///< contact loop 3 iterations
  double penetration_ratio = 0.0;               ///< largest penetration / p_max
  double normal_force = 0.0;                    ///< sum of the normal reactions [N]
  double tangential_force = 0.0;                ///< sum of the friction force magnitudes [N]
  int slipping = 0;                             ///< contact elements sliding (friction at mu R_N)
  /// Contact loops 2 and 3 both ended by their criteria, not at their caps (contact.max_detections,
  /// contact.max_normal_iterations); true without contact forces (no loops).
  bool loops_converged = true;
  double stabilization_force = 0.0;  ///< |viscous stabilisation drag| over all nodes [N] (0: none)
  /// The fold check of the converged state (model::FoldCheck): the smallest det[g1, g2, r'] over every Gauss
  /// point and element centre, and the smallest element chord over its reference length [-].
  double min_orientation = 1.0;
  double min_chord = 1.0;
  /// The smallest clearance between the contact beams' surfaces, axis distance minus both radii, over every
  /// pair of points of different beams or of one beam more than delta_separ apart along it
  /// (contact::min_clearance) [mm]; NaN without contact, +infinity if no two parts are within delta_prox.
  double min_clearance = std::numeric_limits<double>::quiet_NaN();
  bool ends_stage = false;  ///< the step reached the end of its stage
  /// What made the step hard. The changes of regime of the contact elements over the evaluations of the
  /// step's successful attempt (all its Newton solves, contact loops 2 and 3 included), each evaluation
  /// compared with the previous one of the same elements (contact::ContactTerm::regime_changes); 0 without
  /// contact forces.
  contact::RegimeChanges regime_changes;
  /// Why each attempt of the step that failed before it converged failed, in order (`cutbacks` entries).
  std::vector<std::string> cutback_causes;
  double step_size = 0.0;  ///< load-time size of the converged step [s]
};

struct RunSummary {
  bool converged = false;  ///< every stage completed
  int steps = 0;
  int newton_iterations = 0;
  double wall_seconds = 0.0;
  double detection_seconds = 0.0;     ///< of which spent in contact detection
  double assembly_seconds = 0.0;      ///< in residual and tangent evaluations inside Newton (line search too)
  double linear_solve_seconds = 0.0;  ///< in the sparse analysis, factorisation and solves
  int factorizations = 0;             ///< numerical factorisations of the tangent
  int analyses = 0;                   ///< symbolic analyses of the tangent's pattern
  int krylov_iterations = 0;          ///< GMRES iterations on lagged factors (solver.reuse_factor)
  std::string failure;                ///< why the run stopped early
  /// Stopped on request (RunOptions::stop_after_steps), as if killed: on_finish was not called.
  bool interrupted = false;
  /// Stopped by RunOptions::cancel (then `interrupted` is set too: the state is the last converged one).
  bool cancelled = false;
  /// Steps converged by this call of run() (`steps` counts those of a restored state too).
  int new_steps = 0;
  /// The linear solvers this call of run() used, in the order of the stages, each as "name: package"
  /// ("mumps_lu: MUMPS 5.5.1"; LinearSolver::name(), package()).
  std::vector<std::string> linear_solvers;
};

/// The run's cumulative counters, carried by a saved state.
struct RunCounters {
  int steps = 0;  ///< converged steps
  int newton_iterations = 0;
  double wall_seconds = 0.0;  ///< [s], as RunSummary
  double detection_seconds = 0.0;
  double assembly_seconds = 0.0;
  double linear_solve_seconds = 0.0;
  int factorizations = 0;
  int analyses = 0;
  int krylov_iterations = 0;
};

/// Where a run stands in its loading program between two steps.
struct RunProgress {
  int stage = 0;  ///< the stage in progress, or the next one to begin (the number of stages: all done)
  /// The start of `stage` (releases, activations, contact changes, keyframes) is applied and its stepping
  /// under way.
  bool stage_begun = false;
  double stage_start_time = 0.0;  ///< load time at the start of `stage` [s], when begun
  solver::StepperState stepper;   ///< the stepping inside `stage`, when begun
};

/// The complete state of a run between two steps. Restored into a Simulation of the same scenario, the run
/// continues exactly as the one that saved it (persistence/checkpoint_files.hpp stores it in a file).
struct SimulationState {
  RunProgress progress;
  RunCounters counters;
  double time = 0.0;  ///< load time of the last converged state [s]
  ProblemState problem;
  std::vector<loading::ConditionState> conditions;  ///< per condition
  std::vector<int> contact_beams;                   ///< the beams in contact now
  contact::ContactGeometry contact;                 ///< Simulation::contact(): the last detection
  std::vector<ContactState> contact_states;         ///< Simulation::contact_states()
};

/// How a Simulation begins its run.
enum class StartKind {
  fresh,     ///< from the initial state
  resumed,   ///< from a saved state of an interrupted run of the same scenario (outputs go on from it)
  branched,  ///< from the state of the parent run at the end of a branch's `from` stage (outputs start anew)
};

/// Options of one call of Simulation::run.
struct RunOptions {
  /// For tests: stop the run, as if it were killed, after this many steps converged in this call (after the
  /// observers' on_step and, at a stage end, on_stage_end); 0: never.
  int stop_after_steps = 0;
  /// Stops the run after the converged step for which it returns true (between steps, as stop_after_steps
  /// does: a later run() goes on from there). Empty: never. The stepping interface of the Python module
  /// (Simulation.step, run_stage) rests on it.
  std::function<bool(const StepRecord&)> stop_when = {};
  /// Asked after every Newton iteration and every converged step: true stops the run there, back at the last
  /// converged state (RunSummary::cancelled); Ctrl-C in Python. Empty: never.
  std::function<bool()> cancel = {};
};

class Simulation;

/// Receives the run's progress; output writers implement it.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void on_start(const Simulation& /*sim*/) {}
  /// Called when a stage begins, or when a run resumes inside it.
  virtual void on_stage(const Simulation& /*sim*/, int /*stage*/) {}
  /// Called after each converged step; sim.state() is the converged state.
  virtual void on_step(const Simulation& /*sim*/, const StepRecord& /*record*/) {}
  /// Called when a stage is completed (after the on_step of its last step).
  virtual void on_stage_end(const Simulation& /*sim*/, int /*stage*/) {}
  /// Called when the run ends, converged or not; not when it was stopped on request (RunOptions), which acts
  /// as a kill.
  virtual void on_finish(const Simulation& /*sim*/, const RunSummary& /*summary*/) {}
};

class Simulation {
 public:
  explicit Simulation(scenario::Scenario scenario);
  ~Simulation();

  const scenario::Scenario& scenario() const { return scenario_; }
  const model::Model& model() const { return model_; }
  const loading::Conditions& conditions() const { return conditions_; }
  /// The averaged conditions of the rigid bodies; null without bodies.
  const model::AveragedConditionsTerm* averaged_conditions() const { return averaged_; }
  /// The last converged state: nine values (r, g1, g2) per node.
  const Eigen::VectorXd& state() const;
  /// The contact geometry detected in the last converged state; null when the scenario has no contact.
  const contact::ContactGeometry* contact() const { return contact_enabled_ ? &contact_ : nullptr; }
  /// The contact laws, defaults resolved (meaningful when contact forces are on).
  const ContactLawSettings& contact_laws() const { return laws_; }
  bool contact_forces() const { return contact_forces_; }
  /// The state of each element of contact() at the last converged step (empty without contact forces or
  /// before the first step).
  const std::vector<ContactState>& contact_states() const;
  /// The detection parameters, defaults resolved (meaningful when contact() is not null).
  const contact::DetectionParameters& detection_parameters() const { return detection_; }
  /// Load time of the last converged state [s].
  double time() const { return time_; }
  /// Load time at the end of each stage [s].
  double stage_end_time(int stage) const;
  /// Converged steps so far (those of a restored state included).
  int steps() const { return counters_.steps; }
  /// The run's cumulative counters (those of a restored state included), as of the last converged step: in
  /// the observers' on_step they include that step.
  const RunCounters& counters() const { return counters_; }
  /// Where the run stands (valid between steps: in the observers' calls, before and after run()).
  const RunProgress& progress() const { return progress_; }
  StartKind start_kind() const { return start_kind_; }
  /// The name of the linear solver of the stage being run (stages[].linear_solver, or solver.linear_solver;
  /// e.g. "klu", "mumps_ldlt"), or of the last stage run; empty before run().
  const std::string& linear_solver_name() const { return linear_solver_name_; }

  /// The complete state of the run, valid between steps: in the observers' on_start, on_step and
  /// on_stage_end, and before and after run().
  SimulationState snapshot() const;
  /// Continues from `state` (a snapshot() of a Simulation of the same scenario, or for a branch of its
  /// parent, see scenario::branch_scenario); call before run(). Throws std::invalid_argument if the state
  /// does not fit the model.
  void restore(SimulationState state, StartKind kind);

  /// Runs the stages left (all of them unless restored). Observers are called in order.
  RunSummary run(const std::vector<StepObserver*>& observers, const RunOptions& options = {});

 private:
  scenario::Scenario scenario_;
  model::Model model_;
  loading::Conditions conditions_;
  std::unique_ptr<EquilibriumProblem> problem_;
  model::AveragedConditionsTerm* averaged_ = nullptr;  ///< owned by problem_
  double time_ = 0.0;
  std::string linear_solver_name_;
  bool contact_enabled_ = false;
  contact::DetectionParameters detection_;
  std::vector<int> contact_beams_;  ///< the beams in contact now (stages take tools out and put them back)
  contact::ContactGeometry contact_;
  std::vector<ContactState> contact_states_;  ///< per element of contact_, at the last converged step
  double detection_seconds_ = 0.0;            ///< in detect_contact() since construction
  bool contact_forces_ = false;
  ContactLawSettings laws_;
  RunProgress progress_;
  RunCounters counters_;
  StartKind start_kind_ = StartKind::fresh;

  /// Detects contact in the committed state (when the scenario has contact).
  void detect_contact();
};

}  // namespace nodus::simulation
