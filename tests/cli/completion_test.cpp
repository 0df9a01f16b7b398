// `ldmbench completion bash`, run in bash: the script is sourced, a command line is set up as
// bash sets it (COMP_LINE, COMP_POINT, COMP_WORDS, COMP_CWORD: tests/cli/complete_line.sh)
// and _ldmbench's COMPREPLY is compared with what the binary itself lists (its subcommands,
// structures, scenes) and with the axis registry's choices.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

std::set<std::string> lines_of(const std::string& text) {
  std::set<std::string> out;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.insert(line);
  return out;
}

// The first column of each line of `ldmbench ARGS` (scenes prints "name<TAB>description").
std::set<std::string> names_listed_by(const std::string& args) {
  const test::Outcome o = test::ldmbench(args);
  EXPECT_EQ(o.status, 0) << o.output;
  std::set<std::string> names;
  for (const std::string& line : lines_of(o.output)) names.insert(line.substr(0, line.find('\t')));
  return names;
}

class Completion : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::make_temp_dir("ldm-completion");
    script = (fs::path(dir) / "ldmbench.bash").string();
    const test::Outcome o = test::ldmbench("completion bash > " + script);
    ASSERT_EQ(o.status, 0) << o.output;
  }
  // The candidates bash would offer for `line` (cursor at its end), run in `dir`.
  std::set<std::string> complete(const std::string& line) const {
    const test::Outcome o = test::run_shell("cd " + dir + " && bash " + LDM_TEST_SOURCE_DIR +
                                            "/cli/complete_line.sh " + script + " _ldmbench '" + line + "'");
    EXPECT_EQ(o.status, 0) << line << "\n" << o.output;
    return lines_of(o.output);
  }
  std::string dir, script;
};

TEST_F(Completion, ScriptIsValidBashAndRegistersItself) {
  const test::Outcome o = test::run_shell("bash -c 'source " + script + " && complete -p ldmbench'");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("complete -F _ldmbench ldmbench"), std::string::npos) << o.output;
}

TEST_F(Completion, SubcommandsAreThoseOfHelp) {
  const test::Outcome help = test::ldmbench("--help");
  ASSERT_EQ(help.status, 0) << help.output;
  std::set<std::string> expected = {"--help", "-h", "--version"};
  const std::regex subcommand("\n  ([a-z][a-z-]*) ");
  for (auto it = std::sregex_iterator(help.output.begin(), help.output.end(), subcommand);
       it != std::sregex_iterator(); ++it)
    expected.insert((*it)[1].str());
  EXPECT_GE(expected.size(), 18u);
  EXPECT_EQ(complete("ldmbench "), expected);
  EXPECT_EQ(complete("ldmbench stru"), std::set<std::string>{"structures"});
  EXPECT_EQ(complete("ldmbench completion "), std::set<std::string>{"bash"});
}

TEST_F(Completion, OptionsOfTheSubcommand) {
  EXPECT_EQ(complete("ldmbench run --no-im"), std::set<std::string>{"--no-images"});
  EXPECT_EQ(complete("ldmbench compare --ignore"), std::set<std::string>{"--ignore-param"});
  const std::set<std::string> run = complete("ldmbench run -");
  for (const char* option : {"--structure", "--scene", "-N", "--views", "--param", "--out", "--cache-dir"})
    EXPECT_TRUE(run.count(option)) << option;
  EXPECT_FALSE(run.count("--ignore-param")) << "an option of compare offered for run";
  // interleave's command line after --: that subcommand's options.
  EXPECT_EQ(complete("ldmbench interleave A B -- run --str"), std::set<std::string>{"--structure"});
  EXPECT_TRUE(complete("ldmbench interleave A B -- sw").count("sweep"));
}

TEST_F(Completion, AxisValuesFromTheRegistry) {
  std::set<std::string> structures = names_listed_by("structures");
  ASSERT_GE(structures.size(), 6u);
  structures.insert("all");
  EXPECT_EQ(complete("ldmbench run --structure "), structures);
  // A comma list completes its last item.
  std::set<std::string> after_comma;
  for (const auto& s : complete("ldmbench run --structure psppsll,pp")) after_comma.insert(s);
  EXPECT_EQ(after_comma, (std::set<std::string>{"psppsll,ppsll", "psppsll,ppfla"}));
  const std::set<std::string> scenes = complete("ldmbench run --scene ");
  for (const std::string& scene : names_listed_by("scenes")) EXPECT_TRUE(scenes.count(scene)) << scene;
  EXPECT_EQ(complete("ldmbench run --sizing=prev"), std::set<std::string>{"previous_frame"});
  EXPECT_EQ(complete("ldmbench run --pass r"), (std::set<std::string>{"rtao", "rtao_gpu"}));
  EXPECT_EQ(complete("ldmbench run --pass g"), std::set<std::string>{"gtao"});
  EXPECT_EQ(complete("ldmbench sweep x --egl-platform s"), std::set<std::string>{"surfaceless"});
}

// --param OWNER:KEY=VALUE: bash breaks the word at ':' and '=', so what it is offered is the
// rest after the last break.
TEST_F(Completion, ParametersOfStructuresAndPasses) {
  EXPECT_EQ(complete("ldmbench run --param ppf"), std::set<std::string>{"ppfla:k="});
  EXPECT_EQ(complete("ldmbench run --param habuffer:key"), std::set<std::string>{"key_bits="});
  const test::Outcome axes = test::ldmbench("axes --json");
  ASSERT_EQ(axes.status, 0) << axes.output;
  EXPECT_NE(axes.output.find("\"habuffer\""), std::string::npos);
  const std::set<std::string> key_bits = complete("ldmbench run --param habuffer:key_bits=");
  EXPECT_TRUE(key_bits.count("32") && key_bits.count("64")) << key_bits.size();
}

TEST_F(Completion, FilesWherePathsGo) {
  std::ofstream(fs::path(dir) / "my-sweep.json") << "{}";
  EXPECT_EQ(complete("ldmbench sweep my-"), std::set<std::string>{"my-sweep.json"});
  EXPECT_EQ(complete("ldmbench run --out my-"), std::set<std::string>{"my-sweep.json"});
  EXPECT_TRUE(complete("ldmbench run --scene my-").count("my-sweep.json"));
  // A number is no file: -N offers nothing.
  EXPECT_TRUE(complete("ldmbench run -N my-").empty());
}

}  // namespace
}  // namespace ldm
