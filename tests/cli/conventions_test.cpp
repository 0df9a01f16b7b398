// Command-line conventions: --version (and the version stamp a tarball build gets), the
// unknown-subcommand message, and the reference cache's default folder under XDG_CACHE_HOME.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::ldmbench;

const fs::path kSourceRoot = fs::path(LDM_TEST_SOURCE_DIR) / "..";

TEST(Conventions, VersionNamesTheProjectVersionAndCommit) {
  const Outcome o = ldmbench("--version");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_TRUE(std::regex_match(o.output, std::regex(R"(ldmbench \d+\.\d+\.\d+ \(commit ([0-9a-f]{7,40}|unknown)(, dirty)?\)\n)")))
      << o.output;
  // The project version is CMakeLists.txt's project(... VERSION x.y.z).
  const std::string cmake = test::read_text((kSourceRoot / "CMakeLists.txt").string());
  std::smatch m;
  ASSERT_TRUE(std::regex_search(cmake, m, std::regex(R"(project\(ldmbench VERSION ([0-9.]+))")));
  EXPECT_NE(o.output.find("ldmbench " + m[1].str() + " "), std::string::npos) << o.output;
  const Outcome help = ldmbench("--help");
  EXPECT_NE(help.output.find("\n" + o.output), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("--version"), std::string::npos) << help.output;
}

// cmake/VersionStamp.cmake, run as the build runs it: "unknown" outside git (a tarball), the
// commit and a clean tree inside, ", dirty" once a tracked file changes; an unchanged stamp
// is not rewritten (so nothing recompiles).
TEST(Conventions, VersionStampOutsideAndInsideGit) {
  const fs::path dir = test::make_temp_dir("ldm-stamp");
  const fs::path source = dir / "src", out = dir / "version.cpp";
  fs::create_directories(source);
  std::ofstream(source / "file.txt") << "one\n";
  const std::string stamp = "cmake -DSOURCE=" + source.string() + " -DIN=" + (kSourceRoot / "cmake" / "version.cpp.in").string() +
                            " -DOUT=" + out.string() + " -DPROJECT_VERSION=9.8.7 -P " +
                            (kSourceRoot / "cmake" / "VersionStamp.cmake").string();
  Outcome o = test::run_shell(stamp);
  ASSERT_EQ(o.status, 0) << o.output;
  std::string text = test::read_text(out.string());
  EXPECT_NE(text.find("git_commit() { return \"unknown\"; }"), std::string::npos) << text;
  EXPECT_NE(text.find("git_tree_dirty() { return false; }"), std::string::npos) << text;
  EXPECT_NE(text.find("ldmbench_version() { return \"9.8.7\"; }"), std::string::npos) << text;

  o = test::run_shell("cd " + source.string() + " && git init -q && git add file.txt && git -c user.name=t "
                      "-c user.email=t@t commit -qm one && git rev-parse --short=12 HEAD");
  ASSERT_EQ(o.status, 0) << o.output;
  const std::string commit = o.output.substr(0, o.output.find('\n'));
  ASSERT_EQ(test::run_shell(stamp).status, 0);
  text = test::read_text(out.string());
  EXPECT_NE(text.find("git_commit() { return \"" + commit + "\"; }"), std::string::npos) << text;
  EXPECT_NE(text.find("git_tree_dirty() { return false; }"), std::string::npos) << text;
  const auto written = fs::last_write_time(out);
  std::ofstream(source / "untracked.txt") << "not part of the commit\n";
  ASSERT_EQ(test::run_shell(stamp).status, 0);
  EXPECT_EQ(fs::last_write_time(out), written) << "an unchanged stamp was rewritten";

  std::ofstream(source / "file.txt") << "two\n";
  ASSERT_EQ(test::run_shell(stamp).status, 0);
  EXPECT_NE(test::read_text(out.string()).find("git_tree_dirty() { return true; }"), std::string::npos);
}

TEST(Conventions, UnknownSubcommandIsNamedWithTheList) {
  Outcome o = ldmbench("foo");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("unknown subcommand 'foo'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("subcommands: run sweep"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("did you mean"), std::string::npos) << o.output;
  o = ldmbench("strucures");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("unknown subcommand 'strucures' (did you mean 'structures'?)"), std::string::npos)
      << o.output;
  o = ldmbench("comp A B");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("(did you mean 'compare'?)"), std::string::npos) << o.output;
  // A known subcommand still parses its own options.
  EXPECT_EQ(ldmbench("structures").status, 0);
}

// The reference cache's default: $XDG_CACHE_HOME/ldmbench/references, else
// $HOME/.cache/ldmbench/references; --cache-dir wins; neither variable is an error, before
// anything is written.
class ReferenceCacheDefault : public ::testing::Test {
 protected:
  // A tiny AO run with a reference, in `dir`, after the shell assignments `environment`.
  Outcome run(const std::string& environment, const std::string& extra = "") {
    return ldmbench("run -N 2 -R 8 --width 16 --height 16 --frames 1 --time-target 0 --warmup 0 --reference-spp 4 "
                    "--no-images --out " + (dir / ("run" + std::to_string(++runs))).string() + " " + extra,
                    "cd " + dir.string() + " && env -u XDG_CACHE_HOME -u HOME " + environment);
  }
  static size_t entries(const fs::path& folder) {
    size_t n = 0;
    if (fs::is_directory(folder))
      for (const auto& e : fs::directory_iterator(folder)) n += e.path().extension() == ".json";
    return n;
  }
  fs::path dir = test::make_temp_dir("ldm-xdg");
  int runs = 0;
};

TEST_F(ReferenceCacheDefault, UnderXdgCacheHomeThenHome) {
  Outcome o = run("XDG_CACHE_HOME=" + (dir / "xdg").string() + " HOME=" + (dir / "home").string());
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(entries(dir / "xdg" / "ldmbench" / "references"), 1u);
  // (Mesa puts its shader cache there too: only ldmbench/ is looked at.)
  EXPECT_FALSE(fs::exists(dir / "home" / ".cache" / "ldmbench")) << "HOME used although XDG_CACHE_HOME is set";
  EXPECT_FALSE(fs::exists(dir / "results" / "cache")) << "the old default, under the working folder";

  // A relative XDG_CACHE_HOME is invalid (XDG base directory specification): HOME's.
  o = run("XDG_CACHE_HOME=relative HOME=" + (dir / "home").string());
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(entries(dir / "home" / ".cache" / "ldmbench" / "references"), 1u);
  EXPECT_FALSE(fs::exists(dir / "relative" / "ldmbench"));

  // --cache-dir wins over both.
  o = run("XDG_CACHE_HOME=" + (dir / "xdg2").string(), "--cache-dir " + (dir / "explicit").string());
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(entries(dir / "explicit"), 1u);
  EXPECT_FALSE(fs::exists(dir / "xdg2" / "ldmbench"));
}

TEST_F(ReferenceCacheDefault, NeitherVariableIsAClearErrorBeforeAnyOutput) {
  const Outcome o = run("");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("neither XDG_CACHE_HOME (absolute) nor HOME is set; give --cache-dir"), std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir / "run1")) << "an output folder was created";
  // Without references no cache is needed.
  EXPECT_EQ(run("", "--no-reference").status, 0);
}

}  // namespace
}  // namespace ldm
