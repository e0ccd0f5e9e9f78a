// The data of `nodus view`'s page (src/nodus/output/view_page.hpp) read back by a decoder of its own here:
// the number of runs, states and nodes, every stored value within the quantisation step of what was given,
// the contact records to float precision, the decimation to a size budget, and the HTML around them.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nodus/output/view_page.hpp"
#include "nodus/output/viewer_bundle.hpp"
#include "view_fixtures.hpp"

namespace nodus::output {
namespace {

using nlohmann::json;

std::vector<std::uint8_t> from_base64(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      break;  // '=' padding
    buffer = (buffer << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((buffer >> bits) & 0xff));
    }
  }
  return out;
}

/// Channel c of node i of a decoded node record (value = lo + q step).
double channel_value(const json& run, const std::vector<std::uint8_t>& bytes, std::size_t c, std::size_t i) {
  const std::size_t n = run["node_count"];
  const std::size_t k = 2 * (c * n + i);
  const unsigned q = bytes[k] | (bytes[k + 1] << 8);
  return run["quant"][c][0].get<double>() + q * run["quant"][c][1].get<double>();
}

float record_value(const std::vector<std::uint8_t>& bytes, std::size_t k) {
  std::uint32_t u = 0;
  for (int b = 0; b < 4; ++b) u |= static_cast<std::uint32_t>(bytes[4 * k + b]) << (8 * b);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

TEST(ViewPage, HoldsEveryStateAndNodeOfTheRunAndItsBranch) {
  test::HelixRunSpec spec;
  spec.contact = true;
  spec.branch_states = 4;
  const ResultRun run = test::helix_run(spec);
  const json page = json::parse(view_page_json(run));
  EXPECT_EQ(page["format"], "nodus-view 1");
  EXPECT_FALSE(page["decimated"].get<bool>());
  ASSERT_EQ(page["runs"].size(), 2u);
  EXPECT_EQ(page["runs"][0]["name"], "main");
  EXPECT_EQ(page["runs"][1]["name"], "release");
  const json& main = page["runs"][0];
  EXPECT_EQ(main["node_count"].get<int>(), 3 * 21 + 5);
  EXPECT_EQ(main["beams"].size(), 4u);
  EXPECT_TRUE(main["beams"][3]["tool"].get<bool>());
  EXPECT_EQ(main["states"].size(), run.states.size());
  EXPECT_EQ(main["nodes"].size(), run.states.size());
  EXPECT_EQ(main["contacts"].size(), run.states.size());
  EXPECT_EQ(page["runs"][1]["states"].size(), 4u);
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    EXPECT_EQ(main["states"][k]["step"], run.states[k].step);
    EXPECT_EQ(main["states"][k]["stage"], run.states[k].stage);
    EXPECT_EQ(main["states"][k]["contacts"], run.states[k].contacts.size());
  }
  std::vector<std::string> names;
  for (const json& m : main["measures"]) names.push_back(m["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"e33", "axial_stress", "curvature"}));
}

TEST(ViewPage, NodeValuesRoundTripWithinHalfAQuantisationStep) {
  test::HelixRunSpec spec;
  spec.contact = true;
  const ResultRun run = test::helix_run(spec);
  ViewOptions options;
  options.raw_fields = {"k1", "k2"};
  const json page = json::parse(view_page_json(run, options));
  const json& r = page["runs"][0];
  const std::size_t n = r["node_count"];
  ASSERT_EQ(r["quant"].size(), 9u + 5u);
  // Half a step, plus the rounding of lo + q step in double.
  const auto tolerance = [&](std::size_t c) {
    return 0.5 * r["quant"][c][1].get<double>() * (1 + 1e-9) + 1e-12;
  };
  double worst_position = 0.0;
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    const ResultState& s = run.states[k];
    const std::vector<std::uint8_t> bytes = from_base64(r["nodes"][k]);
    ASSERT_EQ(bytes.size(), 2 * 14 * n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(channel_value(r, bytes, d, i), s.centre[i][d], tolerance(d));
        EXPECT_NEAR(channel_value(r, bytes, 3 + d, i), s.g1[i][d], tolerance(3 + d));
        EXPECT_NEAR(channel_value(r, bytes, 6 + d, i), s.g2[i][d], tolerance(6 + d));
        worst_position = std::max(worst_position, std::abs(channel_value(r, bytes, d, i) - s.centre[i][d]));
      }
      const double e33 = s.node_fields.at("e33")[i];
      const double k1 = s.node_fields.at("k1")[i], k2 = s.node_fields.at("k2")[i];
      const double E = i < 63 ? 4000.0 : 210000.0;
      EXPECT_NEAR(channel_value(r, bytes, 9, i), e33, tolerance(9));
      EXPECT_NEAR(channel_value(r, bytes, 10, i), E * e33, tolerance(10));
      EXPECT_NEAR(channel_value(r, bytes, 11, i), std::hypot(k1, k2), tolerance(11));
      EXPECT_NEAR(channel_value(r, bytes, 12, i), k1, tolerance(12));
      EXPECT_NEAR(channel_value(r, bytes, 13, i), k2, tolerance(13));
    }
  }
  // The positions' step is the box of the run over 65535: well below a micrometre here (a 4 mm bundle).
  EXPECT_LT(worst_position, 1e-4);
  EXPECT_GT(worst_position, 0.0);
}

