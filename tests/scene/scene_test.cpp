// Scenes: the built-in generators, scene files and OBJ meshes, and the errors bad input gets.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/scene/generators.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

using test::write_file;

// Runs `f`, expects a UserError whose message contains every fragment.
template <typename F>
void expect_user_error(F f, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL() << "no error thrown";
  } catch (const UserError& e) {
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "message '" << e.what() << "' lacks '" << fragment << "'";
  }
}

TEST(Scene, CornellBoxHasWallsAndTwoBlocks) {
  const Scene scene = load_scene("cornell");
  EXPECT_EQ(scene.mesh.triangle_count(), 2u * (5 + 10));  // 5 walls, 2 blocks of 5 faces
  EXPECT_EQ(scene.materials.size(), 3u);
  const Bounds b = scene.bounds();
  EXPECT_NEAR(b.hi.y, 5.488f, 1e-4f);
  EXPECT_NEAR(b.hi.z, 5.592f, 1e-4f);
  EXPECT_NO_THROW(scene.validate());
  const Scene without = generate_scene("cornell", {{"blocks", false}}, "test");
  EXPECT_EQ(without.mesh.triangle_count(), 10u);
}

TEST(Scene, AtriumHasTwoStoreysAndCurtains) {
  const Scene scene = load_scene("atrium");
  EXPECT_GT(scene.mesh.triangle_count(), 5000u);
  bool has_curtain = false;
  for (auto m : scene.mesh.triangle_materials)
    has_curtain = has_curtain || scene.materials[m].name.rfind("cloth", 0) == 0;
  EXPECT_TRUE(has_curtain);
  const Bounds b = scene.bounds();
  EXPECT_GT(b.hi.y, 8.0f);  // two storeys of columns plus the gallery roof
}

TEST(Scene, ContentHashChangesWithAnyInput) {
  const Scene a = load_scene("cornell");
  Scene b = a;
  EXPECT_EQ(a.content_hash(), b.content_hash());
  b.ao.d_max *= 2;
  EXPECT_NE(a.content_hash(), b.content_hash());
  b = a;
  b.camera.fov_y_deg += 1;
  EXPECT_NE(a.content_hash(), b.content_hash());
  b = a;
  b.mesh.positions[3].x += 1e-3f;
  EXPECT_NE(a.content_hash(), b.content_hash());
}

TEST(Scene, GeneratorRejectsUnknownAndOutOfRangeParameters) {
  expect_user_error([] { generate_scene("atrium", {{"colum_spacing", 3.0}}, "t"); },
                    {"colum_spacing", "unknown"});
  expect_user_error([] { generate_scene("atrium", {{"column_spacing", -1.0}}, "t"); },
                    {"column_spacing", "outside"});
  expect_user_error([] { generate_scene("nope", nullptr, "t"); }, {"nope", "cornell"});
}

TEST(SceneFile, GeneratorWithOverrides) {
  const std::string dir = test::make_temp_dir("ldm-scene");
  const std::string path = write_file(dir, "box.json", R"({
    "name": "my-box",
    "generator": {"type": "cornell", "blocks": false},
    "camera": {"fov_y_deg": 50},
    "ao": {"d_max": 0.75, "attenuated": false}
  })");
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.name, "my-box");
  EXPECT_EQ(scene.mesh.triangle_count(), 10u);
  EXPECT_FLOAT_EQ(scene.camera.fov_y_deg, 50.0f);
  EXPECT_FLOAT_EQ(scene.ao.d_max, 0.75f);
  EXPECT_FALSE(scene.ao.attenuated);
  EXPECT_EQ(scene.origin, path);
}

