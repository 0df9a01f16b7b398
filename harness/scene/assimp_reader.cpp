#include "harness/scene/assimp_reader.h"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <utility>

namespace ldm {
namespace {

// Triangulation only: Assimp must not invent normals (the converter uses face normals where
// the file has none, as the file says), drop degenerates or merge vertices behind our back.
constexpr unsigned kImportFlags = aiProcess_Triangulate;

// Stops a node tree that never ends (a cyclic graph from a broken importer) before memory
// does; real scenes have thousands of nodes.
constexpr size_t kMaxNodes = size_t(1) << 24;

ImportedMaterial read_material(const aiMaterial& material) {
  ImportedMaterial m;
  aiString name;
  if (material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
  // glTF and PBR materials carry the albedo as the base colour, the others as diffuse.
  aiColor4D colour;
  if (material.Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS ||
      material.Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS) {
    m.has_albedo = true;
    m.albedo = glm::vec3(colour.r, colour.g, colour.b);
  }
  return m;
}

ImportedMesh read_mesh(const aiMesh& mesh) {
  ImportedMesh m;
  m.name = mesh.mName.C_Str();
  m.material = mesh.mMaterialIndex;
  if (mesh.mVertices) {
    m.positions.resize(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i)
      m.positions[i] = glm::vec3(mesh.mVertices[i].x, mesh.mVertices[i].y, mesh.mVertices[i].z);
  }
  if (mesh.mNormals) {
    m.normals.resize(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i)
      m.normals[i] = glm::vec3(mesh.mNormals[i].x, mesh.mNormals[i].y, mesh.mNormals[i].z);
  }
  if (mesh.mFaces) {
    m.face_sizes.reserve(mesh.mNumFaces);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      const unsigned corners = face.mIndices ? face.mNumIndices : 0;
      m.face_sizes.push_back(corners);
      m.indices.insert(m.indices.end(), face.mIndices, face.mIndices + corners);
    }
  }
  return m;
}

glm::mat4 to_glm(const aiMatrix4x4& a) {
  // aiMatrix4x4 is row-major (a.a4 the x translation); glm is column-major.
  return glm::mat4(a.a1, a.b1, a.c1, a.d1, a.a2, a.b2, a.c2, a.d2, a.a3, a.b3, a.c3, a.d3, a.a4,
                   a.b4, a.c4, a.d4);
}

ImportedModel convert(const aiScene& scene) {
  ImportedModel model;
  for (unsigned i = 0; i < scene.mNumMaterials; ++i)
    if (scene.mMaterials && scene.mMaterials[i]) model.materials.push_back(read_material(*scene.mMaterials[i]));
    else model.materials.push_back({});
  for (unsigned i = 0; i < scene.mNumMeshes; ++i)
    if (scene.mMeshes && scene.mMeshes[i]) model.meshes.push_back(read_mesh(*scene.mMeshes[i]));
    else model.meshes.push_back({});
  // Parents before children, without recursion (a deep tree must not overflow the stack).
  std::vector<std::pair<const aiNode*, int32_t>> pending;
  if (scene.mRootNode) pending.emplace_back(scene.mRootNode, -1);
  while (!pending.empty()) {
    if (model.nodes.size() >= kMaxNodes)
      throw std::runtime_error("the node tree has more than " + std::to_string(kMaxNodes) + " nodes");
    const auto [node, parent] = pending.back();
    pending.pop_back();
    ImportedNode n;
    n.name = node->mName.C_Str();
    n.parent = parent;
    n.transform = to_glm(node->mTransformation);
    if (node->mMeshes) n.meshes.assign(node->mMeshes, node->mMeshes + node->mNumMeshes);
    const auto index = int32_t(model.nodes.size());
    model.nodes.push_back(std::move(n));
    if (node->mChildren)
      for (unsigned c = node->mNumChildren; c-- > 0;)
        if (node->mChildren[c]) pending.emplace_back(node->mChildren[c], index);
  }
  return model;
}

std::string assimp_error(const Assimp::Importer& importer) {
  const std::string error = importer.GetErrorString();
  return error.empty() ? std::string("Assimp read no scene") : error;
}

}  // namespace

ImportedModel read_model_with_assimp(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, kImportFlags);
  if (!scene) throw std::runtime_error(assimp_error(importer));
  return convert(*scene);
}

ImportedModel read_model_with_assimp(const std::string& bytes, const std::string& extension_hint) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(), kImportFlags, extension_hint.c_str());
  if (!scene) throw std::runtime_error(assimp_error(importer));
  return convert(*scene);
}

bool assimp_reads_extension(const std::string& extension) {
  std::string lower = extension;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.empty() || lower == ".") return false;
  Assimp::Importer importer;
  return importer.IsExtensionSupported(lower[0] == '.' ? lower : "." + lower);
}

std::string assimp_version() {
  return std::to_string(aiGetVersionMajor()) + "." + std::to_string(aiGetVersionMinor()) + "." +
         std::to_string(aiGetVersionPatch());
}

}  // namespace ldm
