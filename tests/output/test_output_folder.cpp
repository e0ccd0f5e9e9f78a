// The output folder of a run: --out must be a folder or creatable (a file, or a path under one, is bad
// input), and the temporary files a killed run leaves (AtomicFile's, seen on disk while one is open) are
// removed from the folders nodus writes, and nothing else is.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/output_folder.hpp"
#include "nodus/scenario/scenario.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

/// The message of the ScenarioError that check_output_folder throws for `dir`, or "accepted".
std::string verdict(const fs::path& dir) {
  try {
    check_output_folder(dir);
  } catch (const scenario::ScenarioError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(OutputFolder, AFolderOrACreatablePath) {
  ScratchDir dir;
  const fs::path file = dir.path() / "file.txt";
  std::ofstream(file) << "x";
  EXPECT_EQ(verdict(dir.path()), "accepted");
  EXPECT_EQ(verdict(dir.path() / "new"), "accepted");
  EXPECT_EQ(verdict(dir.path() / "new" / "deeper" / "still"), "accepted");
  EXPECT_EQ(verdict(file),
            file.string() +
                ": --out: expected a folder, or a path where one can be created, got an existing "
                "file that is not a folder");
  EXPECT_EQ(verdict(file / "sub" / "out"), (file / "sub" / "out").string() +
                                               ": --out: expected a folder, or a path where one can be "
                                               "created, got a path under the file '" +
                                               file.string() + "'");
  EXPECT_NE(verdict(fs::path()).find("got an empty path"), std::string::npos);
  // A relative path is taken from the current folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  EXPECT_EQ(
      verdict("file.txt/out"),
      "file.txt/out: --out: expected a folder, or a path where one can be created, got a path under the "
      "file '" +
          file.string() + "'");
  EXPECT_EQ(verdict("relative/new"), "accepted");
  fs::current_path(cwd);
}

TEST(OutputFolder, TheTemporaryFileOfAnOpenAtomicFileHasTheNameThatIsCleanedUp) {
  ScratchDir dir;
  for (const char* name :
       {"steps.csv", "result.pvd", "step_000003.vtp", "summary.json", "001_drag.nodus-state"}) {
    AtomicFile file(dir.path() / name);
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir.path()))
      names.insert(entry.path().filename().string());
    ASSERT_EQ(names.size(), 1u) << name;
    const std::string temp = *names.begin();
    EXPECT_TRUE(is_temporary_file_name(temp)) << temp;
    EXPECT_EQ(temp, temporary_path(name, ::getpid()).string());
  }
  for (const char* name : {"steps.csv", "notes.tmp12", "steps.csv.tmp", "steps.csv.tmpx1", ".csv.tmp1",
                           "steps.csv.tmp12.bak", "data.txt.tmp12"})
    EXPECT_FALSE(is_temporary_file_name(name)) << name;
}

TEST(OutputFolder, RemovesOnlyTemporaryFilesInTheFoldersItWrites) {
  ScratchDir dir;
  const fs::path& out = dir.path();
  const auto touch = [](const fs::path& path) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "x";
  };
  const std::vector<fs::path> stale = {
      out / "steps.csv.tmp4242",
      out / "summary.json.tmp7",
      out / "vtk" / "step_000004.vtp.tmp4242",
      out / "contact" / "contact_000004.csv.tmp4242",
      out / "stages" / "001_drag_nodes.csv.tmp4242",
      out / "checkpoints" / "latest.nodus-state.tmp4242",
      out / "branches" / "mu_0.1" / "final_nodes.csv.tmp99",
      out / "branches" / "mu_0.1" / "checkpoints" / "002_back.nodus-state.tmp99",
  };
  const std::vector<fs::path> kept = {
      out / "steps.csv",
      out / "notes.tmp5",                            // not a name nodus writes
      out / "vtk" / "step_000004.vtp",               // a result, not a temporary file
      out / "mine" / "steps.csv.tmp4242",            // not a folder nodus writes
      out / "vtk" / "old" / "step_000001.vtp.tmp1",  // below one
      out / "branches" / "steps.csv.tmp3",           // branches/ holds folders only
  };
  for (const fs::path& p : stale) touch(p);
  for (const fs::path& p : kept) touch(p);
  fs::create_directories(out / "result.pvd.tmp8");  // a folder, not a file
  EXPECT_EQ(remove_stale_temporary_files(out), stale.size());
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  EXPECT_TRUE(fs::is_directory(out / "result.pvd.tmp8"));
  EXPECT_EQ(remove_stale_temporary_files(out), 0u);
  EXPECT_EQ(remove_stale_temporary_files(out / "absent"), 0u);
}

}  // namespace
}  // namespace nodus::output
