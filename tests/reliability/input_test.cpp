// Bad input, always a clear refusal (issue 19, items 4, 5, 8 and 10): keys given twice in a
// scene or sweep file are named with both lines; nesting 200,000 deep is refused, not a
// SIGSEGV; huge files are refused by their size before they are read; and the messages that
// said the wrong thing (a folder as --scene, a NUL byte, translate 1e18, --d-max 3e38, a
// top-level array, a missing mtllib, scene-file values the command line refuses).
#include <gtest/gtest.h>

#include <chrono>

#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

void expect_refused(const Outcome& o, const std::vector<std::string>& parts, const std::string& what) {
  EXPECT_EQ(o.status, 2) << what << "\n" << o.output;
  for (const auto& part : parts) EXPECT_NE(o.output.find(part), std::string::npos) << what << ": " << part << "\n" << o.output;
}

TEST(ReliabilityInput, KeysGivenTwiceAreNamedWithBothLines) {
  const fs::path dir = test::make_temp_dir("ldm-input");
  // The last "name" used to win without a word (and a wrong type blamed the wrong key).
  const std::string scene = write_file(dir / "dup.json", "{\n  \"name\": \"a\",\n  \"generator\": {\"type\": \"cornell\"},\n"
                                                         "  \"name\": 3\n}\n");
  expect_refused(test::ldmbench("run --scene " + scene + " -N 2" + kTiny + "--dry-run"),
                 {"dup.json", "line 4", "key \"name\"", "appears twice", "first at line 2"}, "scene");
  EXPECT_EQ(test::ldmbench("run --scene " + scene + " -N 2" + kTiny + "--dry-run").output.find("must be a string"),
            std::string::npos);
  const std::string nested = write_file(dir / "nested.json", "{\"generator\": {\"type\": \"cornell\"},\n"
                                                             " \"camera\": {\"eye\": [0, 1, 5],\n"
                                                             "             \"eye\": [0, 1, 6]}}\n");
  expect_refused(test::ldmbench("run --scene " + nested + " -N 2" + kTiny + "--dry-run"),
                 {"nested.json", "key \"eye\" at /camera/eye", "line 3", "first at line 2"}, "nested");
  const std::string sweep = write_file(dir / "sweep.json", "{\"axes\": {\n  \"views\": [2, 4],\n  \"r_ldm\": 8,\n"
                                                           "  \"views\": [8]\n}}\n");
  expect_refused(test::ldmbench("sweep " + sweep + " --dry-run"),
                 {"sweep.json", "key \"views\" at /axes/views", "line 4", "first at line 2"}, "sweep");
}

TEST(ReliabilityInput, NestingTooDeepIsRefusedNotACrash) {
  const fs::path dir = test::make_temp_dir("ldm-input");
  // 200,000 arrays overflowed the stack in the JSON library's copy (SIGSEGV, exit 139).
  for (const size_t depth : {100000, 200000}) {
    const std::string sweep = write_file(dir / ("deep" + std::to_string(depth) + ".json"),
                                         "{\"axes\": {\"views\": " + std::string(depth, '[') + std::string(depth, ']') + "}}");
    expect_refused(test::ldmbench("sweep " + sweep + " --dry-run"), {"nested deeper than 64 levels", "line 1"},
                   "sweep depth " + std::to_string(depth));
  }
  std::string objects;
  for (int i = 0; i < 200000; ++i) objects += "{\"a\":";
  objects += "1" + std::string(200000, '}');
  const std::string scene = write_file(dir / "deep-scene.json", objects);
  expect_refused(test::ldmbench("run --scene " + scene + " -N 2" + kTiny + "--dry-run"),
                 {"deep-scene.json", "nested deeper than 64 levels"}, "scene");
  // A journal line too (a run folder is read back by resume, merge, compare and report).
  const fs::path out = dir / "run";
  ASSERT_EQ(test::ldmbench("run -N 2" + kTiny + "--out " + out.string()).status, 0);
  {
    std::ofstream journal(out / "records.jsonl", std::ios::app);
    journal << "{\"record\": {\"config_id\": " << std::string(200000, '[') << std::string(200000, ']') << "}}\n";
  }
  expect_refused(test::ldmbench("run -N 2" + kTiny + "--out " + out.string()), {"records.jsonl:", "nested deeper"}, "journal");
  expect_refused(test::ldmbench("merge " + (dir / "merged").string() + " " + out.string()), {"records.jsonl:", "nested deeper"},
                 "merge");
}

