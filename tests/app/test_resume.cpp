// Saving, resuming and branching runs from the command line: a run stopped (as if killed) with
// --stop-after-steps and continued with --resume leaves exactly the files of the run that was never stopped
// (the reference: the same computation in one go); a branch with the main run's friction and stages gives
// the main run's final state (the same computation done two ways); bad input gives one line, exit status 2,
// and leaves the output folder as it was.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "nodus/parallel/mpi_session.hpp"

namespace {

namespace fs = std::filesystem;

using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

std::string read(const fs::path& path) {
  return nodus::testing::read_file(path);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The value of column `column` of each data row of a CSV text.
std::vector<double> column(const std::string& csv, const std::string& name) {
  const std::vector<std::string> rows = lines(csv);
  std::vector<std::string> header;
  std::stringstream h(rows.at(0));
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto at = std::find(header.begin(), header.end(), name) - header.begin();
  std::vector<double> values;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    std::stringstream row(rows[r]);
    std::string cell;
    for (long i = 0; i <= at; ++i) std::getline(row, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

using nodus::testing::expect_same_results;
using nodus::testing::kBranches;
using nodus::testing::kDrag;
using nodus::testing::results;
constexpr int kDragSteps = 11;  // press 3, drag 4, back 3, lift 1: no cutbacks

/// Runs `scenario` into DIR/`name`_ref in one go.
fs::path reference_run(const fs::path& scenario, const std::string& name) {
  const fs::path out = scratch() / (name + "_ref");
  fs::remove_all(out);
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q");
  EXPECT_EQ(r.status, 0) << r.err;
  return out;
}

/// Runs `scenario` stopped after each of `stops` steps in turn (each a new process, the later ones with
/// --resume), then to its end with --resume; returns the output folder.
fs::path interrupted_run(const fs::path& scenario, const std::string& name, const std::vector<int>& stops) {
  const fs::path out = scratch() / name;
  fs::remove_all(out);
  bool first = true;
  for (const int stop : stops) {
    const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q" +
                               (first ? "" : " --resume") + " --stop-after-steps " + std::to_string(stop));
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_NE(r.err.find("stopped after " + std::to_string(stop) + " converged steps, as asked"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out / "summary.json"));  // as if killed
    first = false;
  }
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --resume");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("resuming from " + (out / "checkpoints").string()), std::string::npos) << r.err;
  return out;
}

TEST(Resume, EqualsTheUninterruptedRun) {
  const fs::path scenario = write("drag.yaml", kDrag);
  const fs::path reference = reference_run(scenario, "drag");
  ASSERT_EQ(lines(read(reference / "steps.csv")).size(), kDragSteps + 1u);
  for (const char* name : {"000_press", "001_drag", "002_back", "003_lift"})
    EXPECT_TRUE(fs::exists(reference / "checkpoints" / (std::string(name) + ".nodus-state"))) << name;
  EXPECT_FALSE(fs::exists(reference / "checkpoints" / "latest.nodus-state"));

  // Inside drag (resumes from the end of press: steps 4 and 5 are done again), exactly at the end of drag,
  // and twice in a row (inside drag, then at its end after resuming from the end of press).
  for (const std::vector<int>& stops : {std::vector<int>{5}, std::vector<int>{7}, std::vector<int>{4, 4}}) {
    SCOPED_TRACE("stops " + std::to_string(stops.front()));
    expect_same_results(reference, interrupted_run(scenario, "drag_" + std::to_string(stops.front()), stops));
  }
  // The run is complete: --resume says so.
  const Result again =
      run_nodus("run " + scenario.string() + " --out " + reference.string() + " -q --resume");
  EXPECT_EQ(again.status, 0);
  EXPECT_NE(again.err.find("already complete"), std::string::npos) << again.err;
}

TEST(Resume, FromIntermediateCheckpoints) {
  // With checkpoint_every: 2, latest.nodus-state is written after steps 2, 4, 6 and 8 (3, 7, 10 and 11 end
  // stages): a stop after step 6 resumes inside drag from step 6, one after step 9 inside back from step 8.
  const fs::path scenario =
      write("drag_every.yaml",
            replaced(kDrag, "  contact_csv: true\n", "  contact_csv: true\n  checkpoint_every: 2\n"));
  const fs::path reference = reference_run(scenario, "drag_every");
  EXPECT_TRUE(fs::exists(reference / "checkpoints" / "latest.nodus-state"));
  for (const int stop : {6, 9}) {
    SCOPED_TRACE("stop " + std::to_string(stop));
    const fs::path out = scratch() / ("drag_every_" + std::to_string(stop));
    fs::remove_all(out);
    const std::string run = "run " + scenario.string() + " --out " + out.string() + " -q";
    EXPECT_EQ(run_nodus(run + " --stop-after-steps " + std::to_string(stop)).status, 3);
    const Result r = run_nodus(run + " --resume");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("latest.nodus-state (step " + std::to_string(stop - stop % 2) + ", "),
              std::string::npos)
        << r.err;
    expect_same_results(reference, out);
  }
}

TEST(Resume, InsideStagesWithTheirOwnParticles) {
  // drag and back take their own particles (stages[].particles), lift the contact section's again: a run
  // resumed inside drag (from step 6) or inside back (from step 8) places them as the run never stopped.
  std::string text = replaced(kDrag, "  contact_csv: true\n", "  contact_csv: true\n  checkpoint_every: 2\n");
  text = replaced(text, "  - name: drag\n    steps: 4\n",
                  "  - name: drag\n    steps: 4\n    particles: facing\n");
  text = replaced(text, "  - name: back\n    steps: 3\n",
                  "  - name: back\n    steps: 3\n    particles: centres\n");
  const fs::path scenario = write("drag_particles.yaml", text);
  const fs::path reference = reference_run(scenario, "drag_particles");
  for (const int stop : {6, 9}) {
    SCOPED_TRACE("stop " + std::to_string(stop));
    expect_same_results(reference,
                        interrupted_run(scenario, "drag_particles_" + std::to_string(stop), {stop}));
  }
}

TEST(Resume, EqualsTheUninterruptedRunWithEachLinearSolver) {
  // A resumed run analyses its tangent again at its first step, where the run never stopped kept its analysis
  // of the same pattern (CHOLMOD and MUMPS, whose analyses read the pattern alone) or analysed again
  // (UMFPACK, which is given the values, and KLU, whose pivots are chosen anew after an analysis): the
  // results must not show it. cholmod is the case above; petsc (one process here) where nodus has PETSc.
  std::vector<const char*> solvers = {"umfpack", "mumps", "klu"};
  if (nodus::parallel::available()) solvers.push_back("petsc");
  for (const char* solver : solvers) {
    SCOPED_TRACE(solver);
    const std::string name = std::string("drag_") + solver;
    const fs::path scenario =
        write(name + ".yaml", replaced(kDrag, "  contact_csv: true\n",
                                       std::string("  contact_csv: true\n  checkpoint_every: 2\nsolver: "
                                                   "{linear_solver: ") +
                                           solver + "}\n"));
    const fs::path reference = reference_run(scenario, name);
    for (const int stop : {6, 9})
      expect_same_results(reference, interrupted_run(scenario, name + "_" + std::to_string(stop), {stop}));
  }
}

TEST(Resume, EqualsTheUninterruptedRunWithShortPasses) {
  // With short passes of loop 3 (contact.normal_pass_residual) the first solve of a step stops at a bound
  // taken from the reactions of the elements its detection replaced (ContactLoops::install): a resumed run
  // must find the same ones in its checkpoint. Stops inside drag and inside back, from checkpoints written
  // every 2 steps.
  const std::string text =
      replaced(replaced(kDrag, "  friction: 0.3\n", "  friction: 0.3\n  normal_pass_residual: 0.01\n"),
               "  contact_csv: true\n", "  contact_csv: true\n  checkpoint_every: 2\n");
  ASSERT_NE(text, kDrag);
  const fs::path scenario = write("drag_short_passes.yaml", text);
  const fs::path reference = reference_run(scenario, "drag_short_passes");
  for (const int stop : {6, 9})
    expect_same_results(reference,
                        interrupted_run(scenario, "drag_short_passes_" + std::to_string(stop), {stop}));
}

TEST(Branches, ContinueTheMainRun) {
  const fs::path scenario = write("branches.yaml", kDrag + kBranches);
  const fs::path reference = reference_run(scenario, "branches");
  const fs::path main_only = reference_run(write("main.yaml", kDrag), "main_only");
  // The main run is the same with or without branches.
  for (const char* name : {"final_nodes.csv", "steps.csv", "contact_final.csv"})
    EXPECT_EQ(read(reference / name), read(main_only / name)) << name;
  for (const char* name :
       {"steps.csv", "final_nodes.csv", "contact_final.csv", "zones_final.csv", "result.pvd", "contact.pvd",
        "summary.json", "vtk/step_000007.vtp", "checkpoints/003_lift.nodus-state"})
    EXPECT_TRUE(fs::exists(reference / "branches" / "same" / name)) << name;

  // The same stages with the same friction, continued from the end of drag: the main run's end, bitwise.
  const fs::path same = reference / "branches" / "same";
  EXPECT_EQ(read(same / "final_nodes.csv"), read(reference / "final_nodes.csv"));
  EXPECT_EQ(read(same / "contact_final.csv"), read(reference / "contact_final.csv"));
  const std::vector<std::string> main_rows = lines(read(reference / "steps.csv"));
  const std::vector<std::string> branch_rows = lines(read(same / "steps.csv"));
  ASSERT_EQ(branch_rows.size(), 1u + 4u);  // header, steps 8 to 11
  EXPECT_EQ(branch_rows[0], main_rows[0]);
  for (std::size_t r = 1; r < branch_rows.size(); ++r) EXPECT_EQ(branch_rows[r], main_rows[r + 7]);

  // Less friction: on the way back the tool slides, with friction forces mu R_N: 0.1 R_N in the branch,
  // 0.3 R_N in the main run, for about the same normal force.
  const std::string low = read(reference / "branches" / "mu_0.1" / "steps.csv");
  const std::string high = read(reference / "steps.csv");
  const std::vector<double> t_low = column(low, "tangential_force"), n_low = column(low, "normal_force");
  const std::vector<double> t_high = column(high, "tangential_force"), n_high = column(high, "normal_force");
  ASSERT_EQ(t_low.size(), 3u);
  for (std::size_t i = 0; i < t_low.size(); ++i) {
    EXPECT_GT(n_low[i], 0.0);
    EXPECT_NEAR(t_low[i], 0.1 * n_low[i], 1e-6 * n_low[i]) << "step " << 8 + i;
    EXPECT_NEAR(t_high[7 + i], 0.3 * n_high[7 + i], 1e-6 * n_high[7 + i]) << "step " << 8 + i;
    EXPECT_NEAR(n_low[i], n_high[7 + i], 0.05 * n_high[7 + i]) << "step " << 8 + i;
  }
  EXPECT_EQ(column(low, "step"), (std::vector<double>{8, 9, 10}));

  const std::string summary = read(reference / "summary.json");
  EXPECT_NE(summary.find("\"branches\": ["), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"name\": \"mu_0.1\",\n      \"from\": \"drag\",\n      \"friction\": 0.1,\n      "
                         "\"folder\": \"branches/mu_0.1\",\n      \"converged\": true"),
            std::string::npos)
      << summary;
  EXPECT_NE(read(same / "summary.json").find("\"branch\": \"same\""), std::string::npos);
}

TEST(Branches, SideBySideAsOneAtATime) {
  // Each branch is computed from the same checkpoint whatever runs beside it: run two at a time, the files
  // are those of the branches run one after the other.
  const fs::path scenario = write("branches_jobs.yaml", kDrag + kBranches);
  const auto run_with = [&](int jobs) {
    const fs::path out = scratch() / ("branches_jobs_" + std::to_string(jobs));
    fs::remove_all(out);
    const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --jobs " +
                               std::to_string(jobs));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("2 branches to run, 2 at a time, each in its own process") != std::string::npos,
              jobs == 2)
        << r.err;
    return out;
  };
  const fs::path one = run_with(1), two = run_with(2);
  expect_same_results(one, two);
  EXPECT_TRUE(fs::exists(two / "branches" / "mu_0.1" / "final_nodes.csv"));
  EXPECT_EQ(read(two / "summary.json").find("\"converged\": false"), std::string::npos);
  const Result zero =
      run_nodus("run " + scenario.string() + " --out " + (scratch() / "jobs_0").string() + " -q --jobs 0");
  EXPECT_EQ(zero.status, 2) << zero.err;
  EXPECT_FALSE(fs::exists(scratch() / "jobs_0"));
}

