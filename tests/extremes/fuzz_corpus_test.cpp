// The fuzzers' seed corpus and every crash input they ever found (tests/fuzz/), replayed
// through the same parsers in the ordinary build: each input loads a valid scene or is
// refused with UserError. A crash input added to tests/fuzz/crashes/ stays a test forever.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/scene/mesh_import.h"
#include "harness/scene/scene_defaults.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/fuzz_inputs.h"
#include "tests/fuzz/targets/import_formats.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(FuzzCorpus, SceneJsonInputsLoadOrAreRefused) {
  const test::FuzzReplay replay = test::replay_fuzz_inputs("scene_json", [](const fs::path&, const std::string& bytes) {
    parse_scene_file(bytes, "/nonexistent-fuzz-dir/scene.json").validate();
  });
  EXPECT_GE(replay.inputs, 3u);
}

TEST(FuzzCorpus, ObjInputsLoadOrAreRefused) {
  const test::FuzzReplay replay = test::replay_fuzz_inputs("obj", [](const fs::path& file, const std::string&) {
    Scene scene;
    scene.name = "fuzz";
    scene.origin = file.string();
    import_mesh_into(scene, file.string(), {}, "fuzz");
    scene.validate();
  });
  EXPECT_GE(replay.inputs, 3u);
}

// Mesh files (tests/fuzz/targets/fuzz_import.cpp): the first byte picks the format. Every seed
// is a real model (assimp-testmodels) and must load; the mutants the fuzzer kept must load
// or be refused, never crash ldmbench (Assimp runs in a child process).
TEST(FuzzCorpus, ImportInputsLoadOrAreRefused) {
  size_t loaded = 0;
  const auto import = [&](const fs::path& file, const std::string& bytes) {
    if (bytes.empty()) return;
    Scene scene;
    scene.name = "fuzz";
    scene.origin = file.string();
    // The fuzzer's limit: one input (assimp-hangs.ply) makes Assimp loop.
    import_mesh_bytes_into(scene, bytes.substr(1), fuzz_import_format(uint8_t(bytes[0])), file.filename().string(), 5.0,
                           "fuzz");
    derive_size_defaults(scene, {});
    scene.validate();
    ++loaded;
  };
  const test::FuzzReplay replay = test::replay_fuzz_inputs("import", import);
  EXPECT_GE(replay.inputs, 9u);
  // The seeds are valid models (BoxWithInfinites is refused for its infinite coordinates).
  EXPECT_GE(loaded, 9u);
}

}  // namespace
}  // namespace ldm
