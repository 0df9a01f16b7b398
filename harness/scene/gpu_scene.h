#pragma once
// The scene's geometry on the GPU. Only the attributes that the enabled passes read are
// uploaded (model only what the scene requires): LDM construction needs positions alone,
// the G-buffer adds normals, lighting passes add per-triangle materials.
#include <cstdint>
#include <string>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/scene/scene.h"

namespace ldm {

struct AttributeSet {
  bool normals = false;    // vertex attribute 1
  bool materials = false;  // per-triangle material index + albedo table (storage buffers)
  AttributeSet& operator|=(const AttributeSet& o) {
    normals = normals || o.normals;
    materials = materials || o.materials;
    return *this;
  }
  // "position", "position+normal", ...; normals the importer derived from faces are said so:
  // "+normal(derived)" when every triangle's were, "+normal(derived for D of T triangles)"
  // when some were (Scene::derived_normal_triangles).
  std::string describe(uint64_t derived_normal_triangles = 0, uint64_t triangles = 0) const;
};

class GpuScene {
 public:
  GpuScene(const Scene& scene, AttributeSet attributes);
  // Draws every triangle with the bound program (positions at location 0, normals at 1).
  void draw() const;
  // Draws every triangle `instances` times in one call (gl_InstanceID 0 .. instances - 1).
  void draw_instanced(uint32_t instances) const;
  const AttributeSet& attributes() const { return attributes_; }
  // Binds the per-triangle material indices and the albedo table (vec4 per material) as
  // storage buffers; needs materials uploaded.
  void bind_materials(uint32_t triangle_materials_binding, uint32_t albedo_binding) const;
  // The frame the positions were uploaded in (Scene::frame_origin): a pass that draws this
  // geometry with a camera must take the camera from a scene in the same frame.
  glm::vec3 frame_origin() const { return frame_origin_; }
  uint64_t triangle_count() const { return triangle_count_; }
  uint64_t bytes() const;  // all geometry buffers
  std::vector<const GlBuffer*> buffers() const;

 private:
  AttributeSet attributes_;
  glm::vec3 frame_origin_{0.0f};
  uint64_t triangle_count_ = 0;
  GlVertexArray vao_;
  GlBuffer positions_, normals_, indices_, triangle_materials_, albedo_;
};

}  // namespace ldm
