// Extremes of scene input (issue 12): inputs at or past the edge of what a scene can hold get
// an error naming the file and the line or JSON key, never a silently altered scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/scene/generators.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::expect_contains;
using test::user_error;
using test::write_file;

// A scene file with one mesh `name` holding `obj`.
std::string scene_with_obj(const std::string& dir, const std::string& name, const std::string& obj,
                           const std::string& mesh_extra = "") {
  write_file(dir, name, obj);
  return write_file(dir, name + ".json",
                    R"({"meshes": [{"file": ")" + name + "\"" + mesh_extra + R"(}],
                        "camera": {"eye": [0.3, 0.3, 5], "target": [0.3, 0.3, 0]}})");
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ExtremesScene, CameraUpParallelToViewIsRejectedNamingCameraUp) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  // Eye straight above the target with up = +y: no roll is defined (Embree aborted on the
  // NaN rays; without a reference the image was all zeros, recorded ok).
  const std::string above = write_file(dir, "above.json", R"({"generator": {"type": "cornell"},
      "camera": {"eye": [2.78, 9, 2.8], "target": [2.78, 0, 2.8], "up": [0, 1, 0]}})");
  expect_contains(user_error([&] { load_scene(above); }), {"above.json", "/camera/up", "parallel"});
  const std::string below = write_file(dir, "below.json", R"({"generator": {"type": "cornell"},
      "camera": {"eye": [0, -4, 0], "target": [0, 0, 0], "up": [0, -2, 0]}})");
  expect_contains(user_error([&] { load_scene(below); }), {"below.json", "/camera/up"});
  // A scene built in code is checked too.
  Scene scene = generate_scene("plane", nullptr, "test");
  scene.camera.eye = {0, 5, 0};
  scene.camera.target = {0, 0, 0};
  scene.camera.up = {0, 1, 0};
  expect_contains(user_error([&] { scene.validate(); }), {"camera.up", "parallel"});
  // A tilted up vector is fine.
  scene.camera.up = {0, 1, 0.1f};
  EXPECT_NO_THROW(scene.validate());
}

TEST(ExtremesScene, ObjCoordinatesBeyondTheRepresentableExtentAreRejected) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  // ±1e38 is a finite float, but the scene's extent (2e38) squared is not.
  const std::string huge = scene_with_obj(dir, "huge.obj",
                                          "v -1e38 0 0\nv 1e38 0 0\nv 0 1e38 0\nf 1 2 3\n");
  expect_contains(user_error([&] { load_scene(huge); }), {"huge.obj:1", "scene extent"});
  // So is a coordinate that only becomes too large through the mesh's scale.
  const std::string scaled = scene_with_obj(dir, "scaled.obj", std::string(kTriangle) + "f 1 2 3\n",
                                            R"(, "scale": 1e30)");
  expect_contains(user_error([&] { load_scene(scaled); }), {"scaled.obj:2", "scale"});
}

TEST(ExtremesScene, MalformedObjLinesNameFileAndLine) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  struct Case {
    const char* name;
    std::string obj;
    std::initializer_list<std::string> expected;
  };
  const Case cases[] = {
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", {"nan.obj:2", "'nan'"}},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", {"inf.obj:3", "'inf'"}},
      {"letters.obj", "v a b c\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", {"letters.obj:1", "'a' is not a number"}},
      {"short.obj", "v 0 0 0\nv 1\nv 0 1 0\nf 1 2 3\n", {"short.obj:2", "3 coordinates", "got 1"}},
      {"twoindex.obj", std::string(kTriangle) + "f 1 2 3\nf 1 2\n", {"twoindex.obj:5", "at least 3"}},
      {"overflow.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", {"overflow.obj:2", "32-bit float"}},
      {"relative.obj", std::string(kTriangle) + "\n\nf -1 -2 -30\n",
       {"relative.obj:6", "-30", "counts back past the first of the 3 vertices"}},
      {"past.obj", std::string(kTriangle) + "f 1 2 7\n", {"past.obj:4", "vertex index 7", "3 vertices"}},
      {"zero.obj", std::string(kTriangle) + "f 0 1 2\n", {"zero.obj:4", "index 0"}},
      {"normal.obj", std::string(kTriangle) + "vn 0 0 1\nf 1//1 2//1 3//2\n", {"normal.obj:5", "normal index 2"}},
      {"vn.obj", std::string(kTriangle) + "vn 0 nan 1\nf 1 2 3\n", {"vn.obj:4", "'nan'"}},
      {"hexfloat.obj", "v 0x1p3 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", {"hexfloat.obj:1", "not a number"}},
  };
  for (const Case& c : cases) {
    const std::string scene = scene_with_obj(dir, c.name, c.obj);
    const std::string message = user_error([&] { load_scene(scene); });
    expect_contains(message, c.expected);
    expect_contains(message, {std::string(c.name) + ".json", "/meshes/0/file"});
  }
  // Forward references are legal OBJ, and a well-formed file still loads.
  const std::string good = scene_with_obj(dir, "good.obj", "f 1 2 3\n" + std::string(kTriangle) +
                                                               "vt 0 0\nvn 0 0 1\nf -3/1/1 -2/1/1 -1/1/1\n");
  EXPECT_EQ(load_scene(good).mesh.triangle_count(), 2u);
}

