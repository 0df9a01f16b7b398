// LDM_SHADER_DUMP (harness/gl/shader_dump.h): what scripts/check-shaders.sh hands to glslang
// must be exactly what the driver compiled, one file per distinct text, complete even when
// several processes share the folder; and the check itself must be able to fail
// (tests/shaders/test_check_shaders.py, fake dumps).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "harness/gl/bindings.h"
#include "harness/gl/shader_dump.h"
#include "harness/gl/shader_program.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

// LDM_SHADER_DUMP set for one scope (after the context, whose self-tests build programs).
class DumpingTo {
 public:
  explicit DumpingTo(const std::string& folder) { setenv("LDM_SHADER_DUMP", folder.c_str(), 1); }
  ~DumpingTo() { unsetenv("LDM_SHADER_DUMP"); }
};

std::set<std::string> names_in(const std::string& folder) {
  std::set<std::string> names;
  if (fs::exists(folder))
    for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename());
  return names;
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(test::read_text(path)); }

const std::vector<ShaderStage> kDisplay = {{GL_VERTEX_SHADER, "viewer/display.vert", {}},
                                           {GL_FRAGMENT_SHADER, "viewer/display.frag", {}}};

// Each stage's text is preprocess_shader()'s, byte for byte, under its content hash and its
// stage; the sidecar names the file and every #line source string; the program names its
// stages in order.
TEST(ShaderDump, HoldsExactlyTheSourceCompiledAndItsProgram) {
  test::gl_context();
  const std::string folder = test::make_temp_dir("ldm-shader-dump") + "/dump";
  {
    DumpingTo dumping(folder);
    build_program(kDisplay, {});
  }
  const std::set<std::string> names = names_in(folder);
  ASSERT_EQ(names.size(), 5u) << "two sources, two sidecars, one program";
  std::string program;
  for (const std::string& name : names)
    if (name.size() > 13 && name.substr(name.size() - 13) == ".program.json") program = name;
  ASSERT_FALSE(program.empty());
  const nlohmann::json stages = read_json(folder + "/" + program)["stages"];
  ASSERT_EQ(stages.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const std::string name = stages[i].get<std::string>();
    EXPECT_EQ(fs::path(name).extension(), i == 0 ? ".vert" : ".frag");
    std::vector<std::string> table;
    const std::string expected = preprocess_shader(kDisplay[i].file, {}, {}, &table);
    EXPECT_EQ(test::read_text(folder + "/" + name), expected);
    const nlohmann::json sidecar = read_json(folder + "/" + name + ".json");
    EXPECT_EQ(sidecar["file"], kDisplay[i].file);
    EXPECT_EQ(sidecar["stage"], shader_stage_name(kDisplay[i].type));
    EXPECT_EQ(sidecar["source_strings"].get<std::vector<std::string>>(), table);
    EXPECT_TRUE(sidecar["preludes"].empty());
  }
}

// The same text is one file however often it is built; another define is another file; a
// prelude is named in the sidecar.
TEST(ShaderDump, OneFilePerDistinctText) {
  test::gl_context();
  const std::string folder = test::make_temp_dir("ldm-shader-dump") + "/dump";
  DumpingTo dumping(folder);
  build_program(kDisplay, {});
  build_program(kDisplay, {});
  EXPECT_EQ(names_in(folder).size(), 5u);
  build_program(kDisplay, ShaderDefines().set("LDM_UNUSED_DEFINE", 1));
  EXPECT_EQ(names_in(folder).size(), 10u);
  build_program({{GL_COMPUTE_SHADER, "ldm/common/reduce_uint.comp", {"common/ldm_views.glsl"}}},
                binding_defines().set("REDUCE_ITEMS_PER_INVOCATION", "4u"));
  bool found = false;
  for (const std::string& name : names_in(folder))
    if (fs::path(name).extension() == ".json" && name.find(".comp.json") != std::string::npos) {
      const nlohmann::json sidecar = read_json(folder + "/" + name);
      EXPECT_EQ(sidecar["preludes"], nlohmann::json::array({"common/ldm_views.glsl"}));
      found = true;
    }
  EXPECT_TRUE(found);
}

