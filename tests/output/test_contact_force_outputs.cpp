// Contact forces in the output files of a real run: two beams crossing at right angles, pressed together,
// then the upper one dragged along the lower one with friction (a coarse variant of
// tests/verification/test_contact_crossing.cpp, two steps). The files are read back and compared with the
// StepRecords and the ContactStates that the simulation handed to its observers.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/vtk_writer.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using testing::ScratchDir;

/// Step 1 presses the upper beam's supports 0.02 mm down (initial surface gap 0.01 mm); step 2 drags them
/// 0.03 mm along x, so that friction acts and an element slides. Three contact elements, about 6e-5 N in all.
/// FORCES is replaced by `true` or `false`.
const char* kCrossing = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: lower, material: m, radius: 0.1, length: 10, elements: 20, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: upper, material: m, radius: 0.1, length: 10, elements: 20, start: [0, -5, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
conditions:
  - {name: l0, type: clamp, beam: lower, at: start, dofs: [position, g1z]}
  - {name: l1, type: clamp, beam: lower, at: end, dofs: [y, z]}
  - {name: u0, type: motion, beam: upper, at: start, dofs: [position, g1z]}
  - {name: u1, type: motion, beam: upper, at: end, dofs: [x, z]}
stages:
  - name: press
    steps: 1
    motions:
      u0: {translation: [0, 0, -0.02]}
      u1: {translation: [0, 0, -0.02]}
  - name: slide
    steps: 1
    motions:
      u0: {translation: [0.03, 0, -0.02]}
      u1: {translation: [0.03, 0, -0.02]}
contact: {self_contact: false, friction: 0.3, forces: FORCES}
output: {vtk_every: 1, contact_csv: true}
)";

scenario::Scenario crossing(bool forces) {
  std::string text = kCrossing;
  text.replace(text.find("FORCES"), 6, forces ? "true" : "false");
  return scenario::parse_scenario(text, "crossing.yaml");
}

/// What the simulation hands its observers at every converged step.
class Recorder : public simulation::StepObserver {
 public:
  std::vector<simulation::StepRecord> records;
  std::vector<contact::ContactGeometry> geometries;
  std::vector<std::vector<simulation::ContactState>> states;
  contact::ContactGeometry initial;  ///< the geometry of the initial state
  void on_start(const simulation::Simulation& sim) override { initial = *sim.contact(); }
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& r) override {
    records.push_back(r);
    geometries.push_back(*sim.contact());
    states.push_back(sim.contact_states());
  }
};

/// A CSV file as rows of fields (header first); names in these files hold no commas.
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : testing::split(testing::read_text(path), '\n'))
    rows.push_back(testing::split(line, ','));
  return rows;
}

void expect_close(double read, double expected, const std::string& what) {
  EXPECT_NEAR(read, expected, 1e-9 * (1 + std::abs(expected))) << what;
}

const std::vector<std::string> kGeometryColumns{
    "zone", "beam_i", "beam_j", "zeta", "abscissa_i", "abscissa_j", "xi1_i", "xi2_i", "xi1_j", "xi2_j",
    "x_i",  "y_i",    "z_i",    "x_j",  "y_j",        "z_j",        "nx",    "ny",    "nz",    "gap"};
const std::vector<std::string> kForceColumns{"normal_force", "tangential_force", "tx", "ty", "tz", "state"};

/// Checks a contact element table read back against the geometry and, if given, the states it was written
/// from.
void expect_contact_table(const std::filesystem::path& path, const contact::ContactGeometry& geometry,
                          const std::vector<simulation::ContactState>* states) {
  SCOPED_TRACE(path.filename().string());
  const auto rows = read_csv(path);
  ASSERT_EQ(rows.size(), geometry.elements.size() + 1);
  std::vector<std::string> header = kGeometryColumns;
  if (states) header.insert(header.end(), kForceColumns.begin(), kForceColumns.end());
  EXPECT_EQ(rows[0], header);
  for (std::size_t e = 0; e < geometry.elements.size(); ++e) {
    const contact::ContactElement& c = geometry.elements[e];
    const auto& f = rows[1 + e];
    ASSERT_EQ(f.size(), header.size());
    EXPECT_EQ(std::stoi(f[0]), c.zone);
    EXPECT_EQ(f[1], "lower");
    EXPECT_EQ(f[2], "upper");
    expect_close(std::stod(f[5]), c.particle_j.abscissa, "abscissa_j");
    for (int k = 0; k < 3; ++k)
      expect_close(std::stod(f[16 + static_cast<std::size_t>(k)]), c.normal[k], "n");
    expect_close(std::stod(f[19]), c.gap, "gap");
    if (!states) continue;
    const simulation::ContactState& s = (*states)[e];
    expect_close(std::stod(f[20]), s.normal_reaction, "normal_force");
    expect_close(std::stod(f[21]), s.tangential.norm(), "tangential_force");
    for (int k = 0; k < 3; ++k)
      expect_close(std::stod(f[22 + static_cast<std::size_t>(k)]), s.tangential[k], "tx, ty, tz");
    const char* state = s.normal_reaction == 0.0 ? "open" : s.slip ? "slip" : "stick";
    EXPECT_EQ(f[25], state) << "element " << e;
  }
}

