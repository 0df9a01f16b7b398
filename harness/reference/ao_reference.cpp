#include "harness/reference/ao_reference.h"

#include <cstdio>

#include "harness/reference/ao_estimator.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"

namespace ldm {
namespace {

// Larger images are a typo, not a reference anyone can wait for.
constexpr int kMaxImageSide = 16384;

void validate(const AoReferenceRequest& request) {
  if (request.width <= 0 || request.width > kMaxImageSide)
    throw UserError("AO reference: width must lie in [1, " + std::to_string(kMaxImageSide) +
                    "] (got " + std::to_string(request.width) + ")");
  if (request.height <= 0 || request.height > kMaxImageSide)
    throw UserError("AO reference: height must lie in [1, " + std::to_string(kMaxImageSide) +
                    "] (got " + std::to_string(request.height) + ")");
  if (request.threads < 0) throw UserError("AO reference: threads must be >= 0");
}

AoSettings settings_used(const Scene& scene, const AoReferenceRequest& request) {
  return request.ao.value_or(scene.ao);
}

}  // namespace

Image render_ao_half(const EmbreeScene& embree, const AoSettings& ao, int width, int height,
                     uint32_t spp, uint64_t seed, uint32_t pass, int threads, bool progress) {
  const AoEstimator estimator(embree, ao, width, height);
  PixelRenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.spp = spp;
  settings.seed = seed;
  settings.pass = pass;
  settings.threads = threads;
  settings.progress = progress;
  settings.label = "AO reference (seed " + std::to_string(seed) + ", pass " +
                   std::to_string(pass) + ", " + std::to_string(spp) + " spp)";
  return render_pixels(settings, 1,
                       [&estimator](int x, int y, uint32_t n, Pcg32& rng, float* mean) {
                         *mean = estimator.pixel_mean(x, y, n, rng);
                       });
}

namespace {

// The secondary rays start up to `offset` off the surface, so hit distances are biased by up
// to that much: V = (d/d_max)^2 moves by at most 2 * offset / d_max, and an occluder closer
// than the offset is missed. Below 1e-3 of d_max the squared bias stays under 4e-6, below the
// reference's own noise target (1e-5); above it (or above 1e-3 of the scene's radius) the
// record says the reference may be biased.
constexpr double kMaterialOffsetFraction = 1e-3;

void annotate_ray_offset(ReferenceResult& result, const Scene& scene, const AoSettings& ao) {
  result.ray_offset = AoEstimator::max_ray_offset(centred_on_bounding_sphere(scene));
  const double radius = scene.bounding_sphere().radius;
  const char* scale = ao.attenuated && result.ray_offset > kMaterialOffsetFraction * ao.d_max
                          ? "d_max"
                      : result.ray_offset > kMaterialOffsetFraction * radius ? "the scene's radius"
                                                                             : nullptr;
  if (scale) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "reference ray offset %g is a material fraction (> 1e-3) of %s: the reference "
                  "may be biased",
                  result.ray_offset, scale);
    result.ray_offset_warning = text;
  }
}

}  // namespace

Image render_ao_half(const Scene& scene, const AoSettings& ao, int width, int height,
                     uint32_t spp, uint64_t seed, uint32_t pass, int threads, bool progress) {
  scene.validate();
  const Scene centred = centred_on_bounding_sphere(scene);
  const EmbreeScene embree(centred);
  return render_ao_half(embree, ao, width, height, spp, seed, pass, threads, progress);
}

ReferenceResult render_ao_reference(const Scene& scene, const AoReferenceRequest& request) {
  validate(request);
  const SppRule& rule = request.spp;
  validate_spp_rule(rule);
  scene.validate();
  const AoSettings ao = settings_used(scene, request);
  const Scene centred = centred_on_bounding_sphere(scene);
  const EmbreeScene embree(centred);  // one BVH for every pass of both halves
  ReferenceResult result = render_reference_pair(
      [&](uint64_t seed, uint32_t spp, uint32_t pass) {
        return render_ao_half(embree, ao, request.width, request.height, spp, seed, pass,
                                request.threads, request.progress);
      },
      rule, request.seed);
  result.cache_key = reference_cache_key(ao_reference_inputs(scene, request));
  annotate_ray_offset(result, scene, ao);
  return result;
}

nlohmann::json ao_reference_inputs(const Scene& scene, const AoReferenceRequest& request) {
  const AoSettings ao = settings_used(scene, request);
  nlohmann::json spp;
  if (request.spp.spp_per_half > 0)
    spp = {{"per_half", request.spp.spp_per_half}};
  else
    spp = {{"auto_target_noise_mse", request.spp.target_noise_mse},
           {"auto_max_per_half", request.spp.max_spp_per_half},
           {"auto_start_per_half", request.spp.start_spp_per_half}};
  return {{"pass", "ao"},
          {"renderer_version", kAoReferenceVersion},
          {"scene", scene.name},
          {"scene_content_hash", hex64(scene.content_hash())},
          {"width", request.width},
          {"height", request.height},
          {"ao",
           {{"attenuated", ao.attenuated},
            {"d_max", ao.d_max},
            {"falloff_exponent", ao.falloff_exponent}}},
          {"spp", spp},
          {"seed", request.seed}};
}

ReferenceResult cached_ao_reference(const Scene& scene, const AoReferenceRequest& request,
                                    const std::string& cache_dir) {
  validate(request);
  validate_spp_rule(request.spp);
  const nlohmann::json inputs = ao_reference_inputs(scene, request);
  if (auto cached = load_cached_reference(cache_dir, inputs)) {
    annotate_ray_offset(*cached, scene, settings_used(scene, request));
    return *cached;
  }
  ReferenceResult result = render_ao_reference(scene, request);
  store_cached_reference(cache_dir, inputs, result);
  return result;
}

ReferenceResult ao_reference_for_run(const Scene& scene, const AoSettings& ao, int width,
                                     int height, const ReferenceSettings& settings) {
  AoReferenceRequest request;
  request.width = width;
  request.height = height;
  request.ao = ao;
  request.spp = settings.spp;
  request.seed = settings.seed;
  request.progress = settings.progress;
  if (!settings.use_cache) return render_ao_reference(scene, request);
  return cached_ao_reference(
      scene, request, settings.cache_dir.empty() ? kDefaultReferenceCacheDir : settings.cache_dir);
}

}  // namespace ldm
