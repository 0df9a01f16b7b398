#include "harness/scene/spot_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ldm {
namespace {

float cos_deg(float degrees) { return std::cos(glm::radians(degrees)); }

}  // namespace

float spot_falloff(const SpotLight& light, float cos_angle) {
  const float c_in = cos_deg(light.inner_angle_deg), c_out = cos_deg(light.outer_angle_deg);
  if (!(c_in > c_out)) return cos_angle >= c_in ? 1.0f : 0.0f;  // hard-edged cone
  const float t = std::clamp((cos_angle - c_out) / (c_in - c_out), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

glm::vec3 spot_radiant_intensity(const SpotLight& light, const glm::vec3& direction_from_light) {
  const float c = glm::dot(glm::normalize(light.direction), direction_from_light);
  return light.intensity * spot_falloff(light, c);
}

float spot_effective_solid_angle(const SpotLight& light) {
  const double c_in = std::cos(double(light.inner_angle_deg) * std::numbers::pi / 180.0);
  const double c_out = std::cos(double(light.outer_angle_deg) * std::numbers::pi / 180.0);
  return float(2.0 * std::numbers::pi * (1.0 - 0.5 * (c_in + c_out)));
}

float spot_outer_cone_solid_angle(const SpotLight& light) {
  const double c_out = std::cos(double(light.outer_angle_deg) * std::numbers::pi / 180.0);
  return float(2.0 * std::numbers::pi * (1.0 - c_out));
}

glm::vec3 spot_radiant_flux(const SpotLight& light) {
  return light.intensity * spot_effective_solid_angle(light);
}

float spot_texel_solid_angle(float tan_half_extent, int resolution, float x_ndc, float y_ndc) {
  const double t = tan_half_extent, side = 2.0 * t / double(resolution);
  const double x = double(x_ndc) * t, y = double(y_ndc) * t;
  return float(side * side / std::pow(1.0 + x * x + y * y, 1.5));
}

}  // namespace ldm
