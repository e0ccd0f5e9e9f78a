#pragma once
// Running the nodus binary from the command-line tests: a scratch folder per test process, the exit status
// and stderr of one call, and scenario files written into the scratch folder.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nodus::testing {

namespace fs = std::filesystem;

struct Result {
  int status;       ///< exit status (-1: did not exit normally)
  std::string err;  ///< what it wrote on stderr
};

/// A folder of this test process, created on first use.
inline fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("nodus_app_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
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

/// Writes `text` to scratch()/name and returns its path.
inline fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p;
}

}  // namespace nodus::testing
