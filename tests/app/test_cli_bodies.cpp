// Rigid bodies through the command line: two active conditions that prescribe the same unknown of a body are
// refused before anything runs (one line naming both, exit status 2), as for beam sections; and a run with
// bodies writes their columns to steps.csv, which obey the statics of a cantilever of two fibres held by a
// clamped body at one end and loaded through a body at the other.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using nodus::testing::read_file;
using nodus::testing::Result;
using nodus::testing::run_nodus;
using nodus::testing::scratch;
using nodus::testing::write;

// Lines 1-8; conditions start at line 10.
const std::string kHead = R"(materials:
  - {name: pa, young_modulus: 4000, poisson_ratio: 0.3}
beams:
  - {name: a, material: pa, radius: 0.1, length: 4, elements: 4}
  - {name: b, material: pa, radius: 0.1, length: 4, elements: 4, start: [0, 0.3, 0]}
bodies:
  - {name: base, beams: [a, b], at: start}
  - {name: cap, beams: [a, b], at: end}
conditions:
)";

/// `nodus check` of kHead + `rest`: its exit status and stderr.
Result check(const std::string& name, const std::string& rest) {
  return run_nodus("check " + write(name, kHead + rest).string());
}

TEST(CliBodies, TwoConditionsPrescribingOneUnknownOfABody) {
  struct Case {
    std::string name, rest, expected;
  };
  const std::vector<Case> cases = {
      // Both active from the start: the later condition is named with its line.
      {"both_active.yaml",
       "  - {name: hold, type: clamp, bodies: [base]}\n"
       "  - {name: pin, type: clamp, bodies: [base], dofs: [ry]}\n"
       "stages:\n  - {name: s, steps: 1}\n",
       ":11: conditions[1].dofs: expected no unknown prescribed by two active conditions, got 'hold' and "
       "'pin' both prescribing unknown ry of body 'base' in stage 's'"},
      // One of several bodies, activated in a later stage.
      {"later_stage.yaml",
       "  - {name: hold, type: clamp, bodies: [base, cap], dofs: [position, rz]}\n"
       "  - {name: turn, type: motion, bodies: [cap], dofs: [rotation], active: false}\n"
       "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, activate: [turn]}\n",
       ":11: conditions[1].dofs: expected no unknown prescribed by two active conditions, got 'hold' and "
       "'turn' both prescribing unknown rz of body 'cap' in stage 't'"},
      // In a branch, from the state of the conditions at the end of its from stage.
      {"branch.yaml",
       "  - {name: hold, type: clamp, bodies: [cap], dofs: [x]}\n"
       "  - {name: push, type: motion, bodies: [cap], dofs: [x], active: false}\n"
       "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, release: [hold]}\n"
       "branches:\n  - {name: again, from: s, stages: [{name: u, steps: 1, activate: [push]}]}\n",
       ":11: conditions[1].dofs: expected no unknown prescribed by two active conditions, got 'hold' and "
       "'push' both prescribing unknown x of body 'cap' in stage 'u' of branch 'again'"},
  };
  for (const Case& c : cases) {
    const Result r = check(c.name, c.rest);
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.err;
    EXPECT_EQ(r.err, "nodus: " + (scratch() / c.name).string() + c.expected + "\n") << c.name;
  }

  // Different unknowns of one body, or one condition released in the stage that activates the other: fine.
  EXPECT_EQ(check("disjoint.yaml",
                  "  - {name: hold, type: clamp, bodies: [base], dofs: [position]}\n"
                  "  - {name: turn, type: motion, bodies: [base, cap], dofs: [rotation]}\n"
                  "stages:\n  - {name: s, steps: 1}\n")
                .status,
            0);
  EXPECT_EQ(
      check("handover.yaml",
            "  - {name: hold, type: clamp, bodies: [cap], dofs: [x]}\n"
            "  - {name: push, type: motion, bodies: [cap], dofs: [x], active: false}\n"
            "stages:\n  - {name: s, steps: 1}\n  - {name: t, steps: 1, release: [hold], activate: [push]}\n")
          .status,
      0);
}

