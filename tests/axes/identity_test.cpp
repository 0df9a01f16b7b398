// Identity by construction: a configuration's resume identity covers every field of the
// scene it measures (Scene::identity_hash: the loaded scene and its source's bytes), so an
// edit anywhere in a scene file or its mesh can never resume a stale record; formatting does
// not count. Before issue 18 an edited ao.normal_offset resumed the old record.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "harness/scene/scene_loader.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A scene file setting every key the format has (scenes/README.md), with a mesh.
json full_scene() {
  return json::parse(R"({
    "name": "every-key",
    "generator": {"type": "cornell", "blocks": false, "scale": 0.01},
    "meshes": [{"file": "tri.obj", "material": "red", "scale": [1, 1, 1], "translate": [2.7, 1.0, 2.7]}],
    "materials": {"red": [0.8, 0.1, 0.1]},
    "camera": {"eye": [2.78, 2.73, -6.5], "target": [2.78, 2.2, 2.8], "up": [0, 1, 0], "fov_y_deg": 40},
    "light": {"position": [2.78, 5.4, 2.8], "direction": [0, -1, 0], "intensity": [8, 8, 8],
              "inner_angle_deg": 30, "outer_angle_deg": 45},
    "ao": {"attenuated": true, "d_max": 1.5, "falloff_exponent": 2, "normal_offset": 0.5}
  })");
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// Every leaf of `j` with its JSON pointer.
void leaves(const json& j, const std::string& pointer, std::vector<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) leaves(value, pointer + "/" + key, out);
  } else if (j.is_array() && !j.empty() && !j[0].is_number()) {
    for (size_t i = 0; i < j.size(); ++i) leaves(j[i], pointer + "/" + std::to_string(i), out);
  } else {
    out.push_back(pointer);
  }
}

// The leaf changed to another valid value of its kind.
json edited(json value, const std::string& pointer) {
  if (value.is_boolean()) return !value.get<bool>();
  if (value.is_number()) return value.get<double>() * 1.25 + 0.125;
  if (value.is_array()) {  // a vector: its first component moved
    value[0] = value[0].get<double>() * 1.25 + 0.125;
    return value;
  }
  if (pointer == "/meshes/0/material") return "green";
  if (pointer == "/meshes/0/file") return "tri2.obj";
  return value.get<std::string>() + "-x";
}

TEST(Identity, EveryKeyOfASceneFileAndEveryByteOfItsMeshChangeTheIdentity) {
  const fs::path dir = test::make_temp_dir("ldm-identity");
  write(dir / "tri.obj", kTriangle);
  write(dir / "tri2.obj", "v 0 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n");
  const fs::path file = dir / "scene.json";
  json base = full_scene();
  base["materials"]["green"] = {0.1, 0.8, 0.1};
  write(file, base.dump(2));
  const uint64_t identity = load_scene(file.string()).identity_hash();

  // Formatting and key order are not the scene: the same identity.
  write(file, base.dump());
  EXPECT_EQ(load_scene(file.string()).identity_hash(), identity);

  std::vector<std::string> pointers;
  leaves(base, "", pointers);
  ASSERT_GE(pointers.size(), 20u);
  size_t edits = 0;
  for (const std::string& pointer : pointers) {
    json changed = base;
    const json::json_pointer at(pointer);
    if (pointer == "/generator/type")  // another generator takes other parameters
      changed["generator"] = {{"type", "atrium"}};
    else
      changed[at] = edited(changed[at], pointer);
    write(file, changed.dump(2));
    uint64_t after = 0;
    try {
      after = load_scene(file.string()).identity_hash();
    } catch (const std::exception& e) {
      ADD_FAILURE() << pointer << ": the edit made the scene invalid: " << e.what();
      continue;
    }
    EXPECT_NE(after, identity) << "editing " << pointer << " left the identity unchanged";
    ++edits;
  }
  EXPECT_EQ(edits, pointers.size());
  // The mesh's bytes, even where the triangles stay the same (a comment).
  write(file, base.dump(2));
  write(dir / "tri.obj", std::string(kTriangle) + "# edited\n");
  EXPECT_NE(load_scene(file.string()).identity_hash(), identity);
}

TEST(Identity, ARunIntoTheSameFolderAfterASceneEditIsRefusedNotResumed) {
  const fs::path dir = test::make_temp_dir("ldm-identity");
  write(dir / "tri.obj", kTriangle);
  json scene = full_scene();
  const fs::path file = dir / "scene.json";
  write(file, scene.dump(2));
  const std::string run = "run --scene " + file.string() +
                          " -N 4 -R 16 --width 16 --height 16 --frames 1 --time-target 0 --warmup 0 --no-reference "
                          "--no-images --out " + (dir / "out").string();
  const test::Outcome first = test::ldmbench(run);
  ASSERT_EQ(first.status, 0) << first.output;
  // The same command and scene: resumed, nothing measured again.
  const test::Outcome again = test::ldmbench(run);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("already recorded"), std::string::npos) << again.output;
  // The normal offset edited (what resumed the stale record before issue 18): another sweep.
  scene["ao"]["normal_offset"] = 1.0;
  write(file, scene.dump(2));
  const test::Outcome edited_run = test::ldmbench(run);
  EXPECT_EQ(edited_run.status, 2) << edited_run.output;
  EXPECT_EQ(edited_run.output.find("already recorded"), std::string::npos) << edited_run.output;
  EXPECT_NE(edited_run.output.find("different sweep"), std::string::npos) << edited_run.output;
}

}  // namespace
}  // namespace ldm
