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
  return nodus::testing::read_file(path);
}

/// The tool drag of the resume tests (kDrag: press, drag, back, lift), or only its first two stages.
std::string tool_drag(bool whole) {
  const std::string& text = nodus::testing::kDrag;
  if (whole) return text;
  return text.substr(0, text.find("  - name: back")) + text.substr(text.find("contact:"));
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
  EXPECT_EQ(read(full / "stages" / "003_lift_nodes.csv"), read(full / "final_nodes.csv"));
  EXPECT_EQ(read(full / "stages" / "003_lift_contact.csv"), read(full / "contact_final.csv"));
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
