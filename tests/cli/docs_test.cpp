// The documentation: its generated parts are what the binaries print (the command reference
// is each command's --help; the records table is checked in columns_test.cpp), every
// relative link resolves, and the README stays short. scripts/update_docs.py regenerates
// the generated parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(LDM_TEST_SOURCE_DIR) / "..";

// What scripts/update_docs.py writes for a command's output: the binary's path shown as its
// name, trailing spaces and blank lines removed.
std::string normalised(std::string text, const std::string& binary, const std::string& name) {
  for (size_t at; (at = text.find(binary)) != std::string::npos;) text.replace(at, binary.size(), name);
  std::stringstream in(text);
  std::string out, blank;
  for (std::string line; std::getline(in, line);) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty()) {
      if (!out.empty()) blank += "\n";
      continue;
    }
    out += blank + line + "\n";
    blank.clear();
  }
  return out;
}

struct Block {
  std::string command;  // e.g. "ldmbench run --help"
  std::string text;     // between the markers, without the code fence
};

// The generated blocks of a file: <!-- generated:begin COMMAND -->, a ```text fence, the
// command's output, the closing fence, <!-- generated:end -->.
std::vector<Block> generated_blocks(const std::string& text) {
  const std::string begin = "<!-- generated:begin ", open = " -->\n```text\n",
                    close = "```\n<!-- generated:end -->";
  std::vector<Block> blocks;
  for (size_t at = text.find(begin); at != std::string::npos; at = text.find(begin, at)) {
    const size_t command = at + begin.size();
    const size_t body = text.find(open, command);
    const size_t end = text.find(close, command);
    EXPECT_TRUE(body != std::string::npos && end != std::string::npos && body < end)
        << "a generated block without its fence or end marker at offset " << at;
    if (body == std::string::npos || end == std::string::npos || body > end) break;
    blocks.push_back({text.substr(command, body - command),
                      text.substr(body + open.size(), end - body - open.size())});
    at = end;
  }
  return blocks;
}

TEST(Docs, CliReferenceIsTheHelp) {
  const std::string reference = test::read_text((kRoot / "docs" / "reference" / "cli.md").string());
  ASSERT_FALSE(reference.empty()) << "docs/reference/cli.md is missing";
  const auto blocks = generated_blocks(reference);
  ASSERT_FALSE(blocks.empty()) << "docs/reference/cli.md has no generated blocks";
  // Every command of `ldmbench --help` has its block.
  std::string commands;
  for (const auto& b : blocks) commands += b.command + "\n";
  const test::Outcome top = test::ldmbench("--help");
  ASSERT_EQ(top.status, 0) << top.output;
  const std::regex subcommand("\n  ([a-z][a-z-]*) ");
  int listed = 0;
  for (auto it = std::sregex_iterator(top.output.begin(), top.output.end(), subcommand);
       it != std::sregex_iterator(); ++it, ++listed)
    EXPECT_NE(commands.find("ldmbench " + (*it)[1].str() + " --help\n"), std::string::npos)
        << "docs/reference/cli.md has no block for `ldmbench " << (*it)[1].str()
        << " --help`: run scripts/update_docs.py";
  EXPECT_GE(listed, 14) << top.output;

  for (const auto& b : blocks) {
    const std::string name = b.command.substr(0, b.command.find(' '));
    std::string binary;
    if (name == "ldmbench") binary = LDM_BINARY_PATH;
#ifdef LDM_GBENCH_PATH
    if (name == "ldmbench_gbench") binary = LDM_GBENCH_PATH;
#else
    if (name == "ldmbench_gbench") continue;  // not built here
#endif
    ASSERT_FALSE(binary.empty()) << "unknown program in `" << b.command << "`";
    const test::Outcome o = test::run_shell(binary + b.command.substr(name.size()));
    EXPECT_EQ(o.status, 0) << b.command << "\n" << o.output;
    EXPECT_EQ(b.text, normalised(o.output, binary, name))
        << "docs/reference/cli.md is stale for `" << b.command << "`: run scripts/update_docs.py";
  }
}

TEST(Docs, EveryRelativeLinkResolves) {
  const test::Outcome o = test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR +
                                          "/cli/check_doc_links.py " + kRoot.string());
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find(" relative links checked, 0 broken"), std::string::npos) << o.output;
}

// The checker finds what it is for: a missing file, a missing heading, and ignores code.
TEST(Docs, LinkCheckerFindsBrokenLinks) {
  const fs::path root = test::make_temp_dir("ldm-doc-links");
  fs::create_directories(root / "docs" / "guide");
  const auto write = [](const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
  };
  write(root / "README.md",
        "# Title\n\n## A heading, with `code`\n\n[ok](docs/guide/a.md#second-part) "
        "[self](#a-heading-with-code) `[not a link](nowhere.md)`\n\n```\n[code](nowhere.md)\n```\n");
  write(root / "docs" / "guide" / "a.md",
        "# A\n\n## Second part\n\n[up](../../README.md) [gone](b.md) [bad anchor](../../README.md#nope)\n"
        "![image](missing.png) [web](https://example.org/x.md)\n");
  const test::Outcome o = test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR +
                                          "/cli/check_doc_links.py " + root.string());
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("docs/guide/a.md:5: b.md: no such file"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("docs/guide/a.md:5: ../../README.md#nope: no heading #nope"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("docs/guide/a.md:6: missing.png: no such file"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("6 relative links checked, 3 broken"), std::string::npos) << o.output;
}

TEST(Docs, ReadmeIsShort) {
  const std::string readme = test::read_text((kRoot / "README.md").string());
  ASSERT_FALSE(readme.empty());
  const auto lines = std::count(readme.begin(), readme.end(), '\n');
  EXPECT_LT(lines, 300) << "README.md has " << lines
                        << " lines: it is the short entry point; move details into docs/";
  // The two commands CI and newcomers start from come first.
  const auto main_job = readme.find("scripts/main-job.sh");
  const auto test_sh = readme.find("scripts/test.sh");
  EXPECT_LT(main_job, 800u);
  EXPECT_LT(test_sh, 800u);
}

}  // namespace
}  // namespace ldm
