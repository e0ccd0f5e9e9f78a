#pragma once
// The simulation of every verification case. Unset, the two variables below change nothing: the case runs as
// written. tests/mpi/test_mpi_verification.py sets them to run the cases on PETSc over 1, 2 and 3 ranks and
// compare each with the serial run (docs/parallel.md, "Same answers: the checks"):
//  - NODUS_VERIFICATION_SOLVER=NAME (a solver.linear_solver name: petsc, cholmod, ...) replaces the linear
//    solver of the scenario and of each of its stages;
//  - NODUS_VERIFICATION_RECORD=DIR: when the simulation ends, rank 0 writes its converged steps (stage, load
//    time, Newton iterations, cutbacks, detections, loop 3's iterations, zones, contact elements, slipping
//    elements, Newton's last |R| and increment with their tolerances, the linear solver) to
//    DIR/CASE.K.steps.csv and its final unknowns to DIR/CASE.K.state.csv, CASE being the test's name ('/' as
//    '_') and K counting the simulations of one test from 0.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/scenario/yaml_reader.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::verification {

/// The scenario with the linear solver of NODUS_VERIFICATION_SOLVER, if set, read as the scenario reads
/// solver.linear_solver.
inline scenario::Scenario with_verification_solver(scenario::Scenario s) {
  const char* name = std::getenv("NODUS_VERIFICATION_SOLVER");
  if (name == nullptr || *name == '\0') return s;
  const auto keys = scenario::SolverSettings::keys();
  const auto key =
      std::find_if(keys.begin(), keys.end(), [](const auto& k) { return k.path == "solver.linear_solver"; });
  const std::vector<std::string_view> choices = scenario::split_choices(key->range);
  const auto choice = std::find(choices.begin(), choices.end(), std::string_view(name));
  if (choice == choices.end())
    throw std::invalid_argument("NODUS_VERIFICATION_SOLVER: expected " + std::string(key->range) + ", got " +
                                name);
  key->set_choice(s.solver, static_cast<int>(choice - choices.begin()));
  for (scenario::StageSpec& stage : s.stages) stage.linear_solver.reset();
  return s;
}

class VerifiedSimulation : public simulation::Simulation {
 public:
  explicit VerifiedSimulation(scenario::Scenario s)
      : simulation::Simulation(with_verification_solver(std::move(s))), name_(record_name()) {}
  VerifiedSimulation(const VerifiedSimulation&) = delete;
  VerifiedSimulation& operator=(const VerifiedSimulation&) = delete;
  ~VerifiedSimulation() {
    try {
      write_record();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "NODUS_VERIFICATION_RECORD: " << e.what();
    }
  }

  /// Simulation::run, keeping every converged step for the record.
  simulation::RunSummary run(std::vector<simulation::StepObserver*> observers,
                             const simulation::RunOptions& options = {}) {
    observers.push_back(&steps_);
    return simulation::Simulation::run(observers, options);
  }

 private:
  struct Steps : simulation::StepObserver {
    std::vector<simulation::StepRecord> records;
    void on_step(const simulation::Simulation&, const simulation::StepRecord& r) override {
      records.push_back(r);
    }
  };

  /// CASE.K for this simulation, or empty without NODUS_VERIFICATION_RECORD.
  static std::string record_name() {
    const char* dir = std::getenv("NODUS_VERIFICATION_RECORD");
    if (dir == nullptr || *dir == '\0') return {};
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    // A fixture's SetUpTestSuite runs outside any test: its suite names it.
    std::string name = test != nullptr
                           ? std::string(test->test_suite_name()) + "." + test->name()
                           : std::string(::testing::UnitTest::GetInstance()->current_test_suite()->name());
    for (char& c : name)
      if (c == '/') c = '_';
    static std::map<std::string, int> count;
    return std::string(dir) + "/" + name + "." + std::to_string(count[name]++);
  }

  void write_record() const {
    if (name_.empty() || !parallel::is_root()) return;
    std::FILE* f = std::fopen((name_ + ".steps.csv").c_str(), "w");
    if (f == nullptr) throw std::runtime_error("cannot write " + name_ + ".steps.csv");
    std::fprintf(
        f,
        "step,stage,time,newton_iterations,cutbacks,detections,normal_iterations,zones,contact_elements,"
        "slipping,residual,residual_tolerance,increment,increment_tolerance,linear_solver\n");
    for (const simulation::StepRecord& r : steps_.records)
      std::fprintf(f, "%d,%d,%.17g,%d,%d,%d,%d,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%s\n", r.step, r.stage,
                   r.time, r.newton_iterations, r.cutbacks, r.detections, r.normal_iterations, r.zones,
                   r.contact_elements, r.slipping, r.residual, r.residual_tolerance, r.increment,
                   scenario().solver.increment_tolerance, linear_solver_name().c_str());
    std::fclose(f);
    f = std::fopen((name_ + ".state.csv").c_str(), "w");
    if (f == nullptr) throw std::runtime_error("cannot write " + name_ + ".state.csv");
    for (double v : state()) std::fprintf(f, "%.17g\n", v);
    std::fclose(f);
  }

  std::string name_;
  Steps steps_;
};

}  // namespace nodus::verification