TEST(Branches, ResumedSideBySide) {
  // Stopped at the end of same's back (its own checkpoint), then resumed with the branches side by side: the
  // process of `same` resumes from its checkpoint, that of `mu_0.1` starts from the main run's, and the files
  // are those of the run never stopped.
  const fs::path scenario = write("branches_resume_jobs.yaml", kDrag + kBranches);
  const fs::path reference = reference_run(scenario, "branches_resume_jobs");
  const fs::path out = scratch() / "branches_resume_jobs_out";
  fs::remove_all(out);
  const std::string run = "run " + scenario.string() + " --out " + out.string() + " -q";
  EXPECT_EQ(run_nodus(run + " --stop-after-steps 14").status, 3);
  const Result r = run_nodus(run + " --resume --jobs 2");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(
      r.err.find("branch 'same': resuming from " + (out / "branches" / "same" / "checkpoints").string()),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("branch 'mu_0.1': starting from"), std::string::npos) << r.err;
  expect_same_results(reference, out);
}

TEST(Branches, OneBranchOnItsOwn) {
  // `--branch NAME` runs that branch alone from the main run's checkpoint: removed and run again, its files
  // are those it had. An unknown name is refused in one line.
  const fs::path scenario = write("branches_one.yaml", kDrag + kBranches);
  const fs::path reference = reference_run(scenario, "branches_one");
  const fs::path out = scratch() / "branches_one_again";
  fs::remove_all(out);
  fs::copy(reference, out, fs::copy_options::recursive);
  fs::remove_all(out / "branches" / "mu_0.1");
  const Result r = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --branch mu_0.1");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(
      r.err.find("branch 'mu_0.1': starting from " + (out / "checkpoints" / "001_drag.nodus-state").string()),
      std::string::npos)
      << r.err;
  expect_same_results(reference, out);

  const Result bad = run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --branch nope");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err,
            "nodus: " + scenario.string() +
                ": --branch: expected the name of a branch of the scenario (same | mu_0.1), got nope\n");
}

