#pragma once
// Assimp (Debian's libassimp) reading a mesh file into an ImportedModel, as the file says,
// checking nothing: the checks are the converter's (mesh_import.h), which runs in the
// calling process while this runs in an isolated child (Assimp may crash on a malformed
// file). Polygons are triangulated (aiProcess_Triangulate); nothing else is changed: node
// transforms, normals and materials are passed on for the converter to apply.
#include <string>

#include "harness/scene/imported_model.h"

namespace ldm {

// Throws std::runtime_error with Assimp's message when it cannot read the file.
ImportedModel read_model_with_assimp(const std::string& path);
// The same from bytes in memory; `extension_hint` ("ply", "glb", ...) picks the importer
// where the bytes do not say (the fuzzer's entry point).
ImportedModel read_model_with_assimp(const std::string& bytes, const std::string& extension_hint);

// Whether Assimp has an importer for files ending in `extension` (".glb", case-insensitive).
bool assimp_reads_extension(const std::string& extension);
// Assimp's version, "5.2.5", for messages.
std::string assimp_version();

}  // namespace ldm
