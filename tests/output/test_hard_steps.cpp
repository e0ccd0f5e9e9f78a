// What made each step of a real run hard, in steps.csv: the size of the step, the changes of regime of the
// contact elements and the causes of its cutbacks, read back from the file (RFC 4180) and checked against
// the StepRecords the simulation handed its observers and against the contact states it ended with.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

/// Rod a along x, 0.45 mm above rod b along y (R = 0.1 mm, delta_prox 0.3 mm: no proximity between them),
/// both ends of a driven 0.9 mm down in one step, b clamped at both ends: the step would take a's axis
/// through b's, and the crossing guard cuts it back until the rods come into contact (as in
/// tests/contact/test_simulation_contact.cpp).
const char* kDriveThrough = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: a, material: m, radius: 0.1, length: 4, elements: 8, start: [-2, 0, 0.45]}
  - {name: b, material: m, radius: 0.1, length: 4, elements: 8, start: [0, -2, 0], direction: [0, 1, 0]}
conditions:
  - {name: a_start, type: motion, beam: a, at: start}
  - {name: a_end, type: motion, beam: a, at: end}
  - {name: b_start, type: clamp, beam: b, at: start}
  - {name: b_end, type: clamp, beam: b, at: end}
stages:
  - name: down
    steps: 1
    motions:
      a_start: {translation: [0, 0, -0.9]}
      a_end: {translation: [0, 0, -0.9]}
contact: {}
)";

class Recorder : public simulation::StepObserver {
 public:
  std::vector<simulation::StepRecord> records;
  void on_step(const simulation::Simulation&, const simulation::StepRecord& r) override {
    records.push_back(r);
  }
};

TEST(HardSteps, StepsCsvSaysWhyAStepWasCutBack) {
  testing::ScratchDir dir;
  simulation::Simulation sim(scenario::parse_scenario(kDriveThrough, "through.yaml"));
  StepsCsvWriter steps(dir.path());
  Recorder recorder;
  const simulation::RunSummary summary = sim.run({&steps, &recorder});
  ASSERT_TRUE(summary.converged) << summary.failure;
  const auto& records = recorder.records;
  ASSERT_GE(records.size(), 2u);
  // The first step was cut back, each time because the axes passed through each other.
  const simulation::StepRecord& first = records.front();
  ASSERT_GT(first.cutbacks, 0);
  ASSERT_EQ(first.cutback_causes.size(), static_cast<std::size_t>(first.cutbacks));
  for (const std::string& cause : first.cutback_causes)
    EXPECT_NE(cause.find("passed through each other"), std::string::npos) << cause;
  // Its size is the nominal step (the stage) halved at each cutback; the steps add up to the stage.
  EXPECT_DOUBLE_EQ(first.step_size, std::ldexp(1.0, -first.cutbacks));
  double total = 0.0;
  for (const simulation::StepRecord& r : records) {
    total += r.step_size;
    EXPECT_EQ(r.cutback_causes.size(), static_cast<std::size_t>(r.cutbacks)) << "step " << r.step;
  }
  EXPECT_NEAR(total, 1.0, 1e-12);

  // The changes of regime are counted between evaluations of the same contact elements only: here every
  // element that presses at the end was detected in a state where it already pressed (the rods come into
  // contact within a Newton solve before a detection), so entering and leaving may stay 0. Frictionless:
  // nothing sticks or slips.
  int pressing = 0;
  for (const simulation::ContactState& s : sim.contact_states()) pressing += s.normal_reaction > 0.0;
  EXPECT_GT(pressing, 0);
  for (const simulation::StepRecord& r : records) {
    EXPECT_EQ(r.regime_changes.to_slip, 0);
    EXPECT_EQ(r.regime_changes.to_stick, 0);
  }

  // The file says the same, the causes as one field each.
  const auto rows = testing::csv_records(testing::read_text(dir.path() / "steps.csv"));
  ASSERT_EQ(rows.size(), records.size() + 1);
  const std::vector<std::string>& header = rows[0];
  const auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name;
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::vector<std::string> last{"step_size", "entered",  "left",
                                      "to_slip",   "to_stick", "cutback_causes"};
  ASSERT_GE(header.size(), last.size());
  EXPECT_EQ(std::vector<std::string>(header.end() - 6, header.end()), last);
  for (std::size_t k = 0; k < records.size(); ++k) {
    const simulation::StepRecord& r = records[k];
    const std::vector<std::string>& row = rows[k + 1];
    ASSERT_EQ(row.size(), header.size()) << "step " << r.step;
    EXPECT_EQ(std::stod(row[column("step_size")]), r.step_size);
    EXPECT_EQ(std::stoi(row[column("entered")]), r.regime_changes.entered);
    EXPECT_EQ(std::stoi(row[column("left")]), r.regime_changes.left);
    EXPECT_EQ(std::stoi(row[column("to_slip")]), r.regime_changes.to_slip);
    EXPECT_EQ(std::stoi(row[column("to_stick")]), r.regime_changes.to_stick);
    std::string joined;
    for (const std::string& cause : r.cutback_causes) joined += (joined.empty() ? "" : " | ") + cause;
    EXPECT_EQ(row[column("cutback_causes")], joined);
  }
  EXPECT_NE(rows[1][column("cutback_causes")], "");
}

}  // namespace
}  // namespace nodus::output