/// A VTK file read back, and its CellData.
struct VtpFile {
  explicit VtpFile(const std::filesystem::path& path) : root(testing::parse_vtk(testing::read_text(path))) {}
  const testing::XmlElement& cell_data() const { return root->one("PolyData").one("Piece").one("CellData"); }
  std::unique_ptr<testing::XmlElement> root;
};

struct CrossingRun {
  ScratchDir dir;
  Recorder recorder;
  std::unique_ptr<simulation::Simulation> sim;
  simulation::RunSummary summary;
};

void run_crossing(CrossingRun& run, bool forces) {
  run.sim = std::make_unique<simulation::Simulation>(crossing(forces));
  StepsCsvWriter steps(run.dir.path());
  VtkSeriesWriter vtk(run.dir.path(), run.sim->scenario().output.vtk_every, 4);
  ContactCsvWriter tables(run.dir.path());
  run.summary = run.sim->run({&steps, &vtk, &tables, &run.recorder});
}

TEST(ContactForceOutputs, FilesCarryTheContactStatesOfEachStep) {
  CrossingRun run;
  run_crossing(run, true);
  ASSERT_TRUE(run.summary.converged) << run.summary.failure;
  const simulation::Simulation& sim = *run.sim;
  const auto& records = run.recorder.records;
  ASSERT_EQ(records.size(), 2u);
  ASSERT_TRUE(sim.contact_forces());
  const std::filesystem::path& dir = run.dir.path();

  // The run is not vacuous: the beams press on each other at the end and friction acts.
  const std::vector<simulation::ContactState>& final_states = sim.contact_states();
  ASSERT_EQ(final_states.size(), sim.contact()->elements.size());
  double largest_friction = 0.0;
  int closed = 0;
  for (const simulation::ContactState& s : final_states) {
    closed += s.normal_reaction > 0.0;
    largest_friction = std::max(largest_friction, s.tangential.norm());
  }
  EXPECT_GT(closed, 0);
  EXPECT_GT(largest_friction, 0.0);
  EXPECT_GT(records.back().slipping, 0);

  // steps.csv: the contact columns after contact_elements, before the condition columns.
  const auto steps = read_csv(dir / "steps.csv");
  ASSERT_EQ(steps.size(), 3u);
  const std::vector<std::string> leading{"step",
                                         "stage",
                                         "time",
                                         "newton_iterations",
                                         "cutbacks",
                                         "residual",
                                         "increment",
                                         "zones",
                                         "contact_elements",
                                         "detections",
                                         "normal_iterations",
                                         "penetration_ratio",
                                         "normal_force",
                                         "tangential_force",
                                         "slipping",
                                         "stabilization_force",
                                         "loops_converged",
                                         "min_orientation",
                                         "min_chord",
                                         "min_clearance",
                                         "l0_fx"};
  ASSERT_GE(steps[0].size(), leading.size());
  EXPECT_EQ(std::vector<std::string>(steps[0].begin(), steps[0].begin() + 21), leading);
  // Then six columns per condition, and last what made each step hard.
  EXPECT_EQ(steps[0].size(), 20u + 6u * 4u + 6u);
  EXPECT_EQ(
      std::vector<std::string>(steps[0].end() - 6, steps[0].end()),
      (std::vector<std::string>{"step_size", "entered", "left", "to_slip", "to_stick", "cutback_causes"}));
  for (std::size_t k = 0; k < records.size(); ++k) {
    const simulation::StepRecord& r = records[k];
    const auto& f = steps[1 + k];
    ASSERT_EQ(f.size(), steps[0].size());
    EXPECT_EQ(std::stoi(f[9]), r.detections);
    EXPECT_GE(r.detections, 1);
    EXPECT_EQ(std::stoi(f[10]), r.normal_iterations);
    EXPECT_EQ(std::stoi(f[14]), r.slipping);
    EXPECT_EQ(f[16], r.loops_converged ? "1" : "0");
    // One step a stage, not cut back: the stage's load time, no causes.
    EXPECT_EQ(std::stod(f[44]), 1.0);
    EXPECT_EQ(std::stoi(f[45]), r.regime_changes.entered);
    EXPECT_EQ(std::stoi(f[46]), r.regime_changes.left);
    EXPECT_EQ(std::stoi(f[47]), r.regime_changes.to_slip);
    EXPECT_EQ(std::stoi(f[48]), r.regime_changes.to_stick);
    EXPECT_EQ(f[49], "");
    EXPECT_EQ(r.cutbacks, 0);
    EXPECT_GE(r.regime_changes.entered, 0);
    EXPECT_GE(r.regime_changes.left, 0);
    // The sums and the extremes over the contact states the step ended with.
    double normal = 0.0, tangential = 0.0, penetration = 0.0;
    int slipping = 0;
    for (const simulation::ContactState& s : run.recorder.states[k]) {
      normal += s.normal_reaction;
      tangential += s.tangential.norm();
      penetration = std::max(penetration, -s.gap);
      slipping += s.slip;
    }
    expect_close(std::stod(f[11]), penetration / sim.contact_laws().max_penetration, "penetration_ratio");
    expect_close(std::stod(f[12]), normal, "normal_force of step " + f[0]);
    expect_close(std::stod(f[13]), tangential, "tangential_force of step " + f[0]);
    EXPECT_EQ(std::stoi(f[14]), slipping);
    EXPECT_GT(normal, 0.0);
  }

  // The press: the elements of the step's first detection, in the initial state 0.01 mm apart, are open at
  // the first evaluation and press once the upper beam is pushed onto the lower one: they entered contact.
  EXPECT_GE(records[0].regime_changes.entered, 1);

  // contact_final.csv: the states of the last step; its normal forces sum to the step's normal force.
  expect_contact_table(dir / "contact_final.csv", *sim.contact(), &final_states);
  const auto final_rows = read_csv(dir / "contact_final.csv");
  double sum_normal = 0.0, sum_tangential = 0.0;
  int slipping = 0;
  for (std::size_t e = 1; e < final_rows.size(); ++e) {
    sum_normal += std::stod(final_rows[e][20]);
    sum_tangential += std::stod(final_rows[e][21]);
    slipping += final_rows[e][25] == "slip";
  }
  EXPECT_NEAR(sum_normal, records.back().normal_force, 1e-9 * records.back().normal_force);
  EXPECT_NEAR(sum_tangential, records.back().tangential_force, 1e-9 * (1 + records.back().tangential_force));
  EXPECT_EQ(slipping, records.back().slipping);

  // contact/contact_NNNNNN.csv at the VTK steps (vtk_every: 1): step 0 has no forces (none computed before
  // the first step), steps 1 and 2 those the steps ended with.
  for (int step : {0, 1, 2}) {
    const std::string name = ContactCsvSeries::file_name(step);
    EXPECT_EQ(name, "contact_00000" + std::to_string(step) + ".csv");
    ASSERT_TRUE(std::filesystem::exists(dir / "vtk" / VtkSeries::file_name(step))) << step;
    ASSERT_TRUE(std::filesystem::exists(dir / "contact" / name)) << name;
  }
  const auto initial = read_csv(dir / "contact" / "contact_000000.csv");
  EXPECT_EQ(initial[0], kGeometryColumns);
  for (std::size_t k = 0; k < 2; ++k)
    expect_contact_table(dir / "contact" / ContactCsvSeries::file_name(static_cast<int>(k) + 1),
                         run.recorder.geometries[k], &run.recorder.states[k]);
  for (const auto& entry : std::filesystem::directory_iterator(dir / "contact"))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();

  // vtk/contact_NNNNNN.vtp: force arrays on the element segments from step 1 on.
  EXPECT_EQ(VtpFile(dir / "vtk" / "contact_000000.vtp").cell_data().all("DataArray").size(), 6u);
  for (std::size_t k = 0; k < 2; ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1));
    const contact::ContactGeometry& g = run.recorder.geometries[k];
    const std::vector<simulation::ContactState>& states = run.recorder.states[k];
    const VtpFile file(dir / "vtk" / VtkSeries::contact_file_name(static_cast<int>(k) + 1));
    const testing::XmlElement& data = file.cell_data();
    const auto kind = testing::numbers(data.data_array("kind").text);
    const auto normal_force = testing::numbers(data.data_array("normal_force").text);
    const auto force = testing::numbers(data.data_array("force").text);
    const auto tangential = testing::numbers(data.data_array("tangential_force").text);
    const auto state = testing::numbers(data.data_array("state").text);
    const std::size_t polylines = kind.size() - g.elements.size();
    ASSERT_EQ(normal_force.size(), kind.size());
    ASSERT_EQ(force.size(), 3 * kind.size());
    ASSERT_EQ(tangential.size(), 3 * kind.size());
    ASSERT_EQ(state.size(), kind.size());
    double sum = 0.0;
    for (std::size_t c = 0; c < kind.size(); ++c) {
      if (c < polylines) {
        EXPECT_EQ(kind[c], 0.0);
        EXPECT_EQ(normal_force[c], 0.0);
        EXPECT_EQ(state[c], 0.0);
        for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(force[3 * c + i], 0.0);
        continue;
      }
      const std::size_t e = c - polylines;
      const simulation::ContactState& s = states[e];
      const contact::Vec3& n = g.elements[e].normal;
      expect_close(normal_force[c], s.normal_reaction, "normal_force");
      sum += normal_force[c];
      for (int i = 0; i < 3; ++i) {
        const std::size_t at = 3 * c + static_cast<std::size_t>(i);
        expect_close(force[at], s.normal_reaction * n[i] + s.tangential[i], "force on J");
        expect_close(tangential[at], s.tangential[i], "tangential_force");
      }
      EXPECT_EQ(state[c], s.normal_reaction == 0.0 ? 0.0 : s.slip ? 2.0 : 1.0);
    }
    EXPECT_NEAR(sum, records[k].normal_force, 1e-9 * records[k].normal_force);
  }
}

