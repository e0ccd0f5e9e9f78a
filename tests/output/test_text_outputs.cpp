// steps.csv lines, summary.json, progress lines and the stderr logger.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <regex>

#include <spdlog/spdlog.h>

#include "nodus/output/logging.hpp"
#include "nodus/output/progress_line.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/output/summary_writer.hpp"
#include "output_test_support.hpp"

#if __has_include(<nlohmann/json.hpp>)
#include <nlohmann/json.hpp>
#define NODUS_TEST_HAVE_JSON 1
#endif

namespace nodus::output {
namespace {

/// The columns of what made a step hard, last in the header.
const std::string kHardColumns = ",step_size,entered,left,to_slip,to_stick,cutback_causes";

TEST(StepsCsv, HeaderNamesContactColumnsThenSixColumnsPerCondition) {
  EXPECT_EQ(steps_csv_header({}),
            "step,stage,time,newton_iterations,cutbacks,residual,increment,zones,contact_elements,detections,"
            "normal_iterations,penetration_ratio,normal_force,tangential_force,slipping,stabilization_force,"
            "loops_converged,min_orientation,min_chord,min_clearance" +
                kHardColumns);
  EXPECT_EQ(steps_csv_header({"left", "right"}),
            "step,stage,time,newton_iterations,cutbacks,residual,increment,zones,contact_elements,detections,"
            "normal_iterations,penetration_ratio,normal_force,tangential_force,slipping,stabilization_force,"
            "loops_converged,min_orientation,min_chord,min_clearance,left_fx,left_fy,left_"
            "fz,left_mx,left_my,left_mz,right_fx,right_fy,right_fz,right_mx,right_my,"
            "right_mz" +
                kHardColumns);
}

TEST(StepsCsv, RowHoldsRecordWithTenDigits) {
  simulation::StepRecord r;
  r.step = 7;
  r.stage = 1;
  r.time = 1.0 / 3.0;
  r.newton_iterations = 4;
  r.cutbacks = 1;
  r.residual = 2.5e-9;
  r.increment = 1e-12;
  loading::SectionForce s;
  s.force = Eigen::Vector3d(1, -2, 0.125);
  s.moment = Eigen::Vector3d(0, 1234.5, -1e-20);
  r.sections = {s};
  // Without contact the zone and element counts and the contact-loop figures are 0, no loop ended at its cap
  // (loops_converged 1), and there is no clearance (nan).
  EXPECT_EQ(steps_csv_row(r, "bend", 1),
            "7,bend,0.3333333333,4,1,2.5e-09,1e-12,0,0,0,0,0,0,0,0,0,1,1,1,nan,1,-2,0.125,0,1234.5,-1e-20,"
            "0,0,0,0,0,");
  r.zones = 3;
  r.contact_elements = 41;
  EXPECT_EQ(steps_csv_row(r, "bend", 1),
            "7,bend,0.3333333333,4,1,2.5e-09,1e-12,3,41,0,0,0,0,0,0,0,1,1,1,nan,1,-2,0.125,0,1234.5,-1e-20,"
            "0,0,0,0,0,");
  r.detections = 2;
  r.normal_iterations = 5;
  r.penetration_ratio = 2.0 / 3.0;
  r.normal_force = 12.5;
  r.tangential_force = 1e-7 / 3.0;
  r.slipping = 17;
  r.stabilization_force = 0.25;
  r.loops_converged = false;
  r.min_orientation = -0.25;
  r.min_chord = 1.0 / 3.0;
  r.min_clearance = -0.0125;
  EXPECT_EQ(
      steps_csv_row(r, "bend", 1),
      "7,bend,0.3333333333,4,1,2.5e-09,1e-12,3,41,2,5,0.6666666667,12.5,3.333333333e-08,17,0.25,0,-0.25,"
      "0.3333333333,-0.0125,1,-2,0.125,0,1234.5,-1e-20,0,0,0,0,0,");
  // What made the step hard: its size [s], the changes of regime, the causes of its cutback.
  r.step_size = 0.0625;
  r.regime_changes = {3, 1, 4, 2};
  r.cutback_causes = {"no progress"};
  EXPECT_TRUE(steps_csv_row(r, "bend", 1).ends_with(",1234.5,-1e-20,0.0625,3,1,4,2,no progress"))
      << steps_csv_row(r, "bend", 1);
  // A missing section gives empty fields; a stage name with a comma is quoted.
  const std::string row = steps_csv_row(r, "a,b", 2);
  EXPECT_EQ(testing::split(row, ',').size(), 20u + 12u + 6u + 1u);  // the quoted comma splits once more
  EXPECT_NE(row.find(",\"a,b\","), std::string::npos);
  EXPECT_NE(row.find(",,,,,,0.0625,3,1,4,2,no progress"), std::string::npos);
}

TEST(StepsCsv, CutbackCausesAreOneQuotedField) {
  // Failure messages hold commas and quotes: joined with " | ", they are one field, quoted as RFC 4180 says,
  // which a CSV reader reads back as they were.
  const std::vector<std::string> causes{
      "the axes of beams 'a' at s = 2 mm and 'b' at s = 2 mm passed through each other at 0.5 of the step",
      "penetration 12.5 times max_penetration (more than 10), at \"zone 3\"", "the tangent is singular"};
  const std::string joined = causes[0] + " | " + causes[1] + " | " + causes[2];
  EXPECT_EQ(cutback_causes_field(causes), "\"" + causes[0] + " | " +
                                              "penetration 12.5 times max_penetration (more than 10), at "
                                              "\"\"zone 3\"\" | the tangent is singular\"");
  EXPECT_EQ(cutback_causes_field({}), "");
  EXPECT_EQ(cutback_causes_field({"no progress"}), "no progress");

  simulation::StepRecord r;
  r.step = 4;
  r.time = 0.75;
  r.cutbacks = 3;
  r.step_size = 0.125;
  r.regime_changes = {5, 2, 1, 0};
  r.cutback_causes = causes;
  r.sections.resize(1);
  const std::vector<std::string> names{"grip, left"};  // a quoted header name too
  const std::string text = steps_csv_header(names) + "\n" + steps_csv_row(r, "pull", 1) + "\n";
  const auto records = testing::csv_records(text);
  ASSERT_EQ(records.size(), 2u);
  ASSERT_EQ(records[1].size(), records[0].size());
  const auto field = [&](const std::string& column) {
    const auto at = std::find(records[0].begin(), records[0].end(), column);
    EXPECT_NE(at, records[0].end()) << column;
    return at == records[0].end() ? std::string()
                                  : records[1][static_cast<std::size_t>(at - records[0].begin())];
  };
  EXPECT_EQ(field("grip, left_fx"), "0");
  EXPECT_EQ(field("cutbacks"), "3");
  EXPECT_EQ(field("step_size"), "0.125");
  EXPECT_EQ(field("entered"), "5");
  EXPECT_EQ(field("left"), "2");
  EXPECT_EQ(field("to_slip"), "1");
  EXPECT_EQ(field("to_stick"), "0");
  EXPECT_EQ(field("cutback_causes"), joined);
  EXPECT_EQ(records[0].back(), "cutback_causes");
  // A resumed run cuts such a file after a step's row, a quoted field and all.
  simulation::StepRecord next;
  next.step = 5;
  const std::string two = text + steps_csv_row(next, "pull", 1) + "\n";
  EXPECT_EQ(steps_csv_up_to(two, 4), text);
}

TEST(StepsCsv, RowHasAFieldPerHeaderColumn) {
  simulation::StepRecord r;
  r.step = 2;
  r.zones = 1;
  r.contact_elements = 6;
  r.detections = 3;
  r.normal_iterations = 7;
  r.penetration_ratio = 0.5;
  r.normal_force = 4.25;
  r.tangential_force = 0.75;
  r.slipping = 2;
  r.stabilization_force = 0.125;
  r.loops_converged = false;
  r.sections.resize(2);
  const auto header = testing::split(steps_csv_header({"left", "right"}), ',');
  const auto fields = testing::split(steps_csv_row(r, "s", 2), ',');
  ASSERT_EQ(fields.size(), header.size());
  const std::vector<std::pair<std::string, std::string>> expected{{"zones", "1"},
                                                                  {"contact_elements", "6"},
                                                                  {"detections", "3"},
                                                                  {"normal_iterations", "7"},
                                                                  {"penetration_ratio", "0.5"},
                                                                  {"normal_force", "4.25"},
                                                                  {"tangential_force", "0.75"},
                                                                  {"slipping", "2"},
                                                                  {"stabilization_force", "0.125"},
                                                                  {"loops_converged", "0"},
                                                                  {"min_orientation", "1"},
                                                                  {"min_chord", "1"},
                                                                  {"min_clearance", "nan"}};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(header[7 + k], expected[k].first);
    EXPECT_EQ(fields[7 + k], expected[k].second) << expected[k].first;
  }
  EXPECT_EQ(header[20], "left_fx");
}

TEST(StepsCsv, BodyColumnsAfterTheConditions) {
  // Eight columns per body, after the six of every condition, in the order of the names given.
  const std::string head =
      "step,stage,time,newton_iterations,cutbacks,residual,increment,zones,contact_elements,detections,"
      "normal_iterations,penetration_ratio,normal_force,tangential_force,slipping,stabilization_force,"
      "loops_converged,min_orientation,min_chord,min_clearance";
  EXPECT_EQ(
      steps_csv_header({"hold"}, {"y.r1.start", "cap"}),
      head +
          ",hold_fx,hold_fy,hold_fz,hold_mx,hold_my,hold_mz,"
          "y.r1.start_fx,y.r1.start_fy,y.r1.start_fz,y.r1.start_mx,y.r1.start_my,y.r1.start_mz,"
          "y.r1.start_error,y.r1.start_tie,cap_fx,cap_fy,cap_fz,cap_mx,cap_my,cap_mz,cap_error,cap_tie" +
          kHardColumns);
  EXPECT_EQ(steps_csv_header({}, {"cap"}),
            head + ",cap_fx,cap_fy,cap_fz,cap_mx,cap_my,cap_mz,cap_error,cap_tie" + kHardColumns);
  // A body name that needs quoting is quoted as a condition name is.
  EXPECT_EQ(steps_csv_header({}, {"a,b"}).substr(head.size()),
            ",\"a,b_fx\",\"a,b_fy\",\"a,b_fz\",\"a,b_mx\",\"a,b_my\",\"a,b_mz\",\"a,b_error\",\"a,b_tie\"" +
                kHardColumns);

  // The row: force [N], moment [N mm], error [mm], tie [N] of each body, with ten significant digits.
  simulation::StepRecord r;
  r.step = 3;
  r.time = 0.5;
  loading::SectionForce s;
  s.force = Eigen::Vector3d(1, 0, 0);
  r.sections = {s};
  simulation::BodyRecord b;
  b.force = Eigen::Vector3d(-1, 2.5, 1.0 / 3.0);
  b.moment = Eigen::Vector3d(0, -1e-20, 1234.5);
  b.error = 2.0 / 3.0 * 1e-6;
  b.tie = 1e-9;
  r.bodies = {b};
  EXPECT_EQ(steps_csv_row(r, "twist", 1, 1),
            "3,twist,0.5,0,0,0,0,0,0,0,0,0,0,0,0,0,1,1,1,nan,1,0,0,0,0,0,"
            "-1,2.5,0.3333333333,0,-1e-20,1234.5,6.666666667e-07,1e-09,0,0,0,0,0,");
  // Every header column has its field; a body missing from the record gives empty fields.
  const auto header = testing::split(steps_csv_header({"hold"}, {"y.r1.start", "cap"}), ',');
  const auto fields = testing::split(steps_csv_row(r, "twist", 1, 2), ',');
  ASSERT_EQ(fields.size(), header.size());
  EXPECT_EQ(header[26], "y.r1.start_fx");
  EXPECT_EQ(fields[26], "-1");
  EXPECT_EQ(header[32], "y.r1.start_error");
  EXPECT_EQ(fields[32], "6.666666667e-07");
  EXPECT_EQ(header[33], "y.r1.start_tie");
  EXPECT_EQ(fields[33], "1e-09");
  for (std::size_t k = 34; k < 42; ++k) EXPECT_EQ(fields[k], "") << header[k];
  EXPECT_EQ(header[42], "step_size");
  EXPECT_EQ(fields.size(), 42u + 6u);
  // Without bodies the row is what it was: no body fields.
  EXPECT_EQ(steps_csv_row(r, "twist", 1), steps_csv_row(r, "twist", 1, 0));
  EXPECT_EQ(testing::split(steps_csv_row(r, "twist", 1), ',').size(), 20u + 6u + 6u);
}

TEST(Summary, JsonHoldsEveryField) {
  SummaryData d;
  d.dofs = 72;
  d.nodes = 8;
  d.elements = 3;
  d.beams = 2;
  d.steps = 40;
  d.newton_iterations = 163;
  d.converged = false;
  d.wall_seconds = 1.5;
  d.detection_seconds = 0.25;
  d.assembly_seconds = 0.5;
  d.linear_solve_seconds = 0.125;
  d.factorizations = 170;
  d.analyses = 12;
  d.krylov_iterations = 9;
  d.failure = "stage \"bend\": no convergence";
  d.final_time = 0.75;
  d.scenario = "scenarios/two_beams.yaml";
  const std::string text = summary_json(d);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
#ifdef NODUS_TEST_HAVE_JSON
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j.at("dofs"), 72);
  EXPECT_EQ(j.at("nodes"), 8);
  EXPECT_EQ(j.at("elements"), 3);
  EXPECT_EQ(j.at("beams"), 2);
  EXPECT_EQ(j.at("steps"), 40);
  EXPECT_EQ(j.at("newton_iterations"), 163);
  EXPECT_EQ(j.at("converged"), false);
  EXPECT_EQ(j.at("wall_seconds"), 1.5);
  EXPECT_EQ(j.at("detection_seconds"), 0.25);
  EXPECT_EQ(j.at("assembly_seconds"), 0.5);
  EXPECT_EQ(j.at("linear_solve_seconds"), 0.125);
  EXPECT_EQ(j.at("factorizations"), 170);
  EXPECT_EQ(j.at("analyses"), 12);
  EXPECT_EQ(j.at("krylov_iterations"), 9);
  EXPECT_EQ(j.at("failure"), d.failure);
  EXPECT_EQ(j.at("final_time"), 0.75);
  EXPECT_EQ(j.at("scenario"), d.scenario);
  EXPECT_EQ(j.size(), 17u);
  EXPECT_FALSE(j.contains("friction"));  // without contact forces
  d.friction = 0.25;
  EXPECT_EQ(nlohmann::json::parse(summary_json(d)).at("friction"), 0.25);
  d.friction.reset();
#else
  for (const char* key : {"\"dofs\": 72", "\"nodes\": 8", "\"elements\": 3", "\"beams\": 2", "\"steps\": 40",
                          "\"newton_iterations\": 163", "\"converged\": false", "\"wall_seconds\": 1.5",
                          "\"final_time\": 0.75", "\"scenario\": \"scenarios/two_beams.yaml\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
#endif
  testing::ScratchDir dir;
  write_summary(dir.path() / "summary.json", d);
  EXPECT_EQ(testing::read_text(dir.path() / "summary.json"), text);
}

TEST(Progress, RemainingTimeExtrapolatesLoadTimeRate) {
  EXPECT_DOUBLE_EQ(remaining_seconds(10.0, 0.0, 0.25, 1.0), 30.0);
  EXPECT_DOUBLE_EQ(remaining_seconds(10.0, 1.0, 1.5, 3.0), 30.0);
  EXPECT_EQ(remaining_seconds(10.0, 0.0, 1.0, 1.0), 0.0);
  EXPECT_TRUE(std::isnan(remaining_seconds(10.0, 0.0, 0.0, 1.0)));
}

// The knot's branch: `release` puts 20 steps into 1 s of load time, `rest` 20 steps into 40 s. Every step
// costing 1 s of wall time, the true time left after k steps is 40 - k s, whatever the stage.
TEST(Progress, RemainingTimeCountsNominalStepsAcrossStages) {
  RemainingTime left({1.0, 41.0}, {20, 20}, 0.0);
  EXPECT_TRUE(std::isnan(left.seconds()));  // nothing measured yet
  EXPECT_DOUBLE_EQ(left.units(0.5), 10.0);
  EXPECT_DOUBLE_EQ(left.units(1.0), 20.0);
  EXPECT_DOUBLE_EQ(left.units(21.0), 30.0);
  EXPECT_DOUBLE_EQ(left.units(99.0), 40.0);
  for (int k = 1; k <= 40; ++k) {
    const double time = k <= 20 ? 0.05 * k : 1.0 + 2.0 * (k - 20);
    left.step(time, 1.0);
    EXPECT_NEAR(left.seconds(), 40.0 - k, 1e-9) << "after step " << k;
    // The load-time extrapolation over the whole run is off by a factor of 21 after the first step.
    if (k == 1) {
      EXPECT_GT(remaining_seconds(k, 0.0, time, 41.0) / (40.0 - k), 20.0);
    }
  }
  EXPECT_EQ(left.seconds(), 0.0);
}

TEST(Progress, RemainingTimeFollowsAChangeOfCostWithinItsWindow) {
  // A stage of 100 steps over 1 s; the first 10 steps cost 1 s each, then 3 s each: the cost per step
  // smoothed over RemainingTime::kWindow steps is c_n = 3 - 2 exp(-n / kWindow) after n steps at 3 s.
  RemainingTime left({1.0}, {100}, 0.0);
  for (int k = 1; k <= 10; ++k) left.step(0.01 * k, 1.0);
  EXPECT_NEAR(left.seconds(), 90.0, 1e-9);
  for (int n = 1; n <= 20; ++n) {
    left.step(0.01 * (10 + n), 3.0);
    const double cost = 3.0 - 2.0 * std::exp(-n / RemainingTime::kWindow);
    EXPECT_NEAR(left.seconds(), cost * (90 - n), 1e-9 * (90 - n)) << n;
  }
}

TEST(Progress, RemainingTimeOfARunStartedInsideAStage) {
  // A resumed run: the first stage done, the second (10 steps over 10 s) half done.
  RemainingTime left({1.0, 11.0}, {10, 10}, 6.0);
  EXPECT_TRUE(std::isnan(left.seconds()));
  left.step(7.0, 2.0);  // one nominal step in 2 s: 4 steps left
  EXPECT_DOUBLE_EQ(left.seconds(), 8.0);
  left.step(7.0, 1.0);  // no progress: no measurement
  EXPECT_DOUBLE_EQ(left.seconds(), 8.0);
}

TEST(Progress, LineFormat) {
  ProgressInfo p;
  p.stage_name = "twist";
  p.stage = 1;
  p.num_stages = 3;
  p.step = 17;
  p.time = 1.25;
  p.start_time = 0.0;
  p.end_time = 3.0;
  p.newton_iterations = 5;
  p.residual = 3.2e-9;
  p.elapsed_seconds = 12.34;
  EXPECT_EQ(
      progress_line(p),
      "stage twist (2/3), step 17, load time 1.25 / 3, Newton its 5, residual 3.200e-09, elapsed 12.3 s, "
      "remaining ~17 s");
  p.time = 0.0;
  EXPECT_NE(progress_line(p).find("remaining ~? s"), std::string::npos);
  p.time = 2.5;
  EXPECT_NE(progress_line(p).find("remaining ~2.5 s"), std::string::npos) << progress_line(p);
  p.remaining_seconds = 123.4;  // RemainingTime's estimate, when given, is the one shown
  EXPECT_NE(progress_line(p).find("remaining ~123 s"), std::string::npos) << progress_line(p);
  // The size of the step: a fraction of the stage's nominal step below it, else in load time.
  p.nominal_step = 0.25;
  p.step_size = 0.25 / 8;
  EXPECT_TRUE(progress_line(p).starts_with(
      "stage twist (2/3), step 17, step size 1/8 of nominal, load time 2.5 / 3, Newton its 5"))
      << progress_line(p);
  p.step_size = 0.25;
  EXPECT_NE(progress_line(p).find("step 17, step size 0.25 s, load time"), std::string::npos)
      << progress_line(p);
}

TEST(Progress, StepSizeAsAFractionOfTheNominalStep) {
  EXPECT_EQ(step_size_text(0.125, 1.0), "1/8 of nominal");
  EXPECT_EQ(step_size_text(0.1 / 3.0, 0.1), "1/3 of nominal");
  EXPECT_EQ(step_size_text(std::ldexp(0.3, -12), 0.3), "1/4096 of nominal");
  EXPECT_EQ(step_size_text(0.375, 1.0), "0.375 of nominal");  // the rest of a stage after cutbacks
  // At the nominal step (to rounding), above it (the last step of a stage takes a remainder within 1 % of
  // it) or without one: in load time.
  EXPECT_EQ(step_size_text(0.1, 0.1), "0.1 s");
  EXPECT_EQ(step_size_text(0.1 * (1 - 1e-12), 0.1), "0.1 s");
  EXPECT_EQ(step_size_text(0.101, 0.1), "0.101 s");
  EXPECT_EQ(step_size_text(0.125, std::numeric_limits<double>::quiet_NaN()), "0.125 s");
  EXPECT_EQ(step_size_text(0.125, 0.0), "0.125 s");
  // Unknown: nothing, and the line leaves it out.
  EXPECT_EQ(step_size_text(0.0, 1.0), "");
  EXPECT_EQ(step_size_text(std::numeric_limits<double>::quiet_NaN(), 1.0), "");
}

TEST(Logging, DefaultLoggerWritesToStderr) {
  use_stderr_logger();
  use_stderr_logger();  // idempotent
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  spdlog::info("hello {}", 42);
  spdlog::default_logger()->flush();
  const std::string err = ::testing::internal::GetCapturedStderr();
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(out, "");
  EXPECT_TRUE(std::regex_search(err, std::regex(R"(\[\d\d:\d\d:\d\d\] hello 42)"))) << err;
}

}  // namespace
}  // namespace nodus::output
