#pragma once
/// The global algorithm of a quasi-static run [Durville 2012, Sect. 6]: the loading program's stages, each
/// divided into load steps, each solved by Newton-Raphson. Contact is detected in every converged state (its
/// forces and loops come with the contact mechanics).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nodus/contact/detection.hpp"
#include "nodus/loading/boundary_conditions.hpp"
#include "nodus/model/model.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/contact_loops.hpp"

namespace nodus::simulation {

class EquilibriumProblem;

/// One converged load step.
struct StepRecord {
  int step = 0;       ///< 1, 2, ... over the whole run
  int stage = 0;      ///< index into Scenario::stages
  double time = 0.0;  ///< load time at the end of the step [s]
  int newton_iterations = 0;
  int cutbacks = 0;                             ///< halvings of the step before it converged
  double residual = 0.0;                        ///< |R| over the free unknowns at convergence [N]
  double increment = 0.0;                       ///< scaled size of the last Newton increment [-]
  std::vector<loading::SectionForce> sections;  ///< per condition (Scenario::conditions order)
  int zones = 0;                                ///< proximity zones detected in the converged state
  int contact_elements = 0;                     ///< contact elements along them
  int detections = 0;                           ///< contact loop 2 iterations (0 without contact forces)
  int normal_iterations = 0;                    ///< contact loop 3 iterations
  double penetration_ratio = 0.0;               ///< largest penetration / p_max
  double normal_force = 0.0;                    ///< sum of the normal reactions [N]
  double tangential_force = 0.0;                ///< sum of the friction force magnitudes [N]
  int slipping = 0;                             ///< contact elements sliding (friction at mu R_N)
};

struct RunSummary {
  bool converged = false;  ///< every stage completed
  int steps = 0;
  int newton_iterations = 0;
  double wall_seconds = 0.0;
  double detection_seconds = 0.0;     ///< of which spent in contact detection
  double assembly_seconds = 0.0;      ///< in residual and tangent evaluations inside Newton (line search too)
  double linear_solve_seconds = 0.0;  ///< in the sparse analysis, factorisation and solves
  std::string failure;                ///< why the run stopped early
};

class Simulation;

/// Receives the run's progress; output writers implement it.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void on_start(const Simulation& /*sim*/) {}
  virtual void on_stage(const Simulation& /*sim*/, int /*stage*/) {}
  /// Called after each converged step; sim.state() is the converged state.
  virtual void on_step(const Simulation& /*sim*/, const StepRecord& /*record*/) {}
  virtual void on_finish(const Simulation& /*sim*/, const RunSummary& /*summary*/) {}
};

class Simulation {
 public:
  explicit Simulation(scenario::Scenario scenario);
  ~Simulation();

  const scenario::Scenario& scenario() const { return scenario_; }
  const model::Model& model() const { return model_; }
  const loading::Conditions& conditions() const { return conditions_; }
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

  /// Runs every stage. Observers are called in order.
  RunSummary run(const std::vector<StepObserver*>& observers);

 private:
  scenario::Scenario scenario_;
  model::Model model_;
  loading::Conditions conditions_;
  std::unique_ptr<EquilibriumProblem> problem_;
  double time_ = 0.0;
  bool contact_enabled_ = false;
  contact::DetectionParameters detection_;
  std::vector<int> contact_beams_;  ///< the beams in contact now (stages take tools out and put them back)
  contact::ContactGeometry contact_;
  std::vector<ContactState> contact_states_;  ///< per element of contact_, at the last converged step
  double detection_seconds_ = 0.0;
  bool contact_forces_ = false;
  ContactLawSettings laws_;

  /// Detects contact in the committed state (when the scenario has contact).
  void detect_contact();
};

}  // namespace nodus::simulation
