// docs/layout.md names every folder of src/nodus/ (a "## FOLDER/" heading) and every unit in it (its header's
// name in backquotes), so that a newcomer finds each file from the map.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

TEST(DocsLayout, NamesEveryFolderAndUnit) {
  std::ifstream in(fs::path(NODUS_SOURCE_DIR) / "docs" / "layout.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  ASSERT_FALSE(docs.empty());
  int units = 0;
  for (const fs::directory_entry& folder :
       fs::directory_iterator(fs::path(NODUS_SOURCE_DIR) / "src" / "nodus")) {
    if (!folder.is_directory()) continue;
    const std::string name = folder.path().filename().string();
    EXPECT_NE(docs.find("\n## " + name + "/"), std::string::npos)
        << "docs/layout.md: no section for " << name;
    for (const fs::directory_entry& file : fs::directory_iterator(folder.path())) {
      if (file.path().extension() != ".hpp") continue;
      ++units;
      const std::string unit = file.path().stem().string();
      EXPECT_NE(docs.find("`" + unit + "`"), std::string::npos)
          << "docs/layout.md does not name " << name << "/" << unit;
    }
  }
  EXPECT_GT(units, 50);
}

}  // namespace
