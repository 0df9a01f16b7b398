#pragma once
// The viewer's camera: orbit (drag turns the eye around the target, the wheel zooms) or fly
// (drag turns the view, arrow keys and Page Up/Down move, the wheel sets the speed). Works on
// the scene's Camera, in world coordinates.
#include "harness/scene/scene.h"

namespace ldm::viewer {

class CameraControl {
 public:
  void reset(const Camera& camera, const BoundingSphere& bounds);
  const Camera& camera() const { return camera_; }
  void toggle_mode() { fly_ = !fly_; }
  bool is_fly() const { return fly_; }
  const char* mode_name() const { return fly_ ? "fly" : "orbit"; }

  // Each returns whether the camera moved.
  bool on_key(int glfw_key);
  void on_button(int glfw_button, bool pressed);
  bool on_cursor(double x, double y);
  bool on_scroll(double dy);

 private:
  void turn(float yaw, float pitch);
  Camera camera_;
  float scale_ = 1.0f;  // the scene's radius: steps are relative to it
  bool fly_ = false, dragging_ = false;
  double last_x_ = 0, last_y_ = 0;
  float speed_ = 0.05f;
};

}  // namespace ldm::viewer