TEST(SceneFile, ObjMeshesWithMaterials) {
  const std::string dir = test::make_temp_dir("ldm-scene");
  write_file(dir, "quad.mtl", "newmtl blue\nKd 0.1 0.2 0.9\n");
  write_file(dir, "quad.obj",
             "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
             "usemtl blue\nf 1//1 2//1 3//1 4//1\n");
  const std::string path = write_file(dir, "scene.json", R"({
    "meshes": [{"file": "quad.obj", "scale": 2, "translate": [0, 0, 1]},
               {"file": "quad.obj", "material": "grey"}],
    "materials": {"grey": [0.5, 0.5, 0.5]},
    "camera": {"eye": [0, 0, 5], "target": [0, 0, 0]}
  })");
  const Scene scene = load_scene(path);
  ASSERT_EQ(scene.mesh.triangle_count(), 4u);  // two quads, triangulated
  EXPECT_EQ(scene.materials[scene.mesh.triangle_materials[0]].name, "blue");
  EXPECT_FLOAT_EQ(scene.materials[scene.mesh.triangle_materials[0]].albedo.z, 0.9f);
  EXPECT_EQ(scene.materials[scene.mesh.triangle_materials[2]].name, "grey");
  // Rebased at load to the bounding-box centre (1, 1, 0.5), recorded as origin_offset.
  EXPECT_EQ(scene.origin_offset, glm::dvec3(1.0, 1.0, 0.5));
  EXPECT_FLOAT_EQ(scene.bounds().hi.x + float(scene.origin_offset.x), 2.0f);
  EXPECT_FLOAT_EQ(scene.bounds().hi.z + float(scene.origin_offset.z), 1.0f);
  EXPECT_FLOAT_EQ(scene.camera.eye.z, 4.5f);  // the file's (0, 0, 5), rebased
  EXPECT_FLOAT_EQ(scene.mesh.normals[0].z, 1.0f);
}

TEST(SceneFile, ErrorsNameTheFileAndLineOrKey) {
  const std::string dir = test::make_temp_dir("ldm-scene");
  expect_user_error([&] { load_scene((std::filesystem::path(dir) / "missing.json").string()); },
                    {"missing.json", "neither a built-in scene"});
  const std::string malformed = write_file(dir, "bad.json", "{\n  \"generator\": {\"type\": \"cornell\"},\n  \"camera\": {\"eye\": [0, 1,]}\n}\n");
  expect_user_error([&] { load_scene(malformed); }, {"bad.json", "malformed JSON", "line 3"});
  const std::string unknown = write_file(dir, "unknown.json", R"({"generator": {"type": "cornell"}, "camra": {}})");
  expect_user_error([&] { load_scene(unknown); }, {"unknown.json", "/camra", "not a known key"});
  const std::string wrong_type = write_file(dir, "type.json", R"({"generator": {"type": "cornell"}, "ao": {"d_max": "far"}})");
  expect_user_error([&] { load_scene(wrong_type); }, {"type.json", "/ao/d_max", "number"});
  const std::string negative = write_file(dir, "neg.json", R"({"generator": {"type": "cornell"}, "ao": {"d_max": -1}})");
  expect_user_error([&] { load_scene(negative); }, {"neg.json", "/ao/d_max", "positive"});
  const std::string no_mesh = write_file(dir, "nomesh.json", R"({"meshes": [{"file": "nothere.obj"}]})");
  expect_user_error([&] { load_scene(no_mesh); }, {"nomesh.json", "/meshes/0/file", "nothere.obj"});
  write_file(dir, "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  const std::string bad_obj = write_file(dir, "badobj.json", R"({"meshes": [{"file": "broken.obj"}]})");
  expect_user_error([&] { load_scene(bad_obj); }, {"broken.obj"});
  const std::string empty = write_file(dir, "empty.json", R"({"name": "x"})");
  expect_user_error([&] { load_scene(empty); }, {"empty.json", "generator"});
}

}  // namespace
}  // namespace ldm

namespace ldm {
namespace {

// The example scene files in scenes/ stay loadable as the format evolves.
TEST(SceneFile, ShippedExamplesLoad) {
  const std::filesystem::path dir = std::filesystem::path(LDM_TEST_SOURCE_DIR) / ".." / "scenes";
  int loaded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene(entry.path().string());
    EXPECT_GT(scene.mesh.triangle_count(), 0u) << entry.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 3);
  const Scene knot = load_scene((dir / "knot_in_box.json").string());
  EXPECT_EQ(knot.mesh.triangle_count(), 10u + 2u * 160u * 10u);  // box walls + the tube
}

}  // namespace
}  // namespace ldm
