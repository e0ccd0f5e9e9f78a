// The stage-end tables DIR/stages/NNN_STAGE_{nodes,contact}.csv: the state at the end of each stage is the
// state a run of the stages up to it ends with (the same computation, stopped there), and the last stage's
// tables are the run's final ones.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The tool drag of examples/tool_drag.yaml, coarser: press, drag, and (when `lift`) the tool taken out.
std::string tool_drag(bool lift) {
  std::string text = R"(units: {length: mm, force: N, stress: MPa, time: s}
materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 20, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 4, start: [0, -1, 0.31],
     direction: [0, 1, 0], director1: [-1, 0, 0]}
conditions:
  - {name: left, type: clamp, beam: beam, at: start, dofs: [position, g1z]}
  - {name: right, type: clamp, beam: beam, at: end, dofs: [y, z]}
  - {name: press, type: rigid, beam: tool}
stages:
  - name: press
    steps: 3
    motions:
      press: {translation: [0, 0, -0.1]}
  - name: drag
    steps: 4
    motions:
      press: {translation: [0, 0.2, -0.1]}
)";
  if (lift) text += "  - name: lift\n    steps: 1\n    contact_off: [tool]\n";
  return text + "contact:\n  self_contact: false\n  friction: 0.3\noutput: {vtk_every: 0}\n";
}

TEST(StageFiles, HoldTheStateOfEachStageEnd) {
  const fs::path full = scratch() / "stages_full", partial = scratch() / "stages_partial";
  fs::remove_all(full);
  fs::remove_all(partial);
  ASSERT_EQ(
      run_nodus("run " + write("stages_full.yaml", tool_drag(true)).string() + " --out " + full.string())
          .status,
      0);
  ASSERT_EQ(run_nodus("run " + write("stages_partial.yaml", tool_drag(false)).string() + " --out " +
                      partial.string())
                .status,
            0);
  // The end of `drag` in the full run is the final state of the run that stops after `drag`.
  EXPECT_EQ(read(full / "stages" / "001_drag_nodes.csv"), read(partial / "final_nodes.csv"));
  EXPECT_EQ(read(full / "stages" / "001_drag_contact.csv"), read(partial / "contact_final.csv"));
  EXPECT_EQ(read(partial / "stages" / "001_drag_nodes.csv"), read(partial / "final_nodes.csv"));
  // The last stage's tables are the final ones.
  EXPECT_EQ(read(full / "stages" / "002_lift_nodes.csv"), read(full / "final_nodes.csv"));
  EXPECT_EQ(read(full / "stages" / "002_lift_contact.csv"), read(full / "contact_final.csv"));
  EXPECT_TRUE(fs::exists(full / "stages" / "000_press_nodes.csv"));
  EXPECT_NE(read(full / "stages" / "000_press_nodes.csv"), read(full / "stages" / "001_drag_nodes.csv"));
}

TEST(StageFiles, StaleOnesAreRemovedByANewRun) {
  const fs::path dir = scratch() / "stages_stale";
  fs::remove_all(dir);
  fs::create_directories(dir / "stages");
  std::ofstream(dir / "stages" / "007_gone_nodes.csv") << "stale\n";
  std::ofstream(dir / "stages" / "notes.txt") << "kept\n";
  ASSERT_EQ(
      run_nodus("run " + write("stages_stale.yaml", tool_drag(false)).string() + " --out " + dir.string())
          .status,
      0);
  EXPECT_FALSE(fs::exists(dir / "stages" / "007_gone_nodes.csv"));
  EXPECT_TRUE(fs::exists(dir / "stages" / "notes.txt"));  // not a stage file: left alone
  EXPECT_TRUE(fs::exists(dir / "stages" / "001_drag_nodes.csv"));
}

}  // namespace