TEST(ExtremesScene, MessagesSayWhatIsReallyWrong) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  // A mesh path that is a directory.
  fs::create_directories(fs::path(dir) / "meshdir.obj");
  const std::string directory = write_file(dir, "dir.json", R"({"meshes": [{"file": "meshdir.obj"}]})");
  expect_contains(user_error([&] { load_scene(directory); }),
                  {"dir.json", "/meshes/0/file", "is a directory"});
  // scale 0 flattens the mesh: that is what the message says, not "no triangles".
  const std::string zero = scene_with_obj(dir, "flat.obj", std::string(kTriangle) + "f 1 2 3\n",
                                          R"(, "scale": [1, 0, 1])");
  expect_contains(user_error([&] { load_scene(zero); }), {"flat.obj.json", "/meshes/0/scale", "non-zero"});
  // Generator parameters: the file and the JSON path of the key.
  const std::string gen = write_file(dir, "gen.json", R"({"generator": {"type": "parallel-planes", "h": -1}})");
  expect_contains(user_error([&] { load_scene(gen); }), {"gen.json", "/generator/h", "outside"});
  const std::string typo = write_file(dir, "typo.json", R"({"generator": {"type": "atrium", "colums": 3}})");
  expect_contains(user_error([&] { load_scene(typo); }), {"typo.json", "/generator/colums", "unknown"});
  const std::string wrapped = write_file(dir, "wrap.json", R"({"generator": {"type": "atrium", "column_sides": 4294967299}})");
  expect_contains(user_error([&] { load_scene(wrapped); }), {"wrap.json", "/generator/column_sides", "outside"});
}

TEST(ExtremesScene, JsonNumbersBeyondFloatAreErrorsWithLine) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  // Beyond double: nlohmann reports out_of_range without a position; we give the line.
  const std::string beyond_double = write_file(
      dir, "e400.json", "{\n  \"generator\": {\"type\": \"cornell\"},\n  \"ao\": {\"d_max\": 1e400}\n}\n");
  expect_contains(user_error([&] { load_scene(beyond_double); }), {"e400.json", "line 3", "1e400"});
  // Beyond float: inf after the conversion.
  const std::string beyond_float = write_file(
      dir, "e39.json", R"({"generator": {"type": "cornell"}, "ao": {"d_max": 1e39}})");
  expect_contains(user_error([&] { load_scene(beyond_float); }), {"e39.json", "/ao/d_max", "32-bit float"});
  // Below float: 0 after the conversion, so not positive.
  const std::string tiny = write_file(
      dir, "tiny.json", R"({"generator": {"type": "cornell"}, "ao": {"d_max": 1e-50}})");
  expect_contains(user_error([&] { load_scene(tiny); }), {"tiny.json", "/ao/d_max", "positive"});
  const std::string eye = write_file(
      dir, "eye.json", R"({"generator": {"type": "cornell"}, "camera": {"eye": [0, 1e39, 0]}})");
  expect_contains(user_error([&] { load_scene(eye); }), {"eye.json", "/camera/eye/1", "32-bit float"});
}

}  // namespace
}  // namespace ldm