TEST(ViewPage, ContactRecordsRoundTripToFloatPrecision) {
  test::HelixRunSpec spec;
  spec.contact = true;
  const ResultRun run = test::helix_run(spec);
  const json page = json::parse(view_page_json(run));
  const json& r = page["runs"][0];
  double max_rn = 0.0;
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    const ResultContacts& c = run.states[k].contacts;
    const std::vector<std::uint8_t> bytes = from_base64(r["contacts"][k]);
    ASSERT_EQ(bytes.size(), 4 * 16 * c.size());
    for (std::size_t e = 0; e < c.size(); ++e) {
      const auto f = [&](std::size_t field) {
        return static_cast<double>(record_value(bytes, 16 * e + field));
      };
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(f(d), c.x_i[e][d], 1e-6 * (1 + std::abs(c.x_i[e][d])));
        EXPECT_NEAR(f(3 + d), c.x_j[e][d], 1e-6 * (1 + std::abs(c.x_j[e][d])));
      }
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(f(6 + d), c.normal[e][d], 1e-7);
      EXPECT_NEAR(f(9), c.gap[e], 1e-7 * (1 + std::abs(c.gap[e])));
      EXPECT_NEAR(f(10), c.normal_force[e], 1e-7 * std::abs(c.normal_force[e]) + 1e-30);
      EXPECT_NEAR(f(11), c.tangential_force[e], 1e-7 * std::abs(c.tangential_force[e]) + 1e-30);
      EXPECT_EQ(f(12), c.state[e] == "open" ? 0 : c.state[e] == "stick" ? 1 : 2);
      EXPECT_EQ(f(13), c.beam_i[e]);
      EXPECT_EQ(f(14), c.beam_j[e]);
      EXPECT_EQ(f(15), c.zone[e]);
      max_rn = std::max(max_rn, c.normal_force[e]);
    }
  }
  EXPECT_NEAR(r["contact_ranges"]["normal_force"][1].get<double>(), max_rn, 1e-12);
}

TEST(ViewPage, StatesWithoutForcesAreMarked) {
  test::HelixRunSpec spec;
  spec.contact = true;
  ResultRun run = test::helix_run(spec);
  for (ResultState& s : run.states) {  // contact.forces: false
    s.contacts.normal_force.clear();
    s.contacts.tangential_force.clear();
    s.contacts.state.clear();
  }
  const json page = json::parse(view_page_json(run));
  const std::vector<std::uint8_t> bytes = from_base64(page["runs"][0]["contacts"].back());
  ASSERT_GE(bytes.size(), 4u * 16u);
  EXPECT_TRUE(std::isnan(record_value(bytes, 10)));
  EXPECT_EQ(record_value(bytes, 12), -1.0f);
}