TEST(ReliabilityInput, HugeInputsAreRefusedByTheirSizeBeforeReading) {
  const fs::path dir = test::make_temp_dir("ldm-input");
  const fs::path obj = dir / "huge.obj";
  // A sparse 1 GB OBJ: it took 3.1 GB and 17 s to refuse, and ended in bad_alloc (exit 1)
  // under a 4 GB address-space cap.
  std::ofstream(obj).close();
  fs::resize_file(obj, 1ull << 30);
  // Refused by its size, before reading (the message names the limit; under the 4 GB cap a
  // read would have ended in bad_alloc instead), whatever the machine's speed.
  const Outcome o = test::run_shell("ulimit -v 4000000; " + std::string(LDM_BINARY_PATH) + " run --scene " + obj.string() +
                                    " -N 2" + kTiny + "--dry-run");
  expect_refused(o, {"huge.obj", "1024 MiB", "larger than the input limit of 512 MiB", "LDMBENCH_MAX_INPUT_MIB"}, "obj");
  EXPECT_EQ(o.output.find("bad_alloc"), std::string::npos) << o.output;
  // Named at its JSON path when a scene file refers to it; sweep files likewise.
  const std::string scene = write_file(dir / "scene.json", "{\"meshes\": [{\"file\": \"huge.obj\"}]}");
  expect_refused(test::ldmbench("run --scene " + scene + " -N 2" + kTiny + "--dry-run"),
                 {"scene.json: /meshes/0/file", "larger than the input limit"}, "scene");
  const fs::path sweep = dir / "huge.json";
  std::ofstream(sweep).close();
  fs::resize_file(sweep, 1ull << 30);
  expect_refused(test::ldmbench("sweep " + sweep.string() + " --dry-run"), {"sweep file", "larger than the input limit"},
                 "sweep");
  // The limit is the user's to set.
  const std::string small = write_file(dir / "small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n" + std::string(4096, '#'));
  expect_refused(test::ldmbench("run --scene " + small + " -N 2" + kTiny + "--dry-run", "LDMBENCH_MAX_INPUT_MIB=0.001"),
                 {"small.obj", "larger than the input limit of 0.001 MiB"}, "limit");
  expect_refused(test::ldmbench("run --scene " + small + " -N 2" + kTiny + "--dry-run", "LDMBENCH_MAX_INPUT_MIB=lots"),
                 {"LDMBENCH_MAX_INPUT_MIB='lots'"}, "bad limit");
  EXPECT_EQ(test::ldmbench("run --scene " + small + " -N 2" + kTiny + "--dry-run", "LDMBENCH_MAX_INPUT_MIB=1").status, 0);
}

