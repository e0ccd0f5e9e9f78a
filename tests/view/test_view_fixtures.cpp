// Writes the pages that tests/view/browser_test.mjs opens in headless Chromium: a small run, a run with
// contact elements, a tool and a branch, and (with NODUS_VIEW_BIG=1) a large one of 75 fibres x 100 elements
// x 300 states, decimated to the size budget. Into the folder NODUS_VIEW_PAGES; skipped without it (ctest's
// view_pages test sets it, tests/CMakeLists.txt).

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "nodus/output/atomic_file.hpp"
#include "nodus/output/view_page.hpp"
#include "nodus/output/viewer_bundle.hpp"
#include "view_fixtures.hpp"

namespace nodus::output {
namespace {

std::filesystem::path pages_folder() {
  const char* dir = std::getenv("NODUS_VIEW_PAGES");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::path();
}

/// Writes `run` to FOLDER/NAME.html and prints its size and the time taken.
void write(const ResultRun& run, const std::string& name, const ViewOptions& options = {}) {
  const auto start = std::chrono::steady_clock::now();
  const std::filesystem::path path = pages_folder() / (name + ".html");
  write_view_page(run, path, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %s in %.2f s\n", path.c_str(), human_size(std::filesystem::file_size(path)).c_str(),
              seconds);
}

TEST(ViewPages, Write) {
  if (pages_folder().empty()) GTEST_SKIP() << "NODUS_VIEW_PAGES not set";
  if (viewer_bundle().empty()) GTEST_SKIP() << "nodus was built without the viewer's page script";
  std::filesystem::create_directories(pages_folder());
  test::HelixRunSpec small;
  small.fibres = 2;
  small.elements = 8;
  small.states = 5;
  ViewOptions options;
  options.title = "small: 2 fibres";
  write(test::helix_run(small), "small", options);

  test::HelixRunSpec contact;
  contact.fibres = 3;
  contact.elements = 20;
  contact.states = 24;
  contact.contact = true;
  contact.branch_states = 8;
  options.title = "contact: 3 fibres, a tool, a branch";
  write(test::helix_run(contact), "contact", options);

  if (const char* big = std::getenv("NODUS_VIEW_BIG"); big != nullptr && std::string(big) == "1") {
    test::HelixRunSpec large;
    large.fibres = 75;
    large.elements = 100;
    large.states = 300;
    large.radius = 0.02;
    large.length = 10.0;
    large.contact = true;
    options.title = "big: 75 fibres x 100 elements x 300 states";
    write(test::helix_run(large), "big", options);
  }
}

}  // namespace
}  // namespace nodus::output
