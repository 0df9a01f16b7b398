#pragma once
// A mesh file as the importer read it, before any of ldmbench's checks: materials, meshes
// (vertices, optional normals, faces of any size) and the node tree that places meshes in
// the scene. It is what crosses from the isolated importer process (harness/scene/
// assimp_reader.h) to the process that checks and converts it (mesh_import.h), so it is a
// plain value with a byte encoding; the decoder trusts nothing of the bytes.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ldm {

struct ImportedMaterial {
  std::string name;
  bool has_albedo = false;  // the file gave a diffuse (or base) colour
  glm::vec3 albedo{0.8f};
};

struct ImportedMesh {
  std::string name;
  uint32_t material = 0;                // index into ImportedModel::materials
  std::vector<glm::vec3> positions;     // in the mesh's own frame
  std::vector<glm::vec3> normals;       // empty, or one per position (as the file says)
  std::vector<uint32_t> face_sizes;     // corners of each face (1 point, 2 line, 3 triangle)
  std::vector<uint32_t> indices;        // the faces' corners, concatenated
};

struct ImportedNode {
  std::string name;
  int32_t parent = -1;           // index of the parent node (< this node's), -1 for the root
  glm::mat4 transform{1.0f};     // to the parent's frame (column-major, glm's convention)
  std::vector<uint32_t> meshes;  // indices into ImportedModel::meshes placed by this node
};

struct ImportedModel {
  std::vector<ImportedMaterial> materials;
  std::vector<ImportedMesh> meshes;
  std::vector<ImportedNode> nodes;  // parents before children
};

std::string encode_imported_model(const ImportedModel& model);
// Throws std::runtime_error on bytes that are not a whole, consistent encoding (truncated,
// a count beyond the bytes left, trailing bytes). Index ranges are checked by the converter.
ImportedModel decode_imported_model(const std::string& bytes);

}  // namespace ldm
