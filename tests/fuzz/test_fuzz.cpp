// The scenario fuzzer (docs/layout.md, "tests/fuzz/"): seeded mutations of every example and of the test
// scenarios in tests/fuzz/seeds, each read as `nodus check` reads it, its model built where it is not large,
// and one Newton iteration of its run made where it is small. Any scenario must be refused with a "FILE:LINE:
// KEY: expected ..." line (status 2), or build and run (status 0 or 3); anything else is a defect: another
// exception (status 1), a refusal without its line, a mutant that takes longer than a bound, and under the
// sanitizers any report (the process stops there).
//
// NODUS_FUZZ_SEED (a number, or `random`), NODUS_FUZZ_MUTANTS, NODUS_FUZZ_BUILD_ELEMENTS and
// NODUS_FUZZ_RUN_DOFS change the defaults;
// NODUS_FUZZ_TRACE=1 writes each mutant's name to stderr before it is judged (to find one that hangs).

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "mutate.hpp"
#include "nodus/scenario/scenario.hpp"
#include "nodus/simulation/simulation.hpp"

namespace nodus::fuzz {
namespace {

namespace fs = std::filesystem;

// The time a mutant may take: a second, and 0.2 ms an element of its model (Release builds the 3x25 yarn's
// 7,500 elements in 0.25 s, 0.03 ms an element). The sanitizers at -O0 are some 30 times slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kSlowdown = 30.0;
constexpr std::uint64_t kDefaultMutants = 60;
#else
constexpr double kSlowdown = 1.0;
constexpr std::uint64_t kDefaultMutants = 400;
#endif
constexpr double kSecondsPerMutant = 1.0, kSecondsPerElement = 2e-4;

struct Seed {
  std::string name;  ///< relative to the source folder
  std::string path;  ///< absolute, as given to the reader
  std::string text;
};

std::vector<Seed> seeds() {
  std::vector<Seed> out;
  for (const char* folder : {"examples", "tests/fuzz/seeds"}) {
    const fs::path dir = fs::path(NODUS_SOURCE_DIR) / folder;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".yaml") continue;
      std::ifstream in(e.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      out.push_back(
          {fmt::format("{}/{}", folder, e.path().filename().string()), e.path().string(), text.str()});
    }
  }
  std::sort(out.begin(), out.end(), [](const Seed& a, const Seed& b) { return a.name < b.name; });
  return out;
}

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

enum class Outcome { refused, read, built, ran, defect };

struct Verdict {
  Outcome outcome = Outcome::defect;
  std::string defect;
  long long elements = 0;  ///< of the model, when read
};

/// "PATH:LINE: KEY: expected ...", LINE >= 1 and KEY not empty.
bool has_file_line_key(const std::string& message, const std::string& path) {
  if (message.rfind(path + ":", 0) != 0) return false;
  std::size_t i = path.size() + 1;
  const std::size_t digits = i;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  if (i == digits || message[digits] == '0' || message.compare(i, 2, ": ") != 0) return false;
  const std::size_t key = i + 2;
  const std::size_t expected = message.find(": expected ", key);
  return expected != std::string::npos && expected > key;
}

/// The mutant read as `nodus check` reads it, its model built up to `build_elements` elements and, up to
/// `run_dofs` unknowns, one Newton iteration of its run.
Verdict judge(const std::string& text, const std::string& path, long long build_elements, int run_dofs) {
  scenario::Scenario s;
  try {
    s = scenario::parse_scenario(text, path);
  } catch (const scenario::ScenarioError& e) {
    if (has_file_line_key(e.what(), path)) return {Outcome::refused, {}};
    return {Outcome::defect, fmt::format("refused without FILE:LINE: KEY: {}", e.what())};
  } catch (const std::exception& e) {
    return {Outcome::defect, fmt::format("read: internal error (status 1): {}", e.what())};
  }
  long long elements = 0;
  for (const scenario::BeamSpec& beam : s.beams) elements += beam.elements;
  if (elements > build_elements) return {Outcome::read, {}, elements};
  try {
    simulation::Simulation sim(std::move(s));
    if (sim.model().num_dofs() > run_dofs) return {Outcome::built, {}, elements};
    bool asked = false;
    simulation::RunOptions options;
    options.cancel = [&asked] { return std::exchange(asked, true); };  // after the first Newton iteration
    sim.run({}, options);
    return {Outcome::ran, {}, elements};
  } catch (const scenario::ScenarioError& e) {  // checks of the model being built: status 2 too
    if (has_file_line_key(e.what(), path)) return {Outcome::refused, {}};
    return {Outcome::defect, fmt::format("refused by the model without FILE:LINE: KEY: {}", e.what())};
  } catch (const std::exception& e) {
    return {Outcome::defect, fmt::format("build or run: internal error (status 1): {}", e.what())};
  }
}

TEST(ScenarioFuzz, EveryMutantIsRefusedWithItsLineOrBuildsAndRuns) {
  const char* seed_text = std::getenv("NODUS_FUZZ_SEED");
  const std::uint64_t seed = seed_text && std::string(seed_text) == "random"
                                 ? std::random_device{}()
                                 : env_number("NODUS_FUZZ_SEED", 1);
  const std::uint64_t mutants = env_number("NODUS_FUZZ_MUTANTS", kDefaultMutants);
  const long long build_elements = static_cast<long long>(env_number("NODUS_FUZZ_BUILD_ELEMENTS", 3000));
  const int run_dofs = static_cast<int>(env_number("NODUS_FUZZ_RUN_DOFS", 6000));
  std::printf(
      "fuzzer: seed %llu, %llu mutants, models built up to %lld elements, one Newton iteration up to %d "
      "unknowns\n",
      static_cast<unsigned long long>(seed), static_cast<unsigned long long>(mutants), build_elements,
      run_dofs);

  const std::vector<Seed> corpus = seeds();
  ASSERT_GE(corpus.size(), 10u);
  for (const Seed& s : corpus) {  // the seeds themselves are good scenarios
    const Verdict v = judge(s.text, s.path, build_elements, 0);
    ASSERT_TRUE(v.outcome == Outcome::read || v.outcome == Outcome::built) << s.name << ": " << v.defect;
  }

  const bool trace = std::getenv("NODUS_FUZZ_TRACE") != nullptr;
  const auto level = spdlog::get_level();
  spdlog::set_level(spdlog::level::off);  // the runs' progress and cutback lines
  Mutator mutator(seed);
  std::map<Outcome, int> counts;
  std::map<Outcome, double> seconds_in;
  std::vector<std::string> defects;
  double slowest = 0.0;
  std::string slowest_what;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t m = 0; m < mutants; ++m) {
    const Seed& s = corpus[m % corpus.size()];
    const Mutant mutant = mutator.mutate(s.text);
    if (trace)
      std::fprintf(stderr, "mutant %llu: %s:%s\n", static_cast<unsigned long long>(m), s.name.c_str(),
                   mutant.what.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    Verdict v = judge(mutant.text, s.path, build_elements, run_dofs);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (seconds > slowest) {
      slowest = seconds;
      slowest_what = fmt::format("{}:{}", s.name, mutant.what);
    }
    const double bound =
        kSlowdown * (kSecondsPerMutant + kSecondsPerElement * static_cast<double>(v.elements));
    if (v.outcome != Outcome::defect && seconds > bound)
      v = {Outcome::defect, fmt::format("took {:.1f} s, over the bound of {:.1f} s", seconds, bound)};
    ++counts[v.outcome];
    seconds_in[v.outcome] += seconds;
    if (v.outcome == Outcome::defect)
      defects.push_back(
          fmt::format("mutant {} of seed {}: {}:{}: {}", m, seed, s.name, mutant.what, v.defect));
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::set_level(level);
  std::printf(
      "fuzzer: %llu mutants of %zu scenarios: %d refused, %d accepted and not built (over %lld "
      "elements), %d built (over %d unknowns, not run), %d ran one Newton iteration, %zu defects; %.2f s "
      "(%.2f s per hundred), slowest %.2f s (%s)\n",
      static_cast<unsigned long long>(mutants), corpus.size(), counts[Outcome::refused],
      counts[Outcome::read], build_elements, counts[Outcome::built], run_dofs, counts[Outcome::ran],
      defects.size(), total, 100.0 * total / static_cast<double>(std::max<std::uint64_t>(mutants, 1)),
      slowest, slowest_what.c_str());
  std::printf(
      "fuzzer: seconds in the refused %.2f, the accepted and not built %.2f, the built %.2f, the run %.2f\n",
      seconds_in[Outcome::refused], seconds_in[Outcome::read], seconds_in[Outcome::built],
      seconds_in[Outcome::ran]);
  for (const std::string& d : defects) ADD_FAILURE() << d;
}

}  // namespace
}  // namespace nodus::fuzz