/// The last data line of a steps.csv as column -> value (no quoted fields here; the text columns, stage and
/// cutback_causes, as 0).
std::map<std::string, double> last_row(const std::string& csv) {
  std::vector<std::string> lines;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto split = [](const std::string& line) {
    std::vector<std::string> out;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) out.push_back(field);
    if (!line.empty() && line.back() == ',') out.emplace_back();  // an empty last field
    return out;
  };
  const std::vector<std::string> header = split(lines.front()), values = split(lines.back());
  EXPECT_EQ(header.size(), values.size());
  std::map<std::string, double> row;
  for (std::size_t i = 0; i < std::min(header.size(), values.size()); ++i)
    row[header[i]] = header[i] == "stage" || header[i] == "cutback_causes" ? 0.0 : std::stod(values[i]);
  return row;
}

TEST(CliBodies, StepsCsvColumnsObeyTheStaticsOfABoundCantilever) {
  // Two fibres, their start sections bound to `base` (clamped), their end sections to `cap`, which carries
  // a dead force F = 0.01 N along z. Statics, whatever the fibres do between:
  //  - the clamp's reaction balances the load: hold_f = -F;
  //  - a body at rest passes on what acts on it: the force base exerts on its sections is the clamp's
  //    reaction, the one cap exerts is the load, and base's moment about its point c equals hold's (one
  //    body: about the same point c);
  //  - the moment of the reaction about base's c balances that of F, applied at cap's c, |x| <= 4 mm away.
  const fs::path file = write("cantilever.yaml", kHead + R"(  - {name: hold, type: clamp, bodies: [base]}
  - {name: pull, type: load, bodies: [cap]}
stages:
  - name: s
    steps: 2
    loads: {pull: {force: [0, 0, 0.01]}}
)");
  const fs::path out = scratch() / "out_cantilever";
  fs::remove_all(out);
  const Result r = run_nodus("run " + file.string() + " --out " + out.string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = read_file(out / "steps.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_TRUE(
      header.ends_with(",hold_fx,hold_fy,hold_fz,hold_mx,hold_my,hold_mz,pull_fx,pull_fy,pull_fz,"
                       "pull_mx,pull_my,pull_mz,base_fx,base_fy,base_fz,base_mx,base_my,base_mz,"
                       "base_error,base_tie,cap_fx,cap_fy,cap_fz,cap_mx,cap_my,cap_mz,cap_error,cap_tie,"
                       "step_size,entered,left,to_slip,to_stick,cutback_causes"))
      << header;

  const std::map<std::string, double> row = last_row(csv);
  const double f = 0.01;
  // What a body passes on differs from what acts on it by the force of its rearrangement tie (steps.csv's
  // *_tie, checked below) and by Newton's residual (< 1e-10 N); 1e-4 F = 1e-6 N bounds
  // both with room.
  const double tol = 1e-4 * f;
  EXPECT_NEAR(row.at("pull_fz"), f, 1e-15);
  for (const char* c : {"x", "y", "z"}) {
    const std::string axis(c);
    const double load = axis == "z" ? f : 0.0;
    EXPECT_NEAR(row.at("hold_f" + axis), -load, tol) << axis;
    EXPECT_NEAR(row.at("base_f" + axis), -load, tol) << axis;
    EXPECT_NEAR(row.at("cap_f" + axis), load, tol) << axis;
    EXPECT_NEAR(row.at("base_m" + axis), row.at("hold_m" + axis), tol) << axis;
    EXPECT_NEAR(row.at("cap_m" + axis), 0.0, tol) << axis;  // F acts at cap's c: no moment about it
  }
  // The lever arm of F about base's c lies along x (the fibres bend little): my = x F with 0 < x <= 4.
  EXPECT_GT(row.at("hold_my"), 0.9 * 4.0 * f);
  EXPECT_LE(row.at("hold_my"), 4.0 * f + tol);
  EXPECT_NEAR(row.at("hold_mx"), 0.0, tol);
  EXPECT_NEAR(row.at("hold_mz"), 0.0, tol);
  // The errors [mm] and tie forces [N] are small and not negative.
  for (const char* body : {"base", "cap"}) {
    const std::string b(body);
    EXPECT_GE(row.at(b + "_error"), 0.0);
    EXPECT_LT(row.at(b + "_error"), 1e-3) << b;
    EXPECT_GE(row.at(b + "_tie"), 0.0);
    EXPECT_LT(row.at(b + "_tie"), tol) << b;
  }
}

}  // namespace
