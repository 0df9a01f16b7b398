// The floors of docs/design/architecture.md, enforced: every #include of harness/ and
// ldm_impls/ runs to the same floor or down, every folder has a floor, and the doc's list of
// known leaks is exactly the includes that still run up.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace ldm {
namespace {

namespace fs = std::filesystem;
const fs::path kRoot = fs::path(LDM_TEST_SOURCE_DIR) / "..";

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The Markdown table between <!-- NAME:begin --> and <!-- NAME:end -->: its body rows' cells.
std::vector<std::vector<std::string>> doc_table(const std::string& name) {
  const std::string doc = read(kRoot / "docs" / "design" / "architecture.md");
  const size_t begin = doc.find("<!-- " + name + ":begin -->");
  const size_t end = doc.find("<!-- " + name + ":end -->");
  EXPECT_NE(begin, std::string::npos) << "architecture.md has no " << name << " table";
  EXPECT_NE(end, std::string::npos);
  std::vector<std::vector<std::string>> rows;
  if (begin == std::string::npos || end == std::string::npos) return rows;
  std::istringstream lines(doc.substr(begin, end - begin));
  int row = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != '|') continue;
    if (row++ < 2) continue;  // header and separator
    std::vector<std::string> cells;
    std::istringstream parts(line.substr(1));
    for (std::string cell; std::getline(parts, cell, '|');) {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    rows.push_back(cells);
  }
  return rows;
}

std::map<std::string, int> floors() {
  std::map<std::string, int> out;
  for (const auto& row : doc_table("floors")) {
    std::istringstream folders(row.at(1));
    for (std::string folder; folders >> folder;) out[folder] = std::stoi(row.at(0));
  }
  return out;
}

// The folder a source file belongs to: harness/<x>, ldm_impls/<family> or ldm_impls itself.
std::string folder_of(const std::string& relative) {
  const fs::path p(relative);
  auto it = p.begin();
  const std::string top = (it++)->string();
  const std::string second = it != p.end() ? it->string() : "";
  if (++it == p.end()) return top;  // a file directly under the top folder
  return top + "/" + second;
}

struct Include {
  std::string file, header;
};

std::vector<Include> project_includes() {
  std::vector<Include> out;
  const std::regex include(R"re(^\s*#\s*include\s+"((harness|ldm_impls)/[^"]+)")re");
  for (const char* top : {"harness", "ldm_impls"})
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string relative = fs::relative(entry.path(), kRoot).generic_string();
      std::istringstream lines(read(entry.path()));
      std::smatch m;
      for (std::string line; std::getline(lines, line);)
        if (std::regex_search(line, m, include)) out.push_back({relative, m[1].str()});
    }
  return out;
}

TEST(Layering, EveryFolderHasAFloor) {
  const auto floor = floors();
  ASSERT_FALSE(floor.empty());
  for (const char* top : {"harness", "ldm_impls"})
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string folder = folder_of(fs::relative(entry.path(), kRoot).generic_string());
      EXPECT_TRUE(floor.count(folder)) << folder << " (" << entry.path().filename().string()
                                       << ") has no floor in docs/design/architecture.md's floors table";
    }
}

TEST(Layering, NoIncludeRunsUpButTheDocumentedLeaks) {
  const auto floor = floors();
  std::set<std::pair<std::string, std::string>> leaks;
  for (const auto& row : doc_table("leaks")) leaks.insert({row.at(0), row.at(1)});
  std::set<std::pair<std::string, std::string>> seen;
  size_t checked = 0;
  for (const Include& inc : project_includes()) {
    const std::string from = folder_of(inc.file), to = folder_of(inc.header);
    if (!floor.count(from) || !floor.count(to)) continue;  // EveryFolderHasAFloor says so
    ++checked;
    if (floor.at(to) <= floor.at(from)) continue;
    if (leaks.count({inc.file, inc.header})) {
      seen.insert({inc.file, inc.header});
      continue;
    }
    ADD_FAILURE() << inc.file << " (floor " << floor.at(from) << ", " << from << ") includes " << inc.header
                  << " (floor " << floor.at(to) << ", " << to
                  << "): an include running up the floors of docs/design/architecture.md";
  }
  EXPECT_GT(checked, 500u);  // the walk found the sources
  for (const auto& leak : leaks)
    EXPECT_TRUE(seen.count(leak)) << leak.first << " -> " << leak.second
                                  << " is listed as a known leak but no longer leaks: remove it from the list";
}

TEST(Layering, TheCheckCatchesAnIncludeRunningUp) {
  // The rule itself on a made-up include: util (0) including run (8) runs up.
  const auto floor = floors();
  EXPECT_LT(floor.at(folder_of("harness/util/files.cpp")), floor.at(folder_of("harness/run/run_command.h")));
  EXPECT_EQ(folder_of("ldm_impls/ldm_structure.h"), "ldm_impls");
  EXPECT_EQ(folder_of("ldm_impls/common/sizing.h"), "ldm_impls/common");
  EXPECT_EQ(folder_of("harness/run/run_command.h"), "harness/run");
}

}  // namespace
}  // namespace ldm
