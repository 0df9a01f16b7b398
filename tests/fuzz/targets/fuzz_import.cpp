// libFuzzer target: any bytes as a mesh file, through the importer's entry point
// (harness/scene/mesh_import.h: import_mesh_bytes_into). The first byte picks the format the
// rest is read as; Assimp reads it in a child process, so a crash or hang of Assimp is a
// refusal (UserError), not a finding; the conversion and its checks run here, under ASan and
// UBSan. A valid scene must load, anything else throw UserError naming the file.
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/scene/mesh_import.h"
#include "harness/scene/scene_defaults.h"
#include "harness/util/error.h"
#include "tests/fuzz/targets/import_formats.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string extension = ldm::fuzz_import_format(data[0]);
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  ldm::Scene scene;
  scene.name = "fuzz";
  scene.origin = "fuzz." + extension;
  try {
    // A short limit: a seed model imports in milliseconds; a mutant that makes Assimp loop
    // is stopped as a refusal.
    ldm::import_mesh_bytes_into(scene, bytes, extension, scene.origin, 5.0, "fuzz");
    ldm::derive_size_defaults(scene, {});
    scene.validate();
  } catch (const ldm::UserError&) {
  }
  return 0;
}
