#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

struct ObjLoadOptions {
  glm::vec3 scale{1.0f};
  glm::vec3 translate{0.0f};
  // Use this scene material for every face instead of the OBJ's own (usemtl / .mtl Kd).
  std::optional<std::string> override_material;
};

// Appends a Wavefront OBJ (triangulated) to the scene. Vertex normals are used when every
// face has them, otherwise face normals. Materials: the override, else the .mtl's Kd under the
// usemtl name, else a scene material of that name, else "default" (0.8 grey).
// `context` prefixes errors ("scene.json: /meshes/0/file").
void load_obj_into(Scene& scene, const std::string& path, const ObjLoadOptions& options,
                   const std::string& context);

}  // namespace ldm
