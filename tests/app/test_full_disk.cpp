// A run whose disk fills up, or cannot be written at all: it stops with exit status 4 and one line naming the
// file and the system's reason; its folder, moved to a disk with room, resumes to the files of the run never
// stopped. The disk is a tmpfs of 300 kB mounted for the test; where mounting is not allowed (not root, a
// container without the capability), the test is skipped and tests/output's
// AtomicFile.AFullDiskIsSaidAndTheTargetKept, on /dev/full, still checks the message.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

using nodus::testing::expect_same_results;
using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

/// A tmpfs mounted at `at` with mount `options` for the life of the object, if this process may mount one.
class SmallDisk {
 public:
  SmallDisk(const fs::path& at, const std::string& options) : at_(at) {
    fs::create_directories(at_);
    const std::string command = "mount -t tmpfs -o " + options + " tmpfs " + at_.string() + " 2> /dev/null";
    mounted_ = std::system(command.c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) [[maybe_unused]]
      const int ignored = std::system(("umount " + at_.string()).c_str());
  }
  bool mounted() const { return mounted_; }

 private:
  fs::path at_;
  bool mounted_ = false;
};

TEST(FullDisk, StopsWithItsCauseAndResumesElsewhere) {
  std::string text = nodus::testing::long_drag();
  text.replace(text.find("  vtk_every: 2\n"), 14, "  vtk_every: 100\n  checkpoint_every: 10\n");
  const fs::path scenario = write("full_disk.yaml", text);
  const fs::path reference = scratch() / "full_disk_ref";
  fs::remove_all(reference);
  const Result full = run_nodus("run " + scenario.string() + " --out " + reference.string() + " -q");
  ASSERT_EQ(full.status, 0) << full.err;

  const fs::path moved = scratch() / "full_disk_moved";
  fs::remove_all(moved);
  {
    SmallDisk disk(scratch() / "small_disk", "size=300k");
    if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
    const fs::path out = scratch() / "small_disk" / "run";
    const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q");
    EXPECT_EQ(r.status, 4) << r.err;
    EXPECT_EQ(r.err.rfind("nodus: cannot write '" + out.string() + "/", 0), 0u) << r.err;
    // The file that did not fit was refused before it was written: its size and the free space are said.
    EXPECT_NE(r.err.find("': No space left on device (it takes "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" are free); the run stopped there: once the cause is removed, continue it with "
                         "--resume from its newest checkpoint\n"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(fs::exists(out / "checkpoints" / "latest.nodus-state"));
    fs::copy(out, moved, fs::copy_options::recursive);
  }
  const Result resumed = run_nodus("run " + scenario.string() + " --out " + moved.string() + " -q --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  expect_same_results(reference, moved);
}

// A run whose pictures will not fit on its disk says so when it starts, from the size of its first picture
// and the number of pictures its stages' steps will write.
TEST(FullDisk, PicturesThatWillNotFitAreForetold) {
  std::string text = nodus::testing::long_drag();
  text.replace(text.find("  vtk_every: 2\n"), 14, "  vtk_every: 1\n");
  const fs::path scenario = write("short_of_space.yaml", text);
  SmallDisk disk(scratch() / "small_disk", "size=300k");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path out = scratch() / "small_disk" / "run";
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q");
  EXPECT_EQ(r.status, 4) << r.err;
  const std::size_t warning =
      r.err.find("the pictures of this run may not fit on its disk: 307 more VTK outputs");
  EXPECT_NE(warning, std::string::npos) << r.err;
  EXPECT_LT(warning, r.err.find("nodus: cannot write")) << r.err;
}

// A read-only file system: the run cannot even make its folder, and says so.
TEST(FullDisk, AReadOnlyFileSystemIsSaid) {
  const fs::path scenario = write("read_only.yaml", nodus::testing::kDrag);
  SmallDisk disk(scratch() / "read_only_disk", "size=100k,ro");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here";
  const fs::path out = scratch() / "read_only_disk" / "run";
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q");
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_EQ(r.err, "nodus: cannot create folder '" + out.string() +
                       "': Read-only file system; the run stopped there: it has no checkpoint yet: once the "
                       "cause is removed, run it again\n");
}

}  // namespace
