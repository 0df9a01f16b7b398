#include "harness/viewer/camera_control.h"

#include <algorithm>
#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

namespace ldm::viewer {

void CameraControl::reset(const Camera& camera, const BoundingSphere& bounds) {
  camera_ = camera;
  scale_ = std::max(bounds.radius, 1e-6f);
}

// Yaw about the camera's up, pitch about its right axis; orbit turns the eye around the
// target, fly turns the target around the eye. The pitch stops short of the up axis, where
// the camera's roll would be undefined (camera_up_is_usable).
void CameraControl::turn(float yaw, float pitch) {
  const glm::vec3 pivot = fly_ ? camera_.eye : camera_.target;
  glm::vec3 arm = (fly_ ? camera_.target : camera_.eye) - pivot;
  const glm::vec3 up = glm::normalize(camera_.up);
  arm = glm::vec3(glm::rotate(glm::mat4(1.0f), yaw, up) * glm::vec4(arm, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(arm, up));
  const glm::vec3 pitched = glm::vec3(glm::rotate(glm::mat4(1.0f), pitch, right) * glm::vec4(arm, 0.0f));
  const float cosine = glm::dot(glm::normalize(pitched), up);
  if (std::abs(cosine) < 0.995f) arm = pitched;
  (fly_ ? camera_.target : camera_.eye) = pivot + arm;
}

bool CameraControl::on_key(int key) {
  if (!fly_) return false;
  const glm::vec3 forward = glm::normalize(camera_.target - camera_.eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera_.up));
  const float step = speed_ * scale_;
  glm::vec3 move(0.0f);
  switch (key) {
    case GLFW_KEY_UP: move = forward * step; break;
    case GLFW_KEY_DOWN: move = -forward * step; break;
    case GLFW_KEY_RIGHT: move = right * step; break;
    case GLFW_KEY_LEFT: move = -right * step; break;
    case GLFW_KEY_PAGE_UP: move = glm::normalize(camera_.up) * step; break;
    case GLFW_KEY_PAGE_DOWN: move = -glm::normalize(camera_.up) * step; break;
    default: return false;
  }
  camera_.eye += move;
  camera_.target += move;
  return true;
}

void CameraControl::on_button(int button, bool pressed) {
  if (button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_RIGHT) dragging_ = pressed;
}

bool CameraControl::on_cursor(double x, double y) {
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x;
  last_y_ = y;
  if (!dragging_ || (dx == 0 && dy == 0)) return false;
  const float radians_per_pixel = 0.005f;
  turn(float(-dx) * radians_per_pixel, float(-dy) * radians_per_pixel * (fly_ ? -1.0f : 1.0f));
  return true;
}

bool CameraControl::on_scroll(double dy) {
  if (dy == 0) return false;
  if (fly_) {
    speed_ = std::clamp(speed_ * float(std::pow(1.25, dy)), 1e-4f, 1.0f);
    return false;
  }
  const glm::vec3 arm = camera_.eye - camera_.target;
  const float factor = float(std::pow(0.9, dy));
  const float length = glm::length(arm) * factor;
  if (length < 1e-3f * scale_ || length > 1e3f * scale_) return false;
  camera_.eye = camera_.target + arm * factor;
  return true;
}

}  // namespace ldm::viewer