TEST(ContactForceOutputs, DetectionOnlyKeepsTheGeometryColumns) {
  CrossingRun run;
  run_crossing(run, false);
  ASSERT_TRUE(run.summary.converged) << run.summary.failure;
  const simulation::Simulation& sim = *run.sim;
  ASSERT_FALSE(sim.contact_forces());
  EXPECT_TRUE(sim.contact_states().empty());
  const std::filesystem::path& dir = run.dir.path();

  const auto steps = read_csv(dir / "steps.csv");
  ASSERT_EQ(steps.size(), 3u);
  for (std::size_t k = 1; k < steps.size(); ++k) {
    EXPECT_EQ(steps[k][9], "0");   // detections
    EXPECT_EQ(steps[k][12], "0");  // normal_force
  }
  expect_contact_table(dir / "contact_final.csv", *sim.contact(), nullptr);
  for (int step : {0, 1, 2})
    expect_contact_table(
        dir / "contact" / ContactCsvSeries::file_name(step),
        step == 0 ? run.recorder.initial : run.recorder.geometries[static_cast<std::size_t>(step) - 1],
        nullptr);
  EXPECT_EQ(VtpFile(dir / "vtk" / "contact_000002.vtp").cell_data().all("DataArray").size(), 6u);
}

TEST(ContactForceOutputs, AConvergedStateWithoutContactKeepsTheForceColumns) {
  // The upper beam 2 mm above the lower one: nothing touches in any step (a knot that came undone ends so).
  std::string text = kCrossing;
  text.replace(text.find("FORCES"), 6, "true");
  text.replace(text.find("0.21]"), 5, "2.21]");
  ScratchDir dir;
  simulation::Simulation sim(scenario::parse_scenario(text, "apart.yaml"));
  ContactCsvWriter tables(dir.path());
  ASSERT_TRUE(sim.run({&tables}).converged);
  ASSERT_TRUE(sim.contact_forces());
  ASSERT_TRUE(sim.contact()->elements.empty());
  const auto rows = read_csv(dir.path() / "contact_final.csv");
  ASSERT_EQ(rows.size(), 1u);  // the header alone
  std::vector<std::string> header = kGeometryColumns;
  header.insert(header.end(), kForceColumns.begin(), kForceColumns.end());
  EXPECT_EQ(rows[0], header);
}

