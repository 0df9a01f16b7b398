#pragma once
// Mesh files into the scene: any format Assimp reads (glTF 2.0 / GLB, PLY, FBX, Collada,
// 3DS, STL, OFF, OBJ, IFC, ...). Assimp reads the file in a child process
// (harness/util/isolated_call.h), so that a file it crashes or hangs on is an error naming
// the file, never a crash of ldmbench; this process then checks what it read and converts
// it: node transforms applied (a mesh placed by several nodes appears once per node),
// per-material diffuse albedo, smooth normals where the file has them (through the node's
// normal matrix), else face normals.
//
// The checks (each a UserError naming the context, the file and, where the file names them,
// the mesh and the node): an index past the mesh's vertices, a material index past the
// file's materials, a non-finite coordinate or colour, a coordinate beyond
// kMaxSceneCoordinate after the node transforms and the scene file's scale and translate, a
// polygon Assimp did not triangulate, a node tree whose parents do not come first, and a
// file whose triangles are all of zero area (or that has none). Zero-area triangles, points
// and lines are skipped. OBJ files are read by the strict line checker (obj_syntax.h) first.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "harness/scene/imported_model.h"
#include "harness/scene/scene.h"

namespace ldm {

struct MeshImportOptions {
  // The scene file's placement, applied in double precision: a mesh moved 1e7 of its sizes
  // away keeps its detail, which 32-bit floats there cannot hold (issue 35).
  glm::dvec3 scale{1.0};
  glm::dvec3 translate{0.0};
  // Vertices are stored as 32-bit floats relative to this point (the scene loader passes
  // the translate, then rebases every mesh to the scene's centre: scene_loader.cpp).
  glm::dvec3 anchor{0.0};
  // If set, receives for every vertex appended the float spacing of its coordinate in the
  // mesh file (after the node transforms, times the scale): the precision the file itself
  // holds it to, which no placement can restore.
  std::vector<float>* file_spacing = nullptr;
  // Use this scene material for every triangle instead of the file's own.
  std::optional<std::string> override_material;
  // An OBJ's materials that its .mtl files define: a `usemtl` name outside it (an undefined
  // material, or a missing .mtl) gets the default grey, as a file without materials does,
  // rather than the albedo Assimp makes up for it. Unset: every material is the file's own.
  std::optional<std::set<std::string>> defined_materials;
};

// Appends the mesh file at `path` to the scene. `context` prefixes errors
// ("scene.json: /meshes/0/file", "--scene").
void import_mesh_into(Scene& scene, const std::string& path, const MeshImportOptions& options,
                      const std::string& context);

// Whether `path` names a mesh file (by its extension, which Assimp must read; not .json).
bool is_mesh_file(const std::string& path);

// The checked conversion alone (what import_mesh_into does after Assimp): appends `model`,
// read from `path`, to the scene. For the fuzzer and the tests.
void append_imported_model(Scene& scene, const ImportedModel& model, const std::string& path,
                           const MeshImportOptions& options, const std::string& context);

// import_mesh_into on the bytes of a file named `label` ending in `extension` ("ply"): the
// same checks, Assimp in a child process that may take `seconds`. The fuzzer's entry point
// (tests/fuzz/targets/fuzz_import.cpp), whose inputs are bytes; a file's relative
// references (an OBJ's .mtl, a glTF's .bin) are not followed.
void import_mesh_bytes_into(Scene& scene, const std::string& bytes, const std::string& extension,
                            const std::string& label, double seconds, const std::string& context);

}  // namespace ldm
