// libFuzzer target: any bytes as an OBJ file, through the same path as a scene file's mesh
// (mesh_import.h: the strict line check, Assimp in a child process, the checked conversion).
// It must load a valid scene or throw UserError naming the file; anything else is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "harness/scene/mesh_import.h"
#include "harness/util/error.h"

namespace {

// One file per fuzzing process, rewritten for every input (the loader reads from a path).
const std::string& obj_path() {
  static const std::string path = "/tmp/ldm-fuzz-" + std::to_string(::getpid()) + ".obj";
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::FILE* file = std::fopen(obj_path().c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  ldm::Scene scene;
  scene.name = "fuzz";
  scene.origin = obj_path();
  try {
    ldm::import_mesh_into(scene, obj_path(), {}, "fuzz");
    scene.validate();
  } catch (const ldm::UserError&) {
  }
  return 0;
}