TEST(ViewPage, KeptStatesIncludeEndsAndStageEnds) {
  EXPECT_EQ(kept_states(5, 10, {4}), (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  const std::vector<std::size_t> kept = kept_states(300, 20, {99, 199, 299});
  EXPECT_EQ(kept.size(), 20u);
  for (std::size_t must : {0, 99, 199, 299}) EXPECT_NE(std::find(kept.begin(), kept.end(), must), kept.end());
  // Evenly spread: no gap above twice the mean one.
  for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_LE(kept[i] - kept[i - 1], 2u * 300u / 19u);
}

TEST(ViewPage, DecimatesToTheSizeBudget) {
  test::HelixRunSpec spec;
  spec.states = 60;
  spec.contact = true;
  spec.branch_states = 20;
  const ResultRun run = test::helix_run(spec);
  const std::size_t full = view_page_json(run).size();
  ViewOptions options;
  options.max_bytes = full / 4;
  const std::string text = view_page_json(run, options);
  EXPECT_LE(text.size(), full / 4 + full / 20);  // the budget covers the states' records; JSON rows around
  const json page = json::parse(text);
  EXPECT_TRUE(page["decimated"].get<bool>());
  const json& main = page["runs"][0];
  EXPECT_EQ(main["state_count"].get<std::size_t>(), 60u);
  EXPECT_LT(main["states"].size(), 20u);
  EXPECT_GE(main["states"].size(), 10u);
  EXPECT_EQ(main["states"].front()["step"], 0);
  EXPECT_EQ(main["states"].back()["step"], 59);
  bool twist_end = false;  // the last state of stage "twist" (step 30)
  for (const json& s : main["states"]) twist_end = twist_end || s["step"] == 30;
  EXPECT_TRUE(twist_end);
  EXPECT_LT(page["runs"][1]["states"].size(), 20u);
}

TEST(ViewPage, RefusesArraysOfTheWrongSize) {
  ResultRun run = test::helix_run({});
  run.states[2].g1.pop_back();
  EXPECT_THROW(view_page_json(run), std::invalid_argument);
  ResultRun no_states = test::helix_run({});
  no_states.states.clear();
  EXPECT_THROW(view_page_json(no_states), std::invalid_argument);
}

TEST(ViewPage, HtmlHoldsTheDataAndTheScriptOnce) {
  ResultRun run = test::helix_run({});
  run.beams[0].name = "</script><b>fibre";  // must not end the data's script element
  if (viewer_bundle().empty()) {
    EXPECT_THROW(view_page_html(run), ViewerUnavailable);
    GTEST_SKIP() << "nodus was built without the viewer's page script (web/node_modules)";
  }
  const std::string html = view_page_html(run);
  std::size_t closings = 0;
  for (std::size_t at = html.find("</script>"); at != std::string::npos; at = html.find("</script>", at + 1))
    ++closings;
  EXPECT_EQ(closings, 2u);
  EXPECT_NE(html.find("<script id=\"nodus-data\" type=\"application/json\">"), std::string::npos);
  // Nothing loaded from elsewhere: no script or style sheet of another file.
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  const std::size_t begin = html.find("application/json\">") + 18;
  const json page = json::parse(html.substr(begin, html.find("</script>", begin) - begin));
  EXPECT_EQ(page["runs"][0]["beams"][0]["name"], "</script><b>fibre");
}

TEST(ViewPage, WritesThePageAtomically) {
  if (viewer_bundle().empty()) GTEST_SKIP() << "nodus was built without the viewer's page script";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("nodus_view_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_view_page(test::helix_run({}), dir / "view.html");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  std::ifstream in(dir / "view.html");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), view_page_html(test::helix_run({})));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nodus::output
