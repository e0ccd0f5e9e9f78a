// result.h5 of real runs of the nodus program, read back with read_result_h5 and compared with the run's
// text files as the file formats describe them (final_nodes.csv, contact_final.csv, steps.csv, the vtk/
// folder) and with the scenario; a run stopped and resumed against one never stopped; a damaged file on
// resuming; output.hdf5: false; the XDMF index's structure.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "nodus/output/result_h5.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using testing::csv_records;
using testing::parse_xml;
using testing::read_text;
using testing::ScratchDir;

/// Two beams crossing at right angles: the upper one pressed onto the lower one in three steps, then dragged
/// along it with friction in three (a variant of test_contact_force_outputs.cpp's crossing). VTK (and so
/// result.h5) every second step; a checkpoint every second step. A `rigid` tool beam far away marks `tool`.
const char* kCrossing = R"(
materials:
  - {name: m, young_modulus: 4000, poisson_ratio: 0.3}
  - {name: steel, young_modulus: 200000, poisson_ratio: 0.3}
beams:
  - {name: lower, material: m, radius: 0.1, length: 10, elements: 20, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: upper, material: m, radius: 0.1, length: 10, elements: 20, start: [0, -5, 0.21],
     direction: [0, 1, 0], director1: [1, 0, 0]}
  - {name: pin, material: steel, radius: 0.2, length: 2, elements: 2, start: [0, 0, 5],
     direction: [1, 0, 0], director1: [0, 1, 0]}
conditions:
  - {name: l0, type: clamp, beam: lower, at: start, dofs: [position, g1z]}
  - {name: l1, type: clamp, beam: lower, at: end, dofs: [y, z]}
  - {name: u0, type: motion, beam: upper, at: start, dofs: [position, g1z]}
  - {name: u1, type: motion, beam: upper, at: end, dofs: [x, z]}
  - {name: hold, type: rigid, beam: pin}
stages:
  - name: press
    steps: 3
    motions:
      u0: {translation: [0, 0, -0.02]}
      u1: {translation: [0, 0, -0.02]}
  - name: slide
    steps: 3
    motions:
      u0: {translation: [0.03, 0, -0.02]}
      u1: {translation: [0.03, 0, -0.02]}
contact: {self_contact: false, friction: 0.3, beams: [lower, upper]}
output: {vtk_every: 2, checkpoint_every: 2, progress_seconds: 100}
)";

/// Runs `nodus ARGS`; returns its exit status, stderr into `err`.
int run_nodus(const std::string& args, const std::filesystem::path& scratch, std::string* err = nullptr) {
  const std::filesystem::path log = scratch / "stderr.txt";
  const std::string cmd = std::string(NODUS_BINARY) + " " + args + " 2> " + log.string() + " > /dev/null";
  const int raw = std::system(cmd.c_str());
  if (err) *err = read_text(log);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::filesystem::path write_scenario(const std::filesystem::path& dir, const std::string& text) {
  const std::filesystem::path path = dir / "crossing.yaml";
  std::ofstream(path) << text;
  return path;
}

/// The relative difference of `a` from `b` printed with `digits` significant digits is within rounding.
void expect_printed(double value, const std::string& printed, int digits, const std::string& what) {
  const double reference = std::stod(printed);
  const double tolerance = std::pow(10.0, 1 - digits) * std::max(std::abs(reference), 1e-300) + 1e-300;
  EXPECT_NEAR(value, reference, tolerance) << what << ": " << printed;
}

/// Column `name`'s index in a CSV header.
std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw std::runtime_error("no column " + name);
  return static_cast<std::size_t>(it - header.begin());
}

class ResultH5 : public ::testing::Test {
 protected:
  void SetUp() override {
    scenario_ = write_scenario(scratch_.path(), kCrossing);
    out_ = scratch_.path() / "run";
    std::string err;
    ASSERT_EQ(
        run_nodus("run " + scenario_.string() + " --out " + out_.string() + " -q", scratch_.path(), &err), 0)
        << err;
  }
  ScratchDir scratch_;
  std::filesystem::path scenario_, out_;
};

