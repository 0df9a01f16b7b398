#include "harness/scene/scene_defaults.h"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace ldm {
namespace {


std::string format(const char* pattern, double value) {
  char text[96];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace

void set_setting_sources(Scene& scene, const std::string& source) {
  scene.sources = {source, source, source};
}

void derive_size_defaults(Scene& scene, const GivenSettings& given) {
  const BoundingSphere sphere = scene.bounding_sphere();
  const glm::vec3 c = sphere.centre;
  // A point (or empty) scene has no size: any positive radius frames it.
  const float r = sphere.radius > 0.0f ? sphere.radius : 1.0f;
  const std::string radius = format("bounding sphere radius %.6g", double(r));
  if (!given.camera) {
    Camera& camera = scene.camera;
    camera.fov_y_deg = kDerivedFovYDeg;
    const float distance = kDerivedFramingMargin * r / std::sin(0.5f * kDerivedFovYDeg * std::numbers::pi_v<float> / 180.0f);
    camera.target = c;
    camera.eye = c + glm::normalize(kCameraDirection) * distance;
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.sources.camera = "derived (frames the " + radius + ")";
  }
  if (!given.light) {
    SpotLight& light = scene.light;
    light.position = c + kLightOffset * r;
    const glm::vec3 to_centre = c - light.position;
    const float distance = glm::length(to_centre);
    light.direction = to_centre / distance;
    // The sphere seen from the light subtends asin(R / d); 5 degrees more reach its rim.
    light.outer_angle_deg = std::asin(r / distance) * 180.0f / std::numbers::pi_v<float> + 5.0f;
    light.inner_angle_deg = 0.75f * light.outer_angle_deg;
    light.intensity = glm::vec3(distance * distance);  // E = I / d^2 = 1 W/m^2 at C
    scene.sources.light = "derived (a spot above the " + radius + ", 1 W/m^2 at its centre)";
  }
  if (!given.d_max) {
    scene.ao.d_max = kDerivedDMaxFraction * r;
    scene.sources.d_max = format("derived (%g x ", double(kDerivedDMaxFraction)) + radius + ")";
  }
}

}  // namespace ldm
