#pragma once
#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

struct CameraFrame {
  glm::vec3 eye, forward, right, up;  // right-handed: right = forward x up
  float tan_half_fov_y = 0, aspect = 1;
  // The primary ray direction through image pixel (x, y), y = 0 the top row (see Camera).
  glm::vec3 ray_direction(int x, int y, int width, int height) const;
};

CameraFrame camera_frame(const Camera& camera, int width, int height);
// Perspective view-projection whose near/far planes bracket the scene's bounding sphere.
glm::mat4 camera_view_projection(const Camera& camera, int width, int height,
                                 const BoundingSphere& bounds);

}  // namespace ldm
