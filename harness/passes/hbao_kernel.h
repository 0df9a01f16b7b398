#pragma once
// The two GL stages of the HBAO pass (harness/passes/hbao.h), each runnable on any G-buffer
// textures (positions xyz with w = 1 where covered, camera-facing normals), so that tests can
// feed them hand-made depth buffers:
//  - HbaoKernel: the horizon search (shaders/passes/hbao.frag) into an R32F AO target;
//  - HbaoBlur: the optional cross-bilateral blur (shaders/passes/hbao_blur.frag), separable,
//    horizontal into a scratch target then vertical back into the AO target, each tap
//    weighted by a Gaussian in pixels and by how far the tap's point lies off x's tangent
//    plane, in units of x's pixel footprint, so that AO does not bleed across depth edges.
#include <array>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"
#include "harness/measure/work_counters.h"
#include "harness/passes/fullscreen_ao_kernel.h"
#include "harness/scene/scene.h"

namespace ldm {

struct HbaoSettings {
  uint32_t directions = 8, steps = 8;
  float angle_bias = 0.1f;
  bool jitter = false;
  uint32_t blur_radius = 0;  // pixels; 0: no blur
};

// Where the G-buffer was seen from: focal_pixels = (height / 2) / tan(fov_y / 2).
struct HbaoCamera {
  glm::vec3 eye{0.0f}, forward{0.0f, 0.0f, -1.0f};
  float focal_pixels = 1.0f;
};

// run(positions, normals) writes AO into target() (FullscreenAoKernel).
class HbaoKernel : public FullscreenAoKernel {
 public:
  // `ao` gives the radius R = d_max and the falloff: attenuated W = 1 - min(r/R, 1)^e (the
  // LDM AO's 1 - V), unattenuated W = 1 within R.
  HbaoKernel(const HbaoSettings& hbao, const AoSettings& ao, int width, int height);
  void set_camera(const HbaoCamera& camera);

 private:
  // The tiled random table: per entry a rotation (radians) and a step offset in (0, 1].
  std::array<glm::vec2, 16> jitter_table(const HbaoSettings& hbao) const;
};

// What hbao_blur.frag counts in the counting replay under `subpass` (HBAO's "blur", GTAO's
// "denoise"): fragments shaded (two directions: twice the image's pixels) and taps weighed.
std::vector<WorkCounter> hbao_blur_work_counters(const std::string& subpass);

// What a horizon search counts besides what every one counts alike (fragments, covered
// pixels, horizon rises): HBAO's directions or GTAO's slices (`searched`, its own unit),
// the samples read and the steps per covered pixel, each described after "<name>: ".
struct HorizonSearchCounters {
  std::string searched, searched_what, samples_what, steps_what;
};
// The work_counters() of a screen-space AO pass: the G-buffer's, the horizon search's under
// `name` ("hbao", "gtao"), then the smoothing's under `smoothing` ("blur", "denoise").
std::vector<WorkCounter> horizon_search_work_counters(const std::string& name,
                                                      const std::string& smoothing,
                                                      const HorizonSearchCounters& own);

class HbaoBlur {
 public:
  // Blurs `ao` (R32F; it must outlive the blur) in place, through a scratch target.
  HbaoBlur(uint32_t radius, const GlTexture2D& ao);
  void set_camera(const HbaoCamera& camera);
  void run(const GlTexture2D& positions, const GlTexture2D& normals) const;
  const GlTexture2D& scratch() const { return scratch_; }

 private:
  void run_direction(const GlTexture2D& source, const GlFramebuffer& target, int dx, int dy,
                     const GlTexture2D& positions, const GlTexture2D& normals) const;
  const GlTexture2D& ao_;
  int width_, height_;
  GlTexture2D scratch_;
  GlFramebuffer scratch_framebuffer_, ao_framebuffer_;
  GlVertexArray empty_vao_;
  GlProgram program_;
};

}  // namespace ldm
