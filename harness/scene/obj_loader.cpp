#include "harness/scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/scene/mesh_builder.h"
#include "harness/scene/obj_syntax.h"
#include "harness/util/error.h"

namespace ldm {

void load_obj_into(Scene& scene, const std::string& path, const ObjLoadOptions& options,
                   const std::string& context) {
  std::error_code error;
  const auto kind = std::filesystem::status(path, error).type();
  if (kind == std::filesystem::file_type::not_found)
    throw UserError(context + ": OBJ file '" + path + "' does not exist");
  if (kind == std::filesystem::file_type::directory)
    throw UserError(context + ": OBJ file '" + path + "' is a directory, not a file");
  if (kind != std::filesystem::file_type::regular)
    throw UserError(context + ": OBJ file '" + path + "' is not a regular file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw UserError(context + ": OBJ file '" + path + "' cannot be read");
  // tinyobjloader accepts malformed numbers and short statements silently: check them first.
  const ObjSyntax syntax = [&] {
    try {
      return check_obj_syntax(text.str(), path);
    } catch (const UserError& e) {
      throw UserError(context + ": " + e.what());
    }
  }();

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw UserError(context + ": cannot parse OBJ '" + path + "': " + reader.Error());
  const auto& attrib = reader.GetAttrib();
  const auto& shapes = reader.GetShapes();
  const auto& obj_materials = reader.GetMaterials();

  MeshBuilder builder(scene);
  auto scene_material = [&](int obj_material) -> uint32_t {
    if (options.override_material) {
      for (uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == *options.override_material) return i;
      throw UserError(context + ": material '" + *options.override_material +
                      "' is not defined in the scene's \"materials\"");
    }
    if (obj_material >= 0 && size_t(obj_material) < obj_materials.size()) {
      const auto& m = obj_materials[size_t(obj_material)];
      for (uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == m.name) return i;
      return builder.material(m.name, {m.diffuse[0], m.diffuse[1], m.diffuse[2]});
    }
    return builder.material("default", glm::vec3(0.8f));
  };

  const size_t vertex_count = attrib.vertices.size() / 3;
  const size_t normal_count = attrib.normals.size() / 3;
  if (vertex_count != syntax.vertex_lines.size())
    throw GpuError("OBJ '" + path + "': tinyobjloader read " + std::to_string(vertex_count) +
                   " vertices where the file has " + std::to_string(syntax.vertex_lines.size()));
  auto position = [&](int index) {
    // check_obj_syntax has checked every index against the file's vertex count.
    if (index < 0 || size_t(index) >= vertex_count)
      throw GpuError("OBJ '" + path + "': tinyobjloader returned vertex index " +
                     std::to_string(index) + " of " + std::to_string(vertex_count));
    const float* v = &attrib.vertices[3 * size_t(index)];
    const glm::vec3 p = glm::vec3(v[0], v[1], v[2]) * options.scale + options.translate;
    const float largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    if (!(largest <= kMaxSceneCoordinate))  // also catches inf and NaN
      throw UserError(path + ":" + std::to_string(syntax.vertex_lines[size_t(index)]) +
                      ": the vertex lies at (" + std::to_string(p.x) + ", " +
                      std::to_string(p.y) + ", " + std::to_string(p.z) + ") after " + context +
                      "'s scale and translate, beyond the representable scene extent (|x| <= 1e18)");
    return p;
  };
  const glm::vec3 normal_scale = 1.0f / options.scale;  // inverse-transpose of a scale
  size_t triangles = 0, degenerate = 0;
  for (const auto& shape : shapes) {
    const auto& mesh = shape.mesh;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      if (mesh.num_face_vertices[f] != 3) continue;  // triangulated; skips points/lines
      const tinyobj::index_t* idx = &mesh.indices[3 * f];
      const uint32_t material =
          scene_material(f < mesh.material_ids.size() ? mesh.material_ids[f] : -1);
      const glm::vec3 a = position(idx[0].vertex_index), b = position(idx[1].vertex_index),
                      c = position(idx[2].vertex_index);
      const bool has_normals = idx[0].normal_index >= 0 && idx[1].normal_index >= 0 &&
                               idx[2].normal_index >= 0 &&
                               size_t(std::max({idx[0].normal_index, idx[1].normal_index,
                                                idx[2].normal_index})) < normal_count;
      const glm::vec3 face = glm::cross(b - a, c - a);
      if (!(glm::length(face) > 0.0f)) {  // zero area: no surface to rasterise or hit
        ++degenerate;
        continue;
      }
      auto& m = scene.mesh;
      const auto base = uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), {a, b, c});
      for (int k = 0; k < 3; ++k) {
        glm::vec3 n = glm::normalize(face);
        if (has_normals) {
          const float* v = &attrib.normals[3 * size_t(idx[k].normal_index)];
          const glm::vec3 vn = glm::vec3(v[0], v[1], v[2]) * normal_scale;
          if (glm::length(vn) > 0.0f) n = glm::normalize(vn);
        }
        m.normals.push_back(n);
      }
      m.triangles.emplace_back(base, base + 1, base + 2);
      m.triangle_materials.push_back(material);
      ++triangles;
    }
  }
  if (triangles == 0 && degenerate > 0)
    throw UserError(context + ": OBJ '" + path + "': all " + std::to_string(degenerate) +
                    " triangles have zero area (after the mesh's scale)");
  if (triangles == 0)
    throw UserError(context + ": OBJ '" + path + "' has no faces (" +
                    std::to_string(syntax.face_count) + " f statements)");
}

}  // namespace ldm
