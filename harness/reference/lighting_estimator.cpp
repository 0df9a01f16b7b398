#include "harness/reference/lighting_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "harness/reference/hemisphere.h"
#include "harness/scene/spot_light.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

void validate_materials(const Scene& scene) {
  for (const Material& m : scene.materials)
    for (int c = 0; c < 3; ++c)
      if (!(m.albedo[c] >= 0.0f && m.albedo[c] <= 1.0f))
        throw UserError("lighting reference: material '" + m.name + "' of scene '" + scene.name +
                        "' has albedo " + std::to_string(m.albedo[c]) +
                        " in channel " + std::to_string(c) + "; it must lie in [0, 1]");
}

void validate_roulette(const RussianRoulette& r) {
  if (r.start_bounce < 1) throw UserError("lighting reference: roulette start_bounce must be >= 1");
  if (!(r.max_survival > 0.0f && r.max_survival < 1.0f))
    throw UserError("lighting reference: roulette max_survival must lie in (0, 1)");
  if (r.max_bounces < r.start_bounce)
    throw UserError("lighting reference: roulette max_bounces must be >= start_bounce");
}

float max_channel(glm::vec3 v) { return std::max({v.x, v.y, v.z}); }

}  // namespace

LightingEstimator::LightingEstimator(const EmbreeScene& scene, LightingComponent component,
                                     int width, int height, const RussianRoulette& roulette)
    : scene_(scene),
      component_(component),
      width_(width),
      height_(height),
      camera_(camera_frame(scene.scene().camera, width, height)),
      roulette_(roulette),
      light_(scene.scene().light) {
  if (width <= 0 || height <= 0)
    throw UserError("lighting reference: image size must be positive");
  validate_materials(scene.scene());
  validate_roulette(roulette);
}

glm::vec3 LightingEstimator::albedo(const SurfacePoint& point) const {
  const Scene& scene = scene_.scene();
  return scene.materials[scene.mesh.triangle_materials[point.triangle]].albedo;
}

glm::vec3 LightingEstimator::direct_radiance(const SurfacePoint& point) const {
  const glm::vec3 to_light = light_.position - point.position;
  const float r2 = glm::dot(to_light, to_light);
  if (!(r2 > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 l = to_light / std::sqrt(r2);
  const float cos_surface = glm::dot(point.shading_normal, l);
  // Lit only from the viewer's side of the surface: a light behind the triangle's plane
  // cannot reach the side the viewer sees, whatever the interpolated normal says.
  if (cos_surface <= 0.0f || glm::dot(point.geometric_normal, to_light) <= 0.0f)
    return glm::vec3(0.0f);
  const glm::vec3 intensity = spot_radiant_intensity(light_, -l);
  if (max_channel(intensity) <= 0.0f) return glm::vec3(0.0f);
  // The shadow ray stops short of the light by the ray offset, so a light touching a surface
  // is not shadowed by it.
  const glm::vec3 shadow = light_.position - point.offset_origin;
  const float distance = glm::length(shadow);
  const float offset = glm::length(point.offset_origin - point.position);
  if (distance > offset &&
      scene_.occluded(point.offset_origin, shadow / distance, 0.0f, distance - offset))
    return glm::vec3(0.0f);
  return albedo(point) * float(std::numbers::inv_pi) * intensity * (cos_surface / r2);
}

std::optional<SurfacePoint> LightingEstimator::next_surface(const SurfacePoint& from,
                                                            Pcg32& rng) const {
  const float u1 = rng.next_float(), u2 = rng.next_float();
  const glm::vec3 w = NormalFrame(from.shading_normal).to_world(cosine_weighted_direction(u1, u2));
  // Below the triangle's plane (possible where shading and geometric normals differ): the
  // ray would start inside the surface; that direction carries no light to the viewer.
  if (glm::dot(w, from.geometric_normal) <= 0.0f) return std::nullopt;
  const auto hit =
      scene_.intersect(from.offset_origin, w, 0.0f, std::numeric_limits<float>::infinity());
  if (!hit) return std::nullopt;
  return surface_point(scene_, *hit, from.offset_origin, w);
}

// L(x) = albedo(x)/π ∫ L_direct(y(ω)) cos dω; with pdf cos/π the sample is albedo(x) L_direct(y).
glm::vec3 LightingEstimator::single_bounce_sample(const SurfacePoint& x, Pcg32& rng) const {
  const auto y = next_surface(x, rng);
  if (!y) return glm::vec3(0.0f);
  return albedo(x) * direct_radiance(*y);
}

// L(x) = albedo(x)/π ∫ [L_direct(y) + L_indirect(y)] cos dω, the recursion unrolled: the
// throughput T is the product of the albedos so far (each cosine-weighted bounce cancels its
// cos/π), next-event estimation adds T · L_direct at every vertex after x, and Russian
// roulette ends paths without bias (survivors' throughput divided by their probability).
glm::vec3 LightingEstimator::multi_bounce_sample(const SurfacePoint& x, Pcg32& rng) const {
  glm::vec3 radiance(0.0f);
  glm::vec3 throughput = albedo(x);
  SurfacePoint at = x;
  for (int bounce = 1;; ++bounce) {
    const auto y = next_surface(at, rng);
    if (!y) break;
    radiance += throughput * direct_radiance(*y);
    if (bounce >= roulette_.max_bounces) break;
    throughput *= albedo(*y);
    if (max_channel(throughput) <= 0.0f) break;  // black: nothing more to carry
    if (bounce >= roulette_.start_bounce) {
      const float survival = std::min(roulette_.max_survival, max_channel(throughput));
      if (!(rng.next_float() < survival)) break;
      throughput /= survival;
    }
    at = *y;
  }
  return radiance;
}

glm::vec3 LightingEstimator::pixel_mean(int x, int y, uint32_t spp, Pcg32& rng) const {
  const auto point = camera_surface_point(scene_, camera_, x, y, width_, height_);
  if (!point) return glm::vec3(0.0f);  // the GPU writes 0 for background
  if (component_ == LightingComponent::direct) return direct_radiance(*point);
  // Double sums: thousands of float samples would lose digits.
  glm::dvec3 sum(0.0);
  for (uint32_t i = 0; i < spp; ++i)
    sum += glm::dvec3(component_ == LightingComponent::single_bounce
                          ? single_bounce_sample(*point, rng)
                          : multi_bounce_sample(*point, rng));
  return glm::vec3(sum / double(spp));
}

}  // namespace ldm