TEST(Branches, ResumeInsideABranch) {
  const fs::path scenario = write("branches_resume.yaml", kDrag + kBranches);
  const fs::path reference = reference_run(scenario, "branches_resume");
  // 11 main steps, then 4 in `same` (back 3, lift 1), then 3 in `mu_0.1`: the first stop is at the end of
  // same's back (its own checkpoint), the second after its last step (before its summary), the third inside
  // mu_0.1 (which starts again from the main run's end of drag); the last resume skips the finished branch.
  const fs::path out = interrupted_run(scenario, "branches_resumed", {14, 1, 2});
  expect_same_results(reference, out);
  EXPECT_EQ(read(out / "summary.json").find("\"converged\": false"), std::string::npos);
}

/// Leaves in `path` what a run killed while writing it through AtomicFile leaves: the first half of `content`
/// in "TARGET.tmpPID" next to it; PID 4194304 is above the largest pid Linux hands out (pid_max <= 2^22), so
/// no live process can own the file.
fs::path leave_temporary_file(const fs::path& target, const std::string& content) {
  fs::path temp = target;
  temp += ".tmp4194304";
  fs::create_directories(temp.parent_path());
  std::ofstream(temp, std::ios::binary) << content.substr(0, content.size() / 2);
  return temp;
}

TEST(Resume, RemovesTemporaryFilesOfAKilledRun) {
  const fs::path scenario = write("stale.yaml", kDrag + kBranches);
  const fs::path reference = reference_run(scenario, "stale");
  const std::string vtp = read(reference / "vtk" / "step_000006.vtp");
  const std::string state = read(reference / "checkpoints" / "001_drag.nodus-state");

  // Killed after step 5, inside drag, while writing the picture of step 6, the stage-end files of drag and
  // a branch's files (from an earlier run into the same folder).
  const fs::path out = scratch() / "stale";
  fs::remove_all(out);
  const std::string run = "run " + scenario.string() + " --out " + out.string() + " -q";
  ASSERT_EQ(run_nodus(run + " --stop-after-steps 5").status, 3);
  const std::vector<fs::path> stale = {
      leave_temporary_file(out / "vtk" / "step_000006.vtp", vtp),
      leave_temporary_file(out / "result.pvd", read(reference / "result.pvd")),
      leave_temporary_file(out / "stages" / "001_drag_nodes.csv",
                           read(reference / "stages" / "001_drag_nodes.csv")),
      leave_temporary_file(out / "checkpoints" / "001_drag.nodus-state", state),
      leave_temporary_file(out / "branches" / "same" / "vtk" / "step_000012.vtp",
                           read(reference / "branches" / "same" / "vtk" / "step_000012.vtp")),
  };
  const Result resumed = run_nodus(run + " --resume");
  EXPECT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("removed 5 temporary file(s) left by an interrupted run in " + out.string()),
            std::string::npos)
      << resumed.err;
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  expect_same_results(reference, out);  // compares every file but checkpoints/ and summary.json, by name too

  // A fresh run into the finished folder clears them too.
  const fs::path again = leave_temporary_file(out / "final_nodes.csv", read(reference / "final_nodes.csv"));
  const fs::path branch_state =
      leave_temporary_file(out / "branches" / "mu_0.1" / "checkpoints" / "000_press.nodus-state", state);
  const Result fresh = run_nodus(run);
  EXPECT_EQ(fresh.status, 0) << fresh.err;
  EXPECT_FALSE(fs::exists(again));
  EXPECT_FALSE(fs::exists(branch_state));
  expect_same_results(reference, out);
}