TEST(ShaderDump, NothingWithoutTheVariable) {
  test::gl_context();
  unsetenv("LDM_SHADER_DUMP");
  EXPECT_EQ(dump_shader_source(GL_VERTEX_SHADER, "viewer/display.vert", {}, "text", {}), "");
  setenv("LDM_SHADER_DUMP", "", 1);
  EXPECT_EQ(dump_shader_source(GL_VERTEX_SHADER, "viewer/display.vert", {}, "text", {}), "");
  unsetenv("LDM_SHADER_DUMP");
}

// A folder that cannot be written fails the build that asked for the dump, naming it: a
// check that silently missed programs would pass vacuously.
TEST(ShaderDump, AFolderThatCannotBeWrittenFailsTheBuild) {
  test::gl_context();
  const std::string blocker = test::make_temp_dir("ldm-shader-dump") + "/a-file";
  std::ofstream(blocker) << "not a folder\n";
  DumpingTo dumping(blocker + "/dump");
  try {
    build_program(kDisplay, {});
    FAIL() << "built without its dump";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find(blocker), std::string::npos) << e.what();
  }
}

// Processes sharing the folder (the check runs two drivers at once): every file complete,
// no temporary left, each source under the hash of its text.
TEST(ShaderDump, ParallelProcessesShareTheFolder) {
  const std::string folder = test::make_temp_dir("ldm-shader-dump") + "/dump";
  const std::string run = "LDM_SHADER_DUMP=" + folder + " " + LDM_BINARY_PATH +
                          " run --structure all --pass ao -N 2 -R 8 --image-size 16x16 --frames 1"
                          " --warmup 0 --time-target 0 --no-reference --no-images --out ";
  const std::string dir = test::make_temp_dir("ldm-shader-dump-runs");
  std::string command;
  for (int i = 0; i < 4; ++i) command += run + dir + "/" + std::to_string(i) + " > /dev/null 2>&1 & ";
  command += "wait";
  ASSERT_EQ(test::run_shell(command).status, 0);
  size_t sources = 0;
  for (const std::string& name : names_in(folder)) {
    EXPECT_NE(name[0], '.') << "a temporary was left: " << name;
    const std::string ext = fs::path(name).extension();
    if (ext == ".json") continue;
    ++sources;
    const std::string text = test::read_text(folder + "/" + name);
    EXPECT_EQ(text.rfind("#version 450 core\n", 0), 0u) << name;
    Fnv1a hash;
    hash.add_bytes(text.data(), text.size());
    EXPECT_EQ(fs::path(name).stem().string(), hex64(hash.value())) << "incomplete: " << name;
    EXPECT_TRUE(fs::exists(folder + "/" + name + ".json")) << name;
  }
  EXPECT_GT(sources, 20u);
  // Each run built the same programs: the four share one file per text.
  const test::Outcome alone = test::ldmbench(
      "run --structure all --pass ao -N 2 -R 8 --image-size 16x16 --frames 1 --warmup 0 "
      "--time-target 0 --no-reference --no-images --out " + dir + "/alone",
      "LDM_SHADER_DUMP=" + dir + "/alone-dump");
  ASSERT_EQ(alone.status, 0) << alone.output;
  EXPECT_EQ(names_in(folder), names_in(dir + "/alone-dump"));
}

// scripts/check_shaders.py against fake dumps: each kind of rejection and of missed variant
// fails it, naming the file; a clean dump passes (Python's unittest).
TEST(CheckShaders, FailsOnEveryKindOfFinding) {
  const test::Outcome o = test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR +
                                          "/shaders/test_check_shaders.py " + LDM_BINARY_PATH);
  EXPECT_EQ(o.status, 0) << o.output;
}

}  // namespace
}  // namespace ldm
