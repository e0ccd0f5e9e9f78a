#pragma once
// Scenarios of a single straight beam for the verification tests, built in code so that each test states its
// reference problem completely.

#include <numbers>

#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "verified_simulation.hpp"

namespace nodus::verification {

struct BeamCase {
  double length = 100.0;  // mm
  double radius = 0.5;    // mm
  double young = 4000.0;  // MPa
  double poisson = 0.3;
  int elements = 40;
  double bending_factor = 1.0;
  int gauss_points = 2;

  double area() const { return std::numbers::pi * radius * radius; }
  double inertia() const { return std::numbers::pi * radius * radius * radius * radius / 4.0; }
  double ei() const { return young * bending_factor * inertia(); }
};

inline scenario::Scenario single_beam(const BeamCase& c) {
  scenario::Scenario s;
  s.path = "verification";
  s.materials.push_back({"material", c.young, c.poisson});
  scenario::BeamSpec b;
  b.name = "beam";
  b.radius = c.radius;
  b.length = c.length;
  b.elements = c.elements;
  b.direction = Eigen::Vector3d::UnitX();
  b.director1 = Eigen::Vector3d::UnitY();
  b.bending_factor = c.bending_factor;
  s.beams.push_back(b);
  s.solver.gauss_points = c.gauss_points;
  return s;
}

inline scenario::DofMask all_dofs() {
  return {true, true, true, true, true, true, true, true, true};
}
inline scenario::DofMask position_dofs() {
  return {true, true, true, false, false, false, false, false, false};
}

/// Adds a condition on the beam's start (node 0) or end (node 2n); returns its index.
inline int add_condition(scenario::Scenario& s, const std::string& name, scenario::ConditionType type,
                         bool at_end, scenario::DofMask dofs = all_dofs()) {
  scenario::ConditionSpec c;
  c.name = name;
  c.type = type;
  c.beam = 0;
  c.node = at_end ? 2 * s.beams[0].elements : 0;
  c.dofs = dofs;
  s.conditions.push_back(c);
  return static_cast<int>(s.conditions.size()) - 1;
}

/// Keeps the record of the last converged step (reactions, iterations).
struct LastStep : simulation::StepObserver {
  simulation::StepRecord last;
  void on_step(const simulation::Simulation&, const simulation::StepRecord& r) override { last = r; }
};

/// Runs the scenario with no output; fails the test if it does not converge.
inline simulation::RunSummary run_quietly(VerifiedSimulation& sim) {
  return sim.run({});
}

/// Centre of local node `local` of beam 0 in the converged state.
inline Eigen::Vector3d centre(const simulation::Simulation& sim, int local) {
  return sim.state().segment<3>(9 * sim.model().beam(0).node(local));
}

}  // namespace nodus::verification
