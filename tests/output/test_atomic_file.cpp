// Whole-file writes through a temporary file and a rename: content, replacement, no leftovers, and errors
// that name the path and the system's reason.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "nodus/output/atomic_file.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using testing::read_text;
using testing::ScratchDir;

int count_files(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplacesWithoutLeftovers) {
  ScratchDir dir;
  const auto path = dir.path() / "a.txt";
  write_file_atomically(path, "first\n");
  EXPECT_EQ(read_text(path), "first\n");
  write_file_atomically(path, "second");
  EXPECT_EQ(read_text(path), "second");
  EXPECT_EQ(count_files(dir.path()), 1);
}

TEST(AtomicFile, UncommittedWriteLeavesTargetUntouched) {
  ScratchDir dir;
  const auto path = dir.path() / "a.txt";
  write_file_atomically(path, "kept");
  {
    AtomicFile file(path);
    file.stream() << "never seen";
  }
  EXPECT_EQ(read_text(path), "kept");
  EXPECT_EQ(count_files(dir.path()), 1);
}

TEST(AtomicFile, ErrorNamesThePath) {
  ScratchDir dir;
  const auto path = dir.path() / "missing_folder" / "a.txt";
  try {
    write_file_atomically(path, "x");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

// A full disk: the temporary file is made a link to /dev/full, where every write fails with ENOSPC. The error
// names the target and the system's reason, and the target keeps its content.
TEST(AtomicFile, AFullDiskIsSaidAndTheTargetKept) {
  ScratchDir dir;
  const auto path = dir.path() / "a.txt";
  write_file_atomically(path, "kept");
  std::filesystem::create_symlink("/dev/full", temporary_path(path, static_cast<long>(::getpid())));
  try {
    write_file_atomically(path, "lost");
    FAIL() << "no exception";
  } catch (const WriteError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write '" + path.string() + "': No space left on device");
  }
  EXPECT_EQ(read_text(path), "kept");
  EXPECT_EQ(count_files(dir.path()), 1);  // the temporary file (here the link) removed
}

// A file larger than the free space of its disk is refused before a byte of it is written, with its size and
// the space there is; the target keeps its content.
TEST(AtomicFile, AFileLargerThanTheFreeSpaceIsRefusedBeforeWriting) {
  ScratchDir dir;
  const auto path = dir.path() / "a.txt";
  write_file_atomically(path, "kept");
  const std::uintmax_t free = std::filesystem::space(dir.path()).available;
  try {
    require_space(dir.path(), free + 1'000'000'000'000, path);
    FAIL() << "no exception";
  } catch (const WriteError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("cannot write '" + path.string() + "': No space left on device (it takes ", 0),
              0u)
        << message;
    EXPECT_NE(message.find(" GB, "), std::string::npos) << message;
    EXPECT_NE(message.find(" are free)"), std::string::npos) << message;
  }
  EXPECT_NO_THROW(require_space(dir.path(), 0, path));
  EXPECT_NO_THROW(require_space(dir.path() / "no such folder", 1'000'000'000'000'000, path));  // cannot tell
  EXPECT_EQ(read_text(path), "kept");
}

TEST(HumanSize, DecimalUnits) {
  EXPECT_EQ(human_size(0), "0 bytes");
  EXPECT_EQ(human_size(999), "999 bytes");
  EXPECT_EQ(human_size(1500), "2 kB");
  EXPECT_EQ(human_size(2'340'000), "2.3 MB");
  EXPECT_EQ(human_size(7'800'000'000), "7.8 GB");
}

}  // namespace
}  // namespace nodus::output
