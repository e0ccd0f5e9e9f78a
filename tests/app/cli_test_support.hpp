#pragma once
// Running the nodus binary from the command-line tests: a scratch folder per test process, the exit status
// and stderr of one call, and scenario files written into the scratch folder.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nodus/output/result_h5.hpp"

namespace nodus::testing {

namespace fs = std::filesystem;

struct Result {
  int status;       ///< exit status (-1: did not exit normally)
  std::string err;  ///< what it wrote on stderr
};

/// A folder of this test process, created on first use and removed when the process ends, unless a test of
/// it failed (then its files are left for a look, and the failure message names them through their paths).
inline fs::path scratch() {
  struct Folder {
    fs::path path = fs::temp_directory_path() / ("nodus_app_" + std::to_string(::getpid()));
    // Destroyed before gtest's UnitTest, which exists before any test asks for the folder.
    ~Folder() {
      if (!::testing::UnitTest::GetInstance()->Passed()) return;
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  fs::create_directories(folder.path);
  return folder.path;
}

/// Runs `nodus ARGS`, stdout discarded.
inline Result run_nodus(const std::string& args) {
  const fs::path err = scratch() / "stderr.txt";
  const std::string cmd = std::string(NODUS_BINARY) + " " + args + " 2> " + err.string() + " > /dev/null";
  const int raw = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text.str()};
}

/// The whole content of the file at `path` (empty if it cannot be read).
inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Writes `text` to scratch()/name and returns its path.
inline fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p;
}

/// A tool beam presses a beam on two supports, drags it with friction, moves back and is lifted off:
/// four stages, 11 steps, contact forces and friction (examples/tool_drag.yaml, coarser).
inline const std::string kDrag = R"(materials:
  - {name: nylon, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: beam, material: nylon, radius: 0.1, length: 10, elements: 20, start: [-5, 0, 0],
     direction: [1, 0, 0], director1: [0, 1, 0]}
  - {name: tool, material: nylon, radius: 0.2, length: 2, elements: 2, start: [0, -1, 0.31],
     direction: [0, 1, 0], director1: [1, 0, 0]}
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
      press: {translation: [0, 0.3, -0.1]}
  - name: back
    steps: 3
    motions:
      press: {translation: [0, 0.1, -0.1]}
  - name: lift
    steps: 1
    contact_off: [tool]
contact:
  self_contact: false
  friction: 0.3
output:
  vtk_every: 2
  contact_csv: true
)";

/// kDrag with a drag stage of 300 steps (seconds): long enough to be stopped, or to fill a small disk, in the
/// middle.
inline std::string long_drag() {
  std::string text = kDrag;
  const std::string drag = "  - name: drag\n    steps: 4\n";
  text.replace(text.find(drag), drag.size(), "  - name: drag\n    steps: 300\n");
  return text;
}

/// The branches: `same` repeats the main run's stages after drag with its friction, `mu_0.1` moves back with
/// less friction.
inline const std::string kBranches = R"(branches:
  - name: same
    from: drag
    stages:
      - name: back
        steps: 3
        motions:
          press: {translation: [0, 0.1, -0.1]}
      - name: lift
        steps: 1
        contact_off: [tool]
  - name: mu_0.1
    from: drag
    contact: {friction: 0.1}
    stages:
      - name: back
        steps: 3
        motions:
          press: {translation: [0, 0.1, -0.1]}
)";

/// `text` (a timing.csv) without its last column, wall_seconds: what two runs of one scenario share.
inline std::string without_wall_times(const std::string& text) {
  std::string out;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string line = text.substr(begin, end - begin);
    out += line.substr(0, line.rfind(',')) + "\n";
    begin = end + 1;
  }
  return out;
}

/// The attributes of result.h5 that describe the process that wrote it (docs/output.md).
inline const std::set<std::string> kProvenanceAttributes = {
    "nodus", "commit", "processor", "hardware_threads", "threads", "mpi_ranks", "linear_solvers"};

/// Every file under `dir` by relative path, with its content; checkpoints and summary.json (they hold wall
/// times) left out, and timing.csv without its wall times.
inline std::map<std::string, std::string> results(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = fs::relative(entry.path(), dir).generic_string();
    if (name.find("checkpoints/") != std::string::npos || name.ends_with("summary.json")) continue;
    if (name.ends_with("result.h5")) {
      // Its content, not its bytes (HDF5 places what a resumed run rewrites elsewhere in the file), without
      // the provenance of the process that wrote it.
      files[name] = output::result_h5_text(entry.path(), kProvenanceAttributes);
      continue;
    }
    files[name] =
        name.ends_with("timing.csv") ? without_wall_times(read_file(entry.path())) : read_file(entry.path());
  }
  return files;
}

inline void expect_same_results(const fs::path& reference, const fs::path& dir) {
  const auto a = results(reference), b = results(dir);
  std::vector<std::string> names_a, names_b;
  for (const auto& [name, text] : a) names_a.push_back(name);
  for (const auto& [name, text] : b) names_b.push_back(name);
  ASSERT_EQ(names_a, names_b);
  for (const auto& [name, text] : a) EXPECT_TRUE(text == b.at(name)) << name << " differs";
}

}  // namespace nodus::testing