TEST(ContactForceOutputs, ContactTablesOnlyWhenAskedAndStaleOnesRemoved) {
  CrossingRun run;  // its recorder is not used
  scenario::Scenario s = crossing(true);
  s.output.contact_csv = false;
  s.output.vtk_every = 0;
  run.sim = std::make_unique<simulation::Simulation>(std::move(s));
  const std::filesystem::path& dir = run.dir.path();
  std::filesystem::create_directories(dir / "contact");
  for (const char* name : {"contact_000007.csv", "notes.csv"}) std::ofstream(dir / "contact" / name) << "x\n";
  VtkSeriesWriter vtk(dir, 0, 4);
  ASSERT_TRUE(run.sim->run({&vtk}).converged);
  EXPECT_FALSE(std::filesystem::exists(dir / "contact" / "contact_000007.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "contact" / "notes.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "contact" / "contact_000000.csv"));
  // The final state is written with its forces although vtk_every is 0.
  EXPECT_EQ(VtpFile(dir / "vtk" / "contact_000000.vtp").cell_data().all("DataArray").size(), 6u);
  EXPECT_EQ(VtpFile(dir / "vtk" / "contact_000002.vtp").cell_data().all("DataArray").size(), 10u);
}

}  // namespace
}  // namespace nodus::output
