// libFuzzer target: any bytes as a scene file. The parser must either return a scene that
// passes Scene::validate() or throw UserError; anything else (another exception, a crash,
// undefined behaviour, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Mesh paths resolve against a folder that does not exist: the OBJ path is fuzzed apart.
    const ldm::Scene scene = ldm::parse_scene_file(text, "/nonexistent-fuzz-dir/scene.json");
    scene.validate();  // a scene that loads is a valid scene
  } catch (const ldm::UserError&) {
    // The expected answer to bad input.
  }
  return 0;
}
