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

void validate_light(const Scene& scene) {
  const SpotLight& l = scene.light;
  for (int c = 0; c < 3; ++c)
    if (!(l.intensity[c] >= 0.0f) || !std::isfinite(l.intensity[c]))
      throw UserError("lighting reference: the spot light of scene '" + scene.name +
                      "' has intensity " + std::to_string(l.intensity[c]) + " in channel " +
                      std::to_string(c) + "; it must be finite and >= 0");
  if (!(glm::length(l.direction) > 0.0f) ||
      !(l.inner_angle_deg >= 0.0f && l.inner_angle_deg <= l.outer_angle_deg &&
        l.outer_angle_deg <= 180.0f))
    throw UserError("lighting reference: the spot light of scene '" + scene.name +
                    "' needs a non-zero direction and 0 <= inner <= outer <= 180 degrees");
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
      light_(scene.scene().light),
      light_frame_(glm::normalize(scene.scene().light.direction)),
      outer_cos_(std::cos(glm::radians(scene.scene().light.outer_angle_deg))),
      outer_solid_angle_(spot_outer_cone_solid_angle(scene.scene().light)) {
  if (width <= 0 || height <= 0)
    throw UserError("lighting reference: image size must be positive");
  validate_materials(scene.scene());
  validate_light(scene.scene());
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

std::optional<RayHit> LightingEstimator::light_sample(Pcg32& rng) const {
  const float u1 = rng.next_float(), u2 = rng.next_float();
  const float mu = 1.0f - u1 * (1.0f - outer_cos_);  // uniform in solid angle within the cone
  const float sine = std::sqrt(std::max(0.0f, 1.0f - mu * mu));
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  const glm::vec3 w = glm::normalize(
      light_frame_.to_world(glm::vec3(sine * std::cos(phi), sine * std::sin(phi), mu)));
  return scene_.intersect(light_.position, w, 0.0f, std::numeric_limits<float>::infinity());
}

// Light directions are uniform in the outer cone (density 1/Ω_outer); the change of measure
// to solid angle at x goes through y's area: dω_light = cos_l dA / r², dω_x = cos_y dA / d²,
// with the geometric normal of y's triangle (the area measure).
float LightingEstimator::light_strategy_pdf(const SurfacePoint& x, const SurfacePoint& y) const {
  const glm::vec3 from_light = y.position - light_.position;
  const float r2 = glm::dot(from_light, from_light);
  const glm::vec3 to_x = x.position - y.position;
  const float d2 = glm::dot(to_x, to_x);
  if (!(r2 > 0.0f) || !(d2 > 0.0f)) return 0.0f;
  const glm::vec3 l = from_light / std::sqrt(r2);
  if (glm::dot(glm::normalize(light_.direction), l) < outer_cos_) return 0.0f;
  const float cos_light = std::abs(glm::dot(y.geometric_normal, l));
  const float cos_y = std::abs(glm::dot(y.geometric_normal, to_x)) / std::sqrt(d2);
  if (!(cos_y > 0.0f)) return 0.0f;
  return (1.0f / outer_solid_angle_) * (cos_light / r2) * (d2 / cos_y);
}

// L(x) = ∫ f dω with f(ω) = albedo(x)/π L_direct(y(ω)) cos θ_x. Two strategies each draw one
// direction: A cosine-weighted at x (p_A = cos θ_x / π; good where the lit surface is near
// or large), B from the light through the surface it reaches first (p_B above; good where
// the lit patch is small and far, which A finds rarely: the spot's cone). The balance
// heuristic weighs each sample f / (p_A + p_B): unbiased, and bounded where either density
// is large (B alone has a 1/d² singularity where lit surfaces meet x's).
glm::vec3 LightingEstimator::single_bounce_sample(const SurfacePoint& x, Pcg32& rng) const {
  glm::vec3 sum(0.0f);
  const glm::vec3 rho_over_pi = albedo(x) * float(std::numbers::inv_pi);
  if (const auto y = next_surface(x, rng)) {  // strategy A
    const glm::vec3 light = direct_radiance(*y);
    if (max_channel(light) > 0.0f) {
      const glm::vec3 w = glm::normalize(y->position - x.offset_origin);
      const float p_a = std::max(0.0f, glm::dot(x.shading_normal, w)) *
                        float(std::numbers::inv_pi);
      const float p_b = light_strategy_pdf(x, *y);
      // f / (p_A + p_B) with f = albedo/π · light · cos θ_x = albedo · light · p_A.
      if (p_a > 0.0f) sum += albedo(x) * light * (p_a / (p_a + p_b));
    }
  }
  if (const auto hit = light_sample(rng)) {  // strategy B
    const glm::vec3 hit_position = surface_point(scene_, *hit, light_.position,
                                                 glm::vec3(0.0f, 0.0f, 1.0f)).position;
    const glm::vec3 toward = hit_position - x.offset_origin;
    const float distance = glm::length(toward);
    if (distance > 0.0f) {
      const glm::vec3 w = toward / distance;
      const float cos_x = glm::dot(x.shading_normal, w);
      if (cos_x > 0.0f && glm::dot(x.geometric_normal, w) > 0.0f) {
        // y as x sees it: the first surface along w (the same event strategy A samples).
        const SurfacePoint y = surface_point(scene_, *hit, x.offset_origin, w);
        const float y_offset = glm::length(y.offset_origin - y.position);
        if (distance > y_offset &&
            !scene_.occluded(x.offset_origin, w, 0.0f, distance - y_offset)) {
          const glm::vec3 light = direct_radiance(y);
          const float p_a = cos_x * float(std::numbers::inv_pi);
          const float p_b = light_strategy_pdf(x, y);
          if (max_channel(light) > 0.0f && p_b > 0.0f)
            sum += rho_over_pi * light * cos_x / (p_a + p_b);
        }
      }
    }
  }
  return sum;
}

// L_indirect(x) = S(x) + albedo(x)/π ∫ L_indirect(y) cos dω, with S the single bounce
// (above). Unrolled along a cosine-weighted path x = z_0, z_1, ... (each bounce's cos/π
// cancels its density): L_indirect(x) = E[Σ_k T_k S(z_k)], T_0 = 1, T_k the product of the
// albedos of z_0 .. z_{k-1}. So every vertex gets the two-strategy estimate of the light
// reaching it by one more bounce, and Russian roulette ends paths without bias (survivors'
// throughput divided by their probability).
glm::vec3 LightingEstimator::multi_bounce_sample(const SurfacePoint& x, Pcg32& rng) const {
  glm::vec3 radiance = single_bounce_sample(x, rng);
  glm::vec3 throughput(1.0f);
  SurfacePoint at = x;
  for (int bounce = 1; bounce < roulette_.max_bounces; ++bounce) {
    throughput *= albedo(at);
    if (max_channel(throughput) <= 0.0f) break;  // black: nothing more to carry
    if (bounce >= roulette_.start_bounce) {
      const float survival = std::min(roulette_.max_survival, max_channel(throughput));
      if (!(rng.next_float() < survival)) break;
      throughput /= survival;
    }
    const auto next = next_surface(at, rng);  // z_bounce
    if (!next) break;
    at = *next;
    radiance += throughput * single_bounce_sample(at, rng);
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
