#pragma once
// The GL stage of the GTAO pass (harness/passes/gtao.h): the slice-wise horizon search and
// cosine-weighted integration of shaders/passes/gtao.frag, runnable on any G-buffer textures
// (positions xyz with w = 1 where covered, camera-facing normals), so that tests can feed it
// hand-made depth buffers. Its optional denoise is HBAO's cross-bilateral blur (HbaoBlur,
// harness/passes/hbao_kernel.h), timed by the pass as a sub-pass of its own.
#include <cstdint>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"
#include "harness/passes/fullscreen_ao_kernel.h"
#include "harness/scene/scene.h"

namespace ldm {

struct GtaoSettings {
  // The pass's defaults are its parameters' (harness/passes/gtao.cpp); these are the
  // kernel's, for tests that build it by hand.
  uint32_t slices = 4;         // slice planes through the view vector per pixel
  uint32_t steps = 8;          // samples per side of a slice
  float radius_scale = 1.0f;   // R = radius_scale * d_max
  float falloff = 0.0f;        // fraction of R over which an occluder's weight fades out
  float thickness = 0.0f;      // beta of the paper's thickness heuristic (0: height field)
  float step_power = 2.0f;     // sample distances R * u^power, u uniform over the steps
  bool jitter = false;         // per-pixel slice rotation and step offset (4x4 Bayer)
  bool normalized = true;      // divide by the open hemisphere's quadrature, not the slices
  uint32_t denoise_radius = 0; // pixels of the cross-bilateral blur; 0: none
  bool reference_weights = true;  // W = 1 - V(r); false: W = 1 within R (binary horizon)
};

// Where the G-buffer was seen from: the camera's frame (harness/scene/camera.h) and
// focal_pixels = (height / 2) / tan(fov_y / 2).
struct GtaoCamera {
  glm::vec3 eye{0.0f}, forward{0.0f, 0.0f, -1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
  float focal_pixels = 1.0f;
};

// A sample must rise this far (radians) above x's tangent plane to occlude: x's own plane,
// read at pixel centres a little off the slice's line, lies on it up to float rounding of the
// G-buffer's positions (relative 1e-7 of the coordinates, far below 1e-4 of any sample's
// distance), so nothing but the plane itself is lost.
inline constexpr float kGtaoTangentBias = 1e-4f;

// run(positions, normals) writes AO into target() (FullscreenAoKernel).
class GtaoKernel : public FullscreenAoKernel {
 public:
  // `ao` gives d_max, the visibility model and its falloff exponent (shaders/passes/gtao.frag).
  GtaoKernel(const GtaoSettings& gtao, const AoSettings& ao, int width, int height);
  void set_camera(const GtaoCamera& camera);
};

}  // namespace ldm
