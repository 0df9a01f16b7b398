#pragma once
// The per-pixel estimators of the lighting references (lighting_reference.h says what each
// component is). Scene-centred coordinates, the AO reference's G-buffer points and ray
// offsets (surface_point.h).
#include <cstdint>

#include <glm/glm.hpp>

#include "harness/reference/embree_scene.h"
#include "harness/reference/hemisphere.h"
#include "harness/reference/lighting_reference.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/surface_point.h"
#include "harness/scene/camera.h"

namespace ldm {

class LightingEstimator {
 public:
  // Throws UserError on an albedo outside [0, 1] or not finite (naming the material): the
  // multi-bounce sum of a brighter-than-white closed scene diverges.
  LightingEstimator(const EmbreeScene& scene, LightingComponent component, int width,
                    int height, const RussianRoulette& roulette = {});

  // The mean of `spp` samples of pixel (x, y)'s outgoing radiance toward the eye (RGB);
  // 0 where the primary ray misses. `direct` draws nothing from `rng` and ignores `spp`.
  glm::vec3 pixel_mean(int x, int y, uint32_t spp, Pcg32& rng) const;

  // Radiance reflected from `point` toward its viewer by the spot light alone:
  // albedo/π · I(ω_l) · max(0, n·ω_l) / r² · V.
  glm::vec3 direct_radiance(const SurfacePoint& point) const;

 private:
  glm::vec3 albedo(const SurfacePoint& point) const;
  // The surface seen from `from` along a cosine-weighted direction about its shading normal
  // (nothing when it points below the triangle's plane or escapes).
  std::optional<SurfacePoint> next_surface(const SurfacePoint& from, Pcg32& rng) const;
  // Light reflected once on its way to x, by both strategies combined with the balance
  // heuristic (lighting_estimator.cpp).
  glm::vec3 single_bounce_sample(const SurfacePoint& x, Pcg32& rng) const;
  // The density, in solid angle at x, with which the light-side strategy picks the
  // direction from x to y (0 where it cannot).
  float light_strategy_pdf(const SurfacePoint& x, const SurfacePoint& y) const;
  // A surface point the light reaches, by a direction uniform in the outer cone.
  std::optional<RayHit> light_sample(Pcg32& rng) const;
  glm::vec3 multi_bounce_sample(const SurfacePoint& x, Pcg32& rng) const;

  const EmbreeScene& scene_;
  LightingComponent component_;
  int width_, height_;
  CameraFrame camera_;
  RussianRoulette roulette_;
  SpotLight light_;
  NormalFrame light_frame_;
  float outer_cos_;            // cos(outer angle): light samples have cos >= this
  float outer_solid_angle_;    // of the cone light samples are drawn from
};

}  // namespace ldm