TEST_F(ResultH5, HoldsWhatTheTextFilesHold) {
  const ResultRun run = read_result_h5(out_);
  EXPECT_EQ(run.name, "main");

  // Beams as the scenario declares them: 41, 41 and 5 nodes, numbered one beam after the other.
  ASSERT_EQ(run.beams.size(), 3u);
  const std::vector<std::string> names = {"lower", "upper", "pin"};
  const std::vector<double> radii = {0.1, 0.1, 0.2}, young = {4000, 4000, 200000};
  const std::vector<int> first = {0, 41, 82}, count = {41, 41, 5};
  for (std::size_t b = 0; b < 3; ++b) {
    EXPECT_EQ(run.beams[b].name, names[b]);
    EXPECT_EQ(run.beams[b].radius, radii[b]);
    EXPECT_EQ(run.beams[b].young_modulus, young[b]);
    EXPECT_EQ(run.beams[b].first_node, first[b]);
    EXPECT_EQ(run.beams[b].node_count, count[b]);
    EXPECT_EQ(run.beams[b].tool, b == 2);
  }
  // Stages: press over load time [0, 1], slide over [1, 2] (duration 1 each, the default).
  ASSERT_EQ(run.stages.size(), 2u);
  EXPECT_EQ(run.stages[0].name, "press");
  EXPECT_EQ(run.stages[1].name, "slide");
  EXPECT_DOUBLE_EQ(run.stages[0].start_time, 0.0);
  EXPECT_DOUBLE_EQ(run.stages[0].end_time, 1.0);
  EXPECT_DOUBLE_EQ(run.stages[1].start_time, 1.0);
  EXPECT_DOUBLE_EQ(run.stages[1].end_time, 2.0);

  // The states are the steps of the VTK pictures: 0, 2, 4, 6.
  std::set<int> pictures;
  for (const auto& entry : std::filesystem::directory_iterator(out_ / "vtk")) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("step_")) pictures.insert(std::stoi(name.substr(5, 6)));
  }
  std::set<int> states;
  for (const ResultState& s : run.states) states.insert(s.step);
  EXPECT_EQ(states, pictures);
  EXPECT_EQ(states, (std::set<int>{0, 2, 4, 6}));

  // Load time and stage of each state: those of its row in steps.csv (step 0: load time 0, first stage).
  const auto steps = csv_records(read_text(out_ / "steps.csv"));
  const std::size_t step_col = column(steps[0], "step"), time_col = column(steps[0], "time");
  const std::size_t stage_col = column(steps[0], "stage");
  ASSERT_EQ(steps.size(), 7u);
  for (const ResultState& s : run.states) {
    if (s.step == 0) {
      EXPECT_EQ(s.load_time, 0.0);
      EXPECT_EQ(s.stage, "press");
      EXPECT_TRUE(s.contacts.normal_force.empty());  // no computed force before the first step
      continue;
    }
    const auto& row = steps[static_cast<std::size_t>(s.step)];
    ASSERT_EQ(std::stoi(row[step_col]), s.step);
    expect_printed(s.load_time, row[time_col], 10, "load time");
    EXPECT_EQ(s.stage, row[stage_col]);
  }

  // The step table: every column of steps.csv, value by value (as result_h5_text prints the datasets: the
  // path, the shape, then the values, strings in single quotes).
  const std::string text = result_h5_text(out_ / "result.h5");
  for (std::size_t c = 0; c < steps[0].size(); ++c) {
    const std::string& name = steps[0][c];
    const std::string head = "\n/steps/" + name + " [6] ";
    const std::size_t at = text.find(head);
    ASSERT_NE(at, std::string::npos) << name;
    const std::string values = text.substr(at + head.size(), text.find('\n', at + 1) - at - head.size());
    if (name == "stage" || name == "cutback_causes") {
      std::string expected;
      for (std::size_t r = 1; r < steps.size(); ++r) expected += "'" + steps[r][c] + "' ";
      EXPECT_EQ(values, expected) << name;
      continue;
    }
    std::istringstream in(values);
    for (std::size_t r = 1; r < steps.size(); ++r) {
      std::string value;
      in >> value;
      if (steps[r][c].empty())
        EXPECT_EQ(value, "nan") << name;
      else
        expect_printed(std::stod(value), steps[r][c], 10, name);
    }
  }

  // The last state: final_nodes.csv, node by node (12 significant digits).
  const ResultState& last = run.states.back();
  const auto nodes = csv_records(read_text(out_ / "final_nodes.csv"));
  ASSERT_EQ(nodes.size(), 1u + 87u);
  ASSERT_EQ(last.centre.size(), 87u);
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    const auto& row = nodes[k];
    const auto b = static_cast<std::size_t>(std::find(names.begin(), names.end(), row[0]) - names.begin());
    const auto n = static_cast<std::size_t>(first[b] + std::stoi(row[1]));
    for (int c = 0; c < 3; ++c) {
      const auto i = static_cast<std::size_t>(c);
      expect_printed(last.centre[n][i], row[3 + i], 12, "centre");
      expect_printed(last.g1[n][i], row[6 + i], 12, "g1");
      expect_printed(last.g2[n][i], row[9 + i], 12, "g2");
    }
  }
  // The strain measures of the VTK point data: e33 = (r'.r' - 1)/2 is 0 on the unloaded pin.
  ASSERT_EQ(last.node_fields.size(), 15u);
  for (const char* name : {"e11", "e22", "e12", "e13", "e23", "e33", "q11", "q12", "q21", "q22", "k1", "k2",
                           "m11", "m22", "m12"})
    ASSERT_EQ(last.node_fields.at(name).size(), 87u) << name;
  EXPECT_NEAR(last.node_fields.at("e33")[84], 0.0, 1e-12);

  // Its contact elements: contact_final.csv, row by row (10 significant digits), beams by index.
  const auto contact = csv_records(read_text(out_ / "contact_final.csv"));
  const auto& h = contact[0];
  ASSERT_GT(contact.size(), 1u);
  ASSERT_EQ(last.contacts.size(), contact.size() - 1);
  ASSERT_EQ(last.contacts.normal_force.size(), last.contacts.size());
  double total = 0.0;
  for (std::size_t k = 0; k < last.contacts.size(); ++k) {
    const auto& row = contact[k + 1];
    EXPECT_EQ(last.contacts.zone[k], std::stoi(row[column(h, "zone")]));
    EXPECT_EQ(names[static_cast<std::size_t>(last.contacts.beam_i[k])], row[column(h, "beam_i")]);
    EXPECT_EQ(names[static_cast<std::size_t>(last.contacts.beam_j[k])], row[column(h, "beam_j")]);
    const char* axes[] = {"x", "y", "z"};
    for (std::size_t c = 0; c < 3; ++c) {
      expect_printed(last.contacts.x_i[k][c], row[column(h, std::string(axes[c]) + "_i")], 10, "x_i");
      expect_printed(last.contacts.x_j[k][c], row[column(h, std::string(axes[c]) + "_j")], 10, "x_j");
      expect_printed(last.contacts.normal[k][c], row[column(h, std::string("n") + axes[c])], 10, "normal");
    }
    expect_printed(last.contacts.gap[k], row[column(h, "gap")], 10, "gap");
    expect_printed(last.contacts.normal_force[k], row[column(h, "normal_force")], 10, "normal_force");
    expect_printed(last.contacts.tangential_force[k], row[column(h, "tangential_force")], 10, "|T|");
    EXPECT_EQ(last.contacts.state[k], row[column(h, "state")]);
    total += last.contacts.normal_force[k];
  }
  // The sum of R_N is steps.csv's normal_force of the last step (docs/output.md).
  expect_printed(total, steps.back()[column(steps[0], "normal_force")], 8, "sum of R_N");
}

