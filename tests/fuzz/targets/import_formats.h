#pragma once
// The formats fuzz_import feeds Assimp, chosen by an input's first byte; the corpus replay
// (tests/extremes/fuzz_corpus_test.cpp) decodes its inputs the same way.
#include <cstdint>
#include <string>

namespace ldm {

inline std::string fuzz_import_format(uint8_t selector) {
  static const char* const kFormats[] = {"obj", "ply", "stl", "off", "gltf", "glb", "dae", "fbx", "3ds"};
  return kFormats[selector % (sizeof kFormats / sizeof kFormats[0])];
}

}  // namespace ldm
