#include "harness/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace ldm {

CameraFrame camera_frame(const Camera& camera, int width, int height) {
  CameraFrame f;
  f.eye = camera.eye;
  f.forward = glm::normalize(camera.target - camera.eye);
  f.right = glm::normalize(glm::cross(f.forward, camera.up));
  f.up = glm::cross(f.right, f.forward);
  f.tan_half_fov_y = std::tan(glm::radians(camera.fov_y_deg) * 0.5f);
  f.aspect = float(width) / float(height);
  return f;
}

glm::vec3 CameraFrame::ray_direction(int x, int y, int width, int height) const {
  const float nx = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
  const float ny = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;
  return glm::normalize(forward + right * (nx * tan_half_fov_y * aspect) +
                        up * (ny * tan_half_fov_y));
}

glm::mat4 camera_view_projection(const Camera& camera, int width, int height,
                                 const BoundingSphere& bounds) {
  const float distance = glm::length(bounds.centre - camera.eye);
  const float far_plane = distance + bounds.radius * 1.01f;
  const float near_plane = std::max(far_plane * 1e-4f, distance - bounds.radius * 1.01f);
  const glm::mat4 view = glm::lookAt(camera.eye, camera.target, camera.up);
  const glm::mat4 projection = glm::perspective(glm::radians(camera.fov_y_deg),
                                                float(width) / float(height), near_plane, far_plane);
  return projection * view;
}

}  // namespace ldm