TEST_F(ResultH5, XdmfIndexNamesTheStatesInTheFile) {
  const auto xdmf = parse_xml(read_text(out_ / "result.xmf"));
  ASSERT_EQ(xdmf->name, "Xdmf");
  const auto& series = xdmf->one("Domain").one("Grid");
  EXPECT_EQ(series.attribute("CollectionType"), "Temporal");
  const auto grids = series.all("Grid");
  const ResultRun run = read_result_h5(out_);
  ASSERT_EQ(grids.size(), run.states.size());
  const std::string text = result_h5_text(out_ / "result.h5");
  for (std::size_t k = 0; k < grids.size(); ++k) {
    EXPECT_DOUBLE_EQ(std::stod(grids[k]->one("Time").attribute("Value")), run.states[k].load_time);
    // Polylines of two nodes: 20 + 20 + 2 elements of two segments each.
    const auto& topology = grids[k]->one("Topology");
    EXPECT_EQ(topology.attribute("TopologyType"), "Polyline");
    EXPECT_EQ(topology.attribute("NumberOfElements"), "84");
    EXPECT_EQ(grids[k]->one("Geometry").one("DataItem").attribute("Dimensions"), "87 3");
    // Every array it names is a dataset of result.h5 of that shape.
    std::vector<const testing::XmlElement*> items = {&topology.one("DataItem"),
                                                     &grids[k]->one("Geometry").one("DataItem")};
    for (const auto* a : grids[k]->all("Attribute")) items.push_back(&a->one("DataItem"));
    EXPECT_EQ(items.size(), 2u + 1u + 3u + 15u);
    for (const auto* item : items) {
      const std::string& ref = item->text;
      ASSERT_TRUE(ref.starts_with("result.h5:/")) << ref;
      std::string dims = item->attribute("Dimensions");
      std::replace(dims.begin(), dims.end(), ' ', 'x');
      EXPECT_NE(text.find("\n" + ref.substr(10) + " [" + dims + "] "), std::string::npos) << ref;
    }
  }
}

