// Whole-file writes through a temporary file and a rename: content, replacement, no leftovers, and errors
// that name the path.

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

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

}  // namespace
}  // namespace nodus::output