TEST(Resume, BadInputIsRefusedAndChangesNothing) {
  const fs::path scenario = write("bad_base.yaml", kDrag);
  const fs::path out = scratch() / "bad_out";
  fs::remove_all(out);
  ASSERT_EQ(
      run_nodus("run " + scenario.string() + " --out " + out.string() + " -q --stop-after-steps 5").status,
      3);
  const auto before = results(out);
  const std::string checkpoint = read(out / "checkpoints" / "000_press.nodus-state");

  struct Case {
    std::string name, text, args, expect;
  };
  const std::string modulus = replaced(kDrag, "young_modulus: 4000", "young_modulus: 3000");
  const Case cases[] = {
      {"other_modulus.yaml", modulus, " --resume",
       "000_press.nodus-state: checkpoint: expected a state of this scenario (fingerprint "},
      {"from_no_stage.yaml", kDrag + replaced(kBranches, "from: drag", "from: drug"), "",
       ":36: branches[0].from: expected the name of a stage of stages (press | drag | back | lift), got "
       "drug"},
      {"duplicate.yaml", kDrag + replaced(kBranches, "name: mu_0.1", "name: same"), "",
       ":45: branches[1].name: expected a name unique among branches (already used at line 35), got same"},
      {"no_contact.yaml",
       replaced(replaced(kDrag, "contact:\n  self_contact: false\n  friction: 0.3\n", ""),
                "    contact_off: [tool]\n", "") +
           replaced(kBranches, "        contact_off: [tool]\n", ""),
       "", ": branches[1].contact: expected no contact override in a scenario without a contact section"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path file = write(c.name, c.text);
    const Result r = run_nodus("run " + file.string() + " --out " + out.string() + " -q" + c.args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(results(out) == before) << "the output folder changed";
    EXPECT_EQ(read(out / "checkpoints" / "000_press.nodus-state"), checkpoint);
  }
  // The reader's errors: nothing is written in a new folder either.
  const fs::path fresh = scratch() / "bad_fresh";
  fs::remove_all(fresh);
  EXPECT_EQ(run_nodus("run " + (scratch() / "duplicate.yaml").string() + " --out " + fresh.string()).status,
            2);
  EXPECT_FALSE(fs::exists(fresh));

  // --resume without a checkpoint: in a folder without one, and in one that does not exist.
  fs::remove_all(out / "checkpoints");
  for (const fs::path& dir : {out, fresh}) {
    const Result r = run_nodus("run " + scenario.string() + " --out " + dir.string() + " -q --resume");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--resume: expected a checkpoint (*.nodus-state) in " +
                         (dir / "checkpoints").string() + ", got none: nothing to resume"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  }
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_TRUE(results(out) == before);
}

}  // namespace

namespace {

/// Damages the file at `path` in one of three ways: a byte flipped in the middle, the second half cut off,
/// the second half zeroed.
void damage(const fs::path& path, int how) {
  std::string bytes = read(path);
  const std::size_t half = bytes.size() / 2;
  if (how == 0) bytes[half] = static_cast<char>(bytes[half] ^ 0xff);
  if (how == 1) bytes.resize(half);
  if (how == 2) std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(half), bytes.end(), '\0');
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

// A damaged newest checkpoint is passed over with a warning naming it: --resume goes on from the newest
// intact one (here the end of press, step 3, the damaged one being at step 6) to the files of the run never
// stopped. With every checkpoint damaged, --resume refuses in one line that names them, and changes nothing.
TEST(Resume, FromTheNewestIntactCheckpoint) {
  const fs::path scenario =
      write("drag_damaged.yaml",
            replaced(kDrag, "  contact_csv: true\n", "  contact_csv: true\n  checkpoint_every: 2\n"));
  const fs::path reference = reference_run(scenario, "drag_damaged");
  for (const int how : {0, 1, 2}) {
    SCOPED_TRACE("damage " + std::to_string(how));
    const fs::path out = scratch() / ("drag_damaged_" + std::to_string(how));
    fs::remove_all(out);
    const std::string run = "run " + scenario.string() + " --out " + out.string() + " -q";
    ASSERT_EQ(run_nodus(run + " --stop-after-steps 6").status, 3);
    damage(out / "checkpoints" / "latest.nodus-state", how);
    const Result r = run_nodus(run + " --resume");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find((out / "checkpoints" / "latest.nodus-state").string() + ": damaged (expected "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("resuming from " + (out / "checkpoints" / "000_press.nodus-state").string() +
                         " (step 3, "),
              std::string::npos)
        << r.err;
    expect_same_results(reference, out);
  }

  const fs::path out = scratch() / "drag_all_damaged";
  fs::remove_all(out);
  const std::string run = "run " + scenario.string() + " --out " + out.string() + " -q";
  ASSERT_EQ(run_nodus(run + " --stop-after-steps 6").status, 3);
  damage(out / "checkpoints" / "latest.nodus-state", 0);
  damage(out / "checkpoints" / "000_press.nodus-state", 1);
  const auto before = results(out);
  const Result r = run_nodus(run + " --resume");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(
      r.err.find("nodus: " + (out / "checkpoints").string() +
                 ": --resume: expected an intact checkpoint, got only damaged ones (000_press.nodus-state, "
                 "latest.nodus-state): nothing to resume from"),
      std::string::npos)
      << r.err;
  EXPECT_TRUE(results(out) == before) << "the output folder changed";
}
