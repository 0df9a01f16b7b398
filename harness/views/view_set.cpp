#include "harness/views/view_set.h"

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "harness/views/sphere_partition.h"

namespace ldm {

glm::vec3 LdmView::pixel_centre(uint32_t i, uint32_t j) const {
  const float nx = (float(i) + 0.5f) / float(resolution) * 2.0f - 1.0f;
  const float ny = (float(j) + 0.5f) / float(resolution) * 2.0f - 1.0f;
  return eye + right * (half_extent * nx) + up * (half_extent * ny);
}

ViewSet make_view_set(const BoundingSphere& sphere, uint32_t count, uint32_t resolution,
                      float margin) {
  if (resolution == 0) throw UserError("R_LDM must be at least 1");
  const HemispherePartition partition(count);
  ViewSet set;
  set.resolution = resolution;
  set.bounds = sphere;
  const float radius = std::max(sphere.radius, 1e-6f) * (1.0f + margin);
  for (const glm::dvec3& centre : partition.centres()) {
    LdmView v;
    v.direction = glm::normalize(glm::vec3(centre));
    v.forward = -v.direction;
    // A fixed reference axis makes the basis deterministic; +z only for near-vertical views.
    const glm::vec3 reference = std::abs(v.forward.y) < 0.999f ? glm::vec3(0, 1, 0)
                                                               : glm::vec3(0, 0, 1);
    v.right = glm::normalize(glm::cross(v.forward, reference));
    v.up = glm::cross(v.right, v.forward);
    v.half_extent = radius;
    v.depth_range = 2.0f * radius;
    v.eye = sphere.centre - v.forward * radius;
    v.resolution = resolution;
    // clip = (dot(p - eye, right) / h, dot(p - eye, up) / h, 2 depth / range - 1, 1)
    glm::mat4 m(0.0f);
    const glm::vec3 rx = v.right / radius, uy = v.up / radius, fz = v.forward * (2.0f / v.depth_range);
    m[0] = glm::vec4(rx.x, uy.x, fz.x, 0.0f);
    m[1] = glm::vec4(rx.y, uy.y, fz.y, 0.0f);
    m[2] = glm::vec4(rx.z, uy.z, fz.z, 0.0f);
    m[3] = glm::vec4(-glm::dot(rx, v.eye), -glm::dot(uy, v.eye), -glm::dot(fz, v.eye) - 1.0f, 1.0f);
    v.view_projection = m;
    set.views.push_back(v);
  }
  return set;
}

namespace {
// Mirrors `struct LdmView` in shaders/common/ldm_views.glsl (std430: vec4-aligned members).
struct GpuView {
  glm::mat4 view_projection;
  glm::vec4 eye;      // xyz eye, w = pixel size
  glm::vec4 forward;  // xyz forward, w = depth range
  glm::vec4 right;    // xyz right, w = half extent
  glm::vec4 up;       // xyz up, w = half extent
  glm::uvec4 dims;    // x = y = resolution, z = first pixel index of this view, w = view index
};
static_assert(sizeof(GpuView) == 144);
}  // namespace

GpuViewSet::GpuViewSet(const ViewSet& views) : views_(views) {
  std::vector<GpuView> data;
  for (uint32_t i = 0; i < views.size(); ++i) {
    const LdmView& v = views.views[i];
    data.push_back({v.view_projection, glm::vec4(v.eye, v.pixel_size()),
                    glm::vec4(v.forward, v.depth_range), glm::vec4(v.right, v.half_extent),
                    glm::vec4(v.up, v.half_extent),
                    glm::uvec4(v.resolution, v.resolution,
                               uint32_t(uint64_t(i) * views.pixels_per_view()), i)});
  }
  buffer_ = GlBuffer("ldm_views", data.size() * sizeof(GpuView), data.data(), 0);
}

void GpuViewSet::bind() const { buffer_.bind_storage(kViewsBinding); }

}  // namespace ldm
