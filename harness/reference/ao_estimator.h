#pragma once
// The ambient-occlusion estimator of one pixel (thesis §4.1, Eq. 5/6, estimated with Eq. 9):
// the pixel-centre primary ray finds x and the camera-facing shading normal n exactly as the
// G-buffer pass does; AO(x) = (1/pi) ∫ V cos dω is the mean of V over cosine-weighted
// directions. No LDM normal offset: this is the ground truth the LDM passes are judged by.
#include <cstdint>

#include "harness/scene/camera.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/sobol_sampler.h"
#include "harness/reference/surface_point.h"
#include "harness/scene/scene.h"

namespace ldm {

class AoEstimator {
 public:
  // Throws UserError on bad AO settings (d_max <= 0, falloff_exponent < 0, not finite).
  AoEstimator(const EmbreeScene& scene, const AoSettings& ao, int width, int height);

  // The mean of `spp` visibility samples at pixel (x, y); 0 where the primary ray misses
  // (the GPU writes 0 for background).
  float pixel_mean(int x, int y, uint32_t spp, Pcg32& rng) const;
  // The same from points first .. first + spp - 1 of the pixel's scrambled Sobol sequence
  // (sobol_sampler.h) instead of independent random numbers.
  float pixel_mean(int x, int y, uint32_t first, uint32_t spp, const ScrambledSobol2D& points) const;

  // Secondary rays start at most this far from x along the camera-facing geometric normal:
  // kRayOffsetUlps float ulps of the largest coordinate of x's triangle (surface_point.h).
  float ray_offset() const { return ray_offset_; }

 private:
  // The sum of V over `count` directions; next_uv() gives each one's two uniform numbers.
  template <typename NextUv>
  double visibility_sum(const SurfacePoint& point, uint32_t count, NextUv next_uv) const;
  // V of `count` (at most one batch) rays from `origin`.
  void trace_visibility(glm::vec3 origin, const glm::vec3* directions, uint32_t count,
                        float* visibility) const;
  float attenuated_visibility(float hit_distance) const;

  const EmbreeScene& scene_;
  AoSettings ao_;
  int width_, height_;
  CameraFrame camera_;
  float ray_offset_;
};

}  // namespace ldm
