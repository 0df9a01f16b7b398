#pragma once
// The N orthographic LDM views (thesis §3.3.1): one per region of the hemisphere partition,
// each an R_LDM x R_LDM orthographic camera fitted to the scene's bounding sphere.
//
// A view looks along `forward` = -d (d the region's centre direction). Depth is the distance
// from the view's image plane along `forward`, in scene units, so depth 0 is the plane
// through `eye` and depth_range is the far plane. Pixel (i, j) covers the square whose centre
// is eye + right * half_extent * ndc_x + up * half_extent * ndc_y with
// ndc = ((i + 0.5) / R * 2 - 1, (j + 0.5) / R * 2 - 1) (GL's pixel centres).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"
#include "harness/scene/scene.h"

namespace ldm {

struct LdmView {
  glm::vec3 direction;  // partition centre d (unit, y > 0); the view answers queries along +-d
  glm::vec3 forward;    // = -direction
  glm::vec3 right, up;  // orthonormal, right x up = -forward (a right-handed view basis)
  glm::vec3 eye;        // centre of the image plane
  float half_extent = 1;  // half the side of the square image plane
  float depth_range = 2;  // far plane depth (the near plane is at depth 0)
  uint32_t resolution = 1;
  glm::mat4 view_projection{1.0f};  // world -> clip, orthographic

  float depth_of(glm::vec3 p) const { return glm::dot(p - eye, forward); }
  // World point on the image plane at the centre of pixel (i, j).
  glm::vec3 pixel_centre(uint32_t i, uint32_t j) const;
  float pixel_size() const { return 2.0f * half_extent / float(resolution); }
};

struct ViewSet {
  std::vector<LdmView> views;
  uint32_t resolution = 0;
  BoundingSphere bounds;
  uint32_t size() const { return uint32_t(views.size()); }
  uint64_t pixels_per_view() const { return uint64_t(resolution) * resolution; }
  uint64_t total_pixels() const { return pixels_per_view() * views.size(); }
};

// `margin` widens the fitted square and the depth range (relative to the radius) so that
// geometry on the bounding sphere is never clipped.
ViewSet make_view_set(const BoundingSphere& sphere, uint32_t count, uint32_t resolution,
                      float margin = 1e-3f);

// The views as the GLSL `LdmView` array of shaders/common/ldm_views.glsl (std430).
class GpuViewSet {
 public:
  explicit GpuViewSet(const ViewSet& views);
  void bind() const;  // to LDM_VIEWS_BINDING
  const ViewSet& views() const { return views_; }

 private:
  ViewSet views_;
  GlBuffer buffer_;
};

}  // namespace ldm
