// `nodus view RUN_DIR` on a real run: examples/tool_drag.yaml with a branch added (a tool drags a beam with
// friction; the branch drags it the other way), read back from its result.h5. The page holds the main run
// and the branch with all their states; bad folders give one line and exit status 2.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "nodus/output/result_h5.hpp"
#include "nodus/output/viewer_bundle.hpp"

namespace nodus::output {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status;
  std::string out, err;
};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("nodus_view_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

Outcome nodus(const std::string& args) {
  const fs::path out = scratch() / "stdout.txt", err = scratch() / "stderr.txt";
  const std::string cmd =
      std::string(NODUS_BINARY) + " " + args + " > " + out.string() + " 2> " + err.string();
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read(out), read(err)};
}

/// The JSON of a page (the text of its <script id="nodus-data">).
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script id=\"nodus-data\" type=\"application/json\">";
  const std::size_t begin = html.find(open) + open.size();
  return nlohmann::json::parse(html.substr(begin, html.find("</script>", begin) - begin));
}

TEST(ViewCommand, WritesThePageOfARunAndItsBranch) {
  std::string scenario = read(fs::path(NODUS_SOURCE_DIR) / "examples" / "tool_drag.yaml");
  scenario += R"(
branches:
  - name: back
    from: press
    stages:
      - name: drag_back
        steps: 4
        motions:
          press: {translation: [0, -0.2, -0.1]}
)";
  const fs::path yaml = scratch() / "drag.yaml", dir = scratch() / "drag";
  std::ofstream(yaml) << scenario;
  const Outcome run = nodus("run " + yaml.string() + " --out " + dir.string() + " --quiet");
  ASSERT_EQ(run.status, 0) << run.err;

  const Outcome view = nodus("view " + dir.string());
  if (viewer_bundle().empty()) {
    EXPECT_EQ(view.status, 2);
    EXPECT_NE(view.err.find("scripts/setup.sh"), std::string::npos) << view.err;
    GTEST_SKIP() << "nodus was built without the viewer's page script";
  }
  ASSERT_EQ(view.status, 0) << view.err;
  EXPECT_NE(view.out.find("view.html"), std::string::npos) << view.out;
  const nlohmann::json page = page_data(read(dir / "view.html"));
  const ResultRun result = read_result_h5(dir);
  ASSERT_EQ(page["runs"].size(), 2u);
  EXPECT_EQ(page["title"], "drag");
  EXPECT_EQ(page["runs"][1]["name"], "back");
  EXPECT_EQ(page["runs"][0]["states"].size(), result.states.size());
  EXPECT_EQ(page["runs"][1]["states"].size(), result.branches.at(0).states.size());
  EXPECT_EQ(page["runs"][0]["beams"].size(), 2u);
  EXPECT_TRUE(page["runs"][0]["beams"][1]["tool"].get<bool>());
  std::size_t contacts = 0;
  for (const auto& s : page["runs"][0]["states"]) contacts += s["contacts"].get<std::size_t>();
  EXPECT_GT(contacts, 0u);

  // --out elsewhere, and a folder with a trailing slash.
  const Outcome elsewhere = nodus("view " + dir.string() + "/ --out " + (scratch() / "page.html").string());
  EXPECT_EQ(elsewhere.status, 0) << elsewhere.err;
  EXPECT_EQ(read(scratch() / "page.html"), read(dir / "view.html"));
  fs::remove_all(scratch());
}

TEST(ViewCommand, AFolderWithoutResultsIsOneLineAndStatus2) {
  const Outcome view = nodus("view " + (scratch() / "nothing_here").string());
  EXPECT_EQ(view.status, 2);
  EXPECT_EQ(view.err.find('\n'), view.err.size() - 1) << view.err;
  EXPECT_NE(view.err.find("result.h5"), std::string::npos) << view.err;
  EXPECT_FALSE(fs::exists(scratch() / "nothing_here" / "view.html"));
  fs::remove_all(scratch());
}

}  // namespace
}  // namespace nodus::output
