#pragma once
// An observer that keeps every converged step's record and state, for the verification tests.

#include <vector>

#include <Eigen/Core>

#include "nodus/simulation/simulation.hpp"

namespace nodus::verification {

class StepRecorder : public simulation::StepObserver {
 public:
  std::vector<simulation::StepRecord> records;
  std::vector<Eigen::VectorXd> states;  ///< sim.state() after each step
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    records.push_back(r);
    states.push_back(sim.state());
  }
};

}  // namespace nodus::verification