TEST_F(ResultH5, ResumedRunHasTheContentOfTheRunNeverStopped) {
  const std::set<std::string> provenance = {"nodus",   "commit",    "processor",     "hardware_threads",
                                            "threads", "mpi_ranks", "linear_solvers"};
  const std::string reference = result_h5_text(out_ / "result.h5", provenance);
  const std::filesystem::path out = scratch_.path() / "stopped";
  std::string err;
  // Stopped after 5 steps: states 0, 2, 4 written, the checkpoint of step 4 the newest; step 5's row dropped.
  EXPECT_EQ(run_nodus("run " + scenario_.string() + " --out " + out.string() + " -q --stop-after-steps 5",
                      scratch_.path(), &err),
            3)
      << err;
  EXPECT_EQ(read_result_h5(out).states.size(), 3u);
  ASSERT_EQ(run_nodus("run " + scenario_.string() + " --out " + out.string() + " -q --resume",
                      scratch_.path(), &err),
            0)
      << err;
  EXPECT_EQ(result_h5_text(out / "result.h5", provenance), reference);
  EXPECT_FALSE(std::filesystem::exists(out / "result.h5.damaged"));
}

TEST_F(ResultH5, ResumeFromAnOlderCheckpointDropsTheStatesWrittenAfterIt) {
  // A run killed after writing states its newest checkpoint does not hold: here the finished run's folder
  // with only the checkpoint of the end of `press` (step 3) left, and states 0, 2, 4 and 6 in result.h5. The
  // resume drops 4 and 6, computes steps 4 to 6 again and must end with the content of the run never stopped.
  const std::set<std::string> provenance = {"nodus",   "commit",    "processor",     "hardware_threads",
                                            "threads", "mpi_ranks", "linear_solvers"};
  const std::string reference = result_h5_text(out_ / "result.h5", provenance);
  const std::filesystem::path out = scratch_.path() / "older";
  std::filesystem::copy(out_, out, std::filesystem::copy_options::recursive);
  std::filesystem::remove(out / "summary.json");
  int kept = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out / "checkpoints")) {
    if (entry.path().filename().string().rfind("000_press", 0) == 0) {
      ++kept;
    } else {
      std::filesystem::remove(entry.path());
    }
  }
  ASSERT_EQ(kept, 1);
  ASSERT_EQ(read_result_h5(out).states.size(), 4u);
  std::string err;
  ASSERT_EQ(run_nodus("run " + scenario_.string() + " --out " + out.string() + " -q --resume",
                      scratch_.path(), &err),
            0)
      << err;
  const ResultRun resumed = read_result_h5(out);
  ASSERT_EQ(resumed.states.size(), 4u);
  EXPECT_EQ(resumed.states[2].step, 4);
  EXPECT_EQ(resumed.states[3].step, 6);
  EXPECT_EQ(result_h5_text(out / "result.h5", provenance), reference);
}

