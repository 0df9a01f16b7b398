#include "harness/reference/lighting_reference.h"

#include <algorithm>

#include "harness/metrics/image_metrics.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/lighting_estimator.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/reference/surface_point.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"

namespace ldm {
namespace {

void validate_lighting_request(const LightingReferenceRequest& request) {
  validate_reference_image_request(std::string(to_string(request.component)) + " reference",
                                   request.width, request.height, request.threads);
  validate_spp_rule(request.spp);
}

Image render_half_with(const EmbreeScene& embree, LightingComponent component, int width,
                       int height, uint32_t spp, uint64_t seed, uint32_t pass, int threads,
                       bool progress, const RussianRoulette& roulette) {
  const LightingEstimator estimator(embree, component, width, height, roulette);
  const PixelRenderSettings settings = reference_render_settings(
      to_string(component), width, height, spp, seed, pass, threads, progress);
  return render_pixels(settings, 3,
                       [&estimator](int x, int y, uint32_t n, Pcg32& rng, float* mean) {
                         const glm::vec3 value = estimator.pixel_mean(x, y, n, rng);
                         for (int c = 0; c < 3; ++c) mean[c] = value[c];
                       });
}

// The automatic rule's target applies to the noise as SSIM sees it: noise_mse · e², with e
// the exposure of the current mean image (lighting_reference.h).
double exposure_squared(const Image& half_a, const Image& half_b) {
  const double e = lighting_ssim_exposure(weighted_mean(half_a, 1, half_b, 1));
  return e * e;
}

nlohmann::json light_inputs(const SpotLight& l) {
  auto vec = [](glm::vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"position", vec(l.position)},
          {"direction", vec(l.direction)},
          {"intensity", vec(l.intensity)},
          {"inner_angle_deg", l.inner_angle_deg},
          {"outer_angle_deg", l.outer_angle_deg}};
}

}  // namespace

const char* to_string(LightingComponent component) {
  switch (component) {
    case LightingComponent::direct: return "direct";
    case LightingComponent::single_bounce: return "single_bounce";
    case LightingComponent::multi_bounce: return "multi_bounce";
  }
  return "?";
}

const std::vector<std::string>& lighting_component_names() {
  static const std::vector<std::string> names = {"direct", "single_bounce", "multi_bounce"};
  return names;
}

LightingComponent parse_lighting_component(const std::string& text, const std::string& context) {
  for (LightingComponent c : {LightingComponent::direct, LightingComponent::single_bounce,
                              LightingComponent::multi_bounce})
    if (text == to_string(c)) return c;
  throw UserError(context + ": unknown lighting component '" + text +
                  "' (expected direct, single_bounce or multi_bounce)");
}

Image render_lighting_half(const Scene& scene, LightingComponent component, int width,
                           int height, uint32_t spp, uint64_t seed, uint32_t pass, int threads,
                           bool progress, const RussianRoulette& roulette) {
  scene.validate();
  const Scene centred = centred_on_bounding_sphere(scene);
  const EmbreeScene embree(centred);
  return render_half_with(embree, component, width, height, spp, seed, pass, threads, progress,
                          roulette);
}

ReferenceResult render_lighting_reference(const Scene& scene,
                                          const LightingReferenceRequest& request) {
  validate_lighting_request(request);
  scene.validate();
  const Scene centred = centred_on_bounding_sphere(scene);
  const EmbreeScene embree(centred);  // one BVH for every pass of both halves
  // The direct image is deterministic: one "sample" per pixel and half is the converged
  // image, and the record says so (spp 1 per half) whatever rule was asked for.
  SppRule rule = request.spp;
  if (request.component == LightingComponent::direct) rule.spp_per_half = 1;
  ReferenceResult result = render_reference_pair(
      [&](uint64_t seed, uint32_t spp, uint32_t pass, uint32_t /*first: random samples*/) {
        return render_half_with(embree, request.component, request.width, request.height, spp,
                                seed, pass, request.threads, request.progress,
                                request.roulette);
      },
      rule, request.seed, exposure_squared);
  result.cache_key = reference_cache_key(lighting_reference_inputs(scene, request));
  annotate_ray_offset(result, scene, 0.0, "");
  return result;
}

nlohmann::json lighting_reference_inputs(const Scene& scene,
                                         const LightingReferenceRequest& request) {
  nlohmann::json inputs = {{"pass", "lighting"},
                           {"component", to_string(request.component)},
                           {"renderer_version", kLightingReferenceVersion},
                           {"scene", scene.name},
                           {"scene_content_hash", hex64(scene.content_hash())},
                           {"light", light_inputs(scene.light)},
                           {"width", request.width},
                           {"height", request.height},
                           {"spp", spp_rule_inputs(request.spp)},
                           {"seed", request.seed}};
  if (request.component == LightingComponent::multi_bounce)
    inputs["roulette"] = {{"start_bounce", request.roulette.start_bounce},
                          {"max_survival", request.roulette.max_survival},
                          {"max_bounces", request.roulette.max_bounces}};
  return inputs;
}

ReferenceResult cached_lighting_reference(const Scene& scene,
                                          const LightingReferenceRequest& request,
                                          const std::string& cache_dir) {
  validate_lighting_request(request);
  const nlohmann::json inputs = lighting_reference_inputs(scene, request);
  if (auto cached = load_cached_reference(cache_dir, inputs)) {
    annotate_ray_offset(*cached, scene, 0.0, "");
    return *cached;
  }
  ReferenceResult result = render_lighting_reference(scene, request);
  store_cached_reference(cache_dir, inputs, result);
  return result;
}

ReferenceResult lighting_reference_for_run(const Scene& scene, LightingComponent component,
                                           int width, int height,
                                           const ReferenceSettings& settings) {
  auto request = reference_request<LightingReferenceRequest>(width, height, settings);
  request.component = component;
  if (!settings.use_cache) return render_lighting_reference(scene, request);
  return cached_lighting_reference(
      scene, request, reference_cache_dir(settings.cache_dir));
}

double lighting_ssim_exposure(const Image& reference) { return exposure_for_reference(reference); }

}  // namespace ldm
