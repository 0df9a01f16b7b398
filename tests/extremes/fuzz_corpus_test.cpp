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
#include "tests/fuzz/targets/import_formats.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputs(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path root = fs::path(LDM_TEST_SOURCE_DIR) / "fuzz";
  for (const char* kind : {"corpus", "crashes"}) {
    const fs::path dir = root / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().filename().string().front() != '.')
        files.push_back(entry.path());
  }
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FuzzCorpus, SceneJsonInputsLoadOrAreRefused) {
  const auto files = inputs("scene_json");
  EXPECT_GE(files.size(), 3u);
  for (const auto& file : files) {
    try {
      parse_scene_file(read_bytes(file), "/nonexistent-fuzz-dir/scene.json").validate();
    } catch (const UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
}

TEST(FuzzCorpus, ObjInputsLoadOrAreRefused) {
  const auto files = inputs("obj");
  EXPECT_GE(files.size(), 3u);
  for (const auto& file : files) {
    Scene scene;
    scene.name = "fuzz";
    scene.origin = file.string();
    try {
      import_mesh_into(scene, file.string(), {}, "fuzz");
      scene.validate();
    } catch (const UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
}

// Mesh files (tests/fuzz/targets/fuzz_import.cpp): the first byte picks the format. Every seed
// is a real model (assimp-testmodels) and must load; the mutants the fuzzer kept must load
// or be refused, never crash ldmbench (Assimp runs in a child process).
TEST(FuzzCorpus, ImportInputsLoadOrAreRefused) {
  const auto files = inputs("import");
  EXPECT_GE(files.size(), 9u);
  size_t loaded = 0;
  for (const auto& file : files) {
    const std::string bytes = read_bytes(file);
    if (bytes.empty()) continue;
    const std::string extension = fuzz_import_format(uint8_t(bytes[0]));
    Scene scene;
    scene.name = "fuzz";
    scene.origin = file.string();
    try {
      // The fuzzer's limit: one input (assimp-hangs.ply) makes Assimp loop.
      import_mesh_bytes_into(scene, bytes.substr(1), extension, file.filename().string(), 5.0, "fuzz");
      derive_size_defaults(scene, {});
      scene.validate();
      ++loaded;
    } catch (const UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
  // The seeds are valid models (BoxWithInfinites is refused for its infinite coordinates).
  EXPECT_GE(loaded, 9u);
}

}  // namespace
}  // namespace ldm