TEST_F(ResultH5, DamagedFileIsMovedAsideOnResuming) {
  const std::filesystem::path out = scratch_.path() / "damaged";
  std::string err;
  EXPECT_EQ(run_nodus("run " + scenario_.string() + " --out " + out.string() + " -q --stop-after-steps 5",
                      scratch_.path(), &err),
            3);
  // A hard kill in the middle of a write: the file's first bytes (its superblock) overwritten.
  {
    std::fstream f(out / "result.h5", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(0);
    f << std::string(64, 'x');
  }
  ASSERT_EQ(run_nodus("run " + scenario_.string() + " --out " + out.string() + " -q --resume",
                      scratch_.path(), &err),
            0)
      << err;
  EXPECT_NE(err.find("result.h5: cannot be opened"), std::string::npos) << err;
  EXPECT_TRUE(std::filesystem::exists(out / "result.h5.damaged"));
  // The new file holds the states written after the resumed step (4), and the whole step table.
  const ResultRun run = read_result_h5(out);
  ASSERT_EQ(run.states.size(), 1u);
  EXPECT_EQ(run.states[0].step, 6);
  const std::string text = result_h5_text(out / "result.h5");
  EXPECT_NE(text.find("\n/steps/step [6] 1 2 3 4 5 6 \n"), std::string::npos);
}

TEST_F(ResultH5, NoneWithHdf5Off) {
  std::string text = kCrossing;
  text.replace(text.find("output: {"), 9, "output: {hdf5: false, ");
  const std::filesystem::path scenario = write_scenario(scratch_.path(), text);
  std::string err;
  // Into the folder of the run above: its result.h5 and result.xmf go.
  ASSERT_TRUE(std::filesystem::exists(out_ / "result.h5"));
  ASSERT_EQ(run_nodus("run " + scenario.string() + " --out " + out_.string() + " -q", scratch_.path(), &err),
            0)
      << err;
  EXPECT_FALSE(std::filesystem::exists(out_ / "result.h5"));
  EXPECT_FALSE(std::filesystem::exists(out_ / "result.xmf"));
  EXPECT_TRUE(std::filesystem::exists(out_ / "final_nodes.csv"));
}

TEST(ResultH5Reader, SaysWhichFileAndWhatWasExpected) {
  ScratchDir scratch;
  try {
    read_result_h5(scratch.path());
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (scratch.path() / "result.h5").string() +
                                         ": expected a nodus result file (result.h5), got none");
  }
  std::ofstream(scratch.path() / "result.h5") << "not HDF5";
  try {
    read_result_h5(scratch.path());
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("result.h5: expected an HDF5 file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nodus::output
