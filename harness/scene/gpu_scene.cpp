#include "harness/scene/gpu_scene.h"

namespace ldm {

namespace {

// Vertex attribute `index` of `vao` read from `buffer`'s tightly packed vec3s (binding `index`).
void attach_vec3_attribute(const GlVertexArray& vao, GLuint index, const GlBuffer& buffer) {
  glVertexArrayVertexBuffer(vao.id(), index, buffer.id(), 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(vao.id(), index, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao.id(), index, index);
  glEnableVertexArrayAttrib(vao.id(), index);
}

}  // namespace

std::string AttributeSet::describe(uint64_t derived_normal_triangles, uint64_t triangles) const {
  std::string s = "position";
  if (normals) s += "+normal";
  if (normals && derived_normal_triangles > 0)
    s += derived_normal_triangles >= triangles
             ? std::string("(derived)")
             : "(derived for " + std::to_string(derived_normal_triangles) + " of " + std::to_string(triangles) +
                   " triangles)";
  if (materials) s += "+material";
  return s;
}

GpuScene::GpuScene(const Scene& scene, AttributeSet attributes)
    : attributes_(attributes),
      frame_origin_(scene.frame_origin),
      triangle_count_(scene.mesh.triangles.size()) {
  const auto& mesh = scene.mesh;
  positions_ = GlBuffer("scene_positions", mesh.positions.size() * sizeof(glm::vec3),
                        mesh.positions.data(), 0);
  indices_ = GlBuffer("scene_indices", mesh.triangles.size() * sizeof(glm::uvec3),
                      mesh.triangles.data(), 0);
  attach_vec3_attribute(vao_, 0, positions_);
  glVertexArrayElementBuffer(vao_.id(), indices_.id());
  if (attributes.normals) {
    normals_ = GlBuffer("scene_normals", mesh.normals.size() * sizeof(glm::vec3),
                        mesh.normals.data(), 0);
    attach_vec3_attribute(vao_, 1, normals_);
  }
  if (attributes.materials) {
    triangle_materials_ = GlBuffer("scene_triangle_materials",
                                   mesh.triangle_materials.size() * sizeof(uint32_t),
                                   mesh.triangle_materials.data(), 0);
    std::vector<glm::vec4> albedo;
    for (const auto& m : scene.materials) albedo.emplace_back(m.albedo, 1.0f);
    albedo_ = GlBuffer("scene_albedo", albedo.size() * sizeof(glm::vec4), albedo.data(), 0);
  }
  check_gl("uploading the scene");
}

void GpuScene::draw() const {
  glBindVertexArray(vao_.id());
  glDrawElements(GL_TRIANGLES, GLsizei(triangle_count_ * 3), GL_UNSIGNED_INT, nullptr);
}

void GpuScene::draw_instanced(uint32_t instances) const {
  glBindVertexArray(vao_.id());
  glDrawElementsInstanced(GL_TRIANGLES, GLsizei(triangle_count_ * 3), GL_UNSIGNED_INT, nullptr,
                          GLsizei(instances));
}

void GpuScene::bind_materials(uint32_t triangle_materials_binding, uint32_t albedo_binding) const {
  triangle_materials_.bind_storage(triangle_materials_binding);
  albedo_.bind_storage(albedo_binding);
}

std::vector<const GlBuffer*> GpuScene::buffers() const {
  std::vector<const GlBuffer*> out;
  for (const GlBuffer* b : {&positions_, &normals_, &indices_, &triangle_materials_, &albedo_})
    if (*b) out.push_back(b);
  return out;
}

uint64_t GpuScene::bytes() const {
  uint64_t total = 0;
  for (const GlBuffer* b : buffers()) total += b->bytes();
  return total;
}

}  // namespace ldm