TEST(ReliabilityInput, MessagesSayWhatIsWrong) {
  const fs::path dir = test::make_temp_dir("ldm-input");
  // A folder given as --scene said "malformed JSON ... unexpected end of input".
  fs::create_directories(dir / "folder");
  expect_refused(test::ldmbench("run --scene " + (dir / "folder").string() + " -N 2" + kTiny + "--dry-run"),
                 {"is a folder"}, "folder");
  // A NUL byte ended the message where it stood.
  std::string nul = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 2";
  nul += '\0';
  nul += " 3\nf 1 2 3\n";
  const std::string obj = write_file(dir / "nul.obj", nul);
  expect_refused(test::ldmbench("run --scene " + obj + " -N 2" + kTiny + "--dry-run"),
                 {"nul.obj:4", "\\x00' is not a number"}, "nul");
  // translate 1e18 said "zero area": it placed the mesh in float, where floats are far
  // apart. Placed in double and rebased (issue 35), 1e15 away loads; past the extent
  // (1e18 is past the float 1e18 bound) is refused naming the vertex's line and the limit.
  write_file(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string far = write_file(dir / "far.json", R"({"meshes": [{"file": "tri.obj", "translate": [1e18, 0, 0]}]})");
  expect_refused(test::ldmbench("run --scene " + far + " -N 2" + kTiny + "--dry-run"),
                 {"tri.obj:1", "far.json", "scale and translate", "beyond the representable scene extent"},
                 "translate");
  const std::string placed = write_file(dir / "placed.json", R"({"meshes": [{"file": "tri.obj", "translate": [1e15, 0, 0]}]})");
  EXPECT_EQ(test::ldmbench("run --scene " + placed + " -N 2" + kTiny + "--dry-run").status, 0);
  // --d-max 3e38 printed its range as a 40-digit number; now one range for every source.
  Outcome o = test::ldmbench("run -N 2 --d-max 3e38" + kTiny + "--dry-run");
  expect_refused(o, {"--d-max", "[1e-30, 1e+30]"}, "--d-max");
  EXPECT_EQ(o.output.find("0000000000"), std::string::npos) << o.output;
  expect_refused(test::ldmbench("run -N 2 --structure psppsll --pass ao --param ao:d_max=3e38" + kTiny + "--dry-run"),
                 {"--param ao:d_max", "set it with --d-max"}, "ao:d_max");
  // Scene-file values the command line refuses were accepted from the file.
  const std::string big_d = write_file(dir / "d.json", R"({"generator": {"type": "cornell"}, "ao": {"d_max": 3e38}})");
  expect_refused(test::ldmbench("run --scene " + big_d + " -N 2" + kTiny + "--dry-run"),
                 {"d.json", "/ao/d_max", "[1e-30, 1e+30]"}, "scene d_max");
  const std::string big_offset =
      write_file(dir / "o.json", R"({"generator": {"type": "cornell"}, "ao": {"normal_offset": 1e30}})");
  expect_refused(test::ldmbench("run --scene " + big_offset + " -N 2" + kTiny + "--dry-run"),
                 {"o.json", "/ao/normal_offset", "[0, 1000]"}, "scene normal_offset");
  const std::string sweep = write_file(dir / "s.json", R"({"axes": {"views": 2, "d_max": 3e38}})");
  expect_refused(test::ldmbench("sweep " + sweep + " --dry-run"), {"s.json", "axes.d_max", "1e+30"}, "sweep d_max");
  // A top-level array printed an empty JSON path.
  const std::string array = write_file(dir / "array.json", "[1, 2]");
  expect_refused(test::ldmbench("run --scene " + array + " -N 2" + kTiny + "--dry-run"),
                 {"array.json: the top level must be a JSON object"}, "array");
  // An OBJ whose mtllib is missing fell back to grey without a word.
  const std::string mtl = write_file(dir / "mtl.obj", "mtllib missing.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  o = test::ldmbench("run --scene " + mtl + " -N 2" + kTiny + "--dry-run");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("warning: " + mtl + ":1: mtllib 'missing.mtl' cannot be read"), std::string::npos) << o.output;
  // ... and in the record's status_detail (the indirect light depends on the albedo).
  const fs::path out = dir / "mtl-out";
  o = test::ldmbench("run --scene " + mtl + " -N 2" + kTiny + "--out " + out.string());
  EXPECT_TRUE(o.status == 0 || o.status == 3) << o.output;  // one triangle: edge-on to the views
  EXPECT_NE(test::read_text((out / "records.csv").string()).find("mtllib 'missing.mtl' cannot be read"),
            std::string::npos);
}

}  // namespace
}  // namespace ldm::reliability
