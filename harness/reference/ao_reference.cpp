#include "harness/reference/ao_reference.h"

#include <cstdio>

#include "harness/reference/ao_estimator.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/reference/surface_point.h"
#include "harness/util/enum_names.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"

namespace ldm {
namespace {

void validate_ao_request(const AoReferenceRequest& request) {
  validate_reference_image_request("AO reference", request.width, request.height,
                                   request.threads);
}

AoSettings settings_used(const Scene& scene, const AoReferenceRequest& request) {
  return request.ao.value_or(scene.ao);
}

}  // namespace

constexpr EnumNames<AoSampler, 2> kAoSamplerNames{{{AoSampler::Sobol, "sobol"}, {AoSampler::Random, "random"}}};

const char* ao_sampler_name(AoSampler sampler) { return name_of(kAoSamplerNames, sampler); }

AoSampler parse_ao_sampler(const std::string& text, const std::string& what) {
  if (const auto sampler = value_named(kAoSamplerNames, text)) return *sampler;
  throw UserError(what + " '" + text + "': expected sobol or random");
}

Image render_ao_half(const EmbreeScene& embree, const AoSettings& ao, int width, int height,
                     uint32_t spp, uint64_t seed, uint32_t pass, int threads, bool progress) {
  return render_ao_batch(embree, ao, width, height, spp, seed, pass, 0, AoSampler::Random,
                         threads, progress);
}

Image render_ao_batch(const EmbreeScene& embree, const AoSettings& ao, int width, int height,
                      uint32_t spp, uint64_t seed, uint32_t pass, uint32_t first,
                      AoSampler sampler, int threads, bool progress) {
  const AoEstimator estimator(embree, ao, width, height);
  const PixelRenderSettings settings =
      reference_render_settings("AO", width, height, spp, seed, pass, threads, progress);
  if (sampler == AoSampler::Random)
    return render_pixels(settings, 1,
                         [&estimator](int x, int y, uint32_t n, Pcg32& rng, float* mean) {
                           *mean = estimator.pixel_mean(x, y, n, rng);
                         });
  return render_pixels(settings, 1, [&](int x, int y, uint32_t n, Pcg32&, float* mean) {
    const ScrambledSobol2D points(seed, uint64_t(y) * uint64_t(width) + uint64_t(x));
    *mean = estimator.pixel_mean(x, y, first, n, points);
  });
}

namespace {

// The secondary rays start up to `offset` off the surface, so hit distances are biased by up
// to that much: V = (d/d_max)^2 moves by at most 2 * offset / d_max, and an occluder closer
// than the offset is missed. Below 1e-3 of d_max the squared bias stays under 4e-6, below the
// reference's own noise target (1e-5); above it (or above 1e-3 of the scene's radius) the
// record says the reference may be biased.
void annotate_ray_offset(ReferenceResult& result, const Scene& scene, const AoSettings& ao) {
  annotate_ray_offset(result, scene, ao.attenuated ? double(ao.d_max) : 0.0, "d_max");
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
  validate_ao_request(request);
  const SppRule& rule = request.spp;
  validate_spp_rule(rule);
  scene.validate();
  const AoSettings ao = settings_used(scene, request);
  const Scene centred = centred_on_bounding_sphere(scene);
  const EmbreeScene embree(centred);  // one BVH for every pass of both halves
  ReferenceResult result = render_reference_pair(
      [&](uint64_t seed, uint32_t spp, uint32_t pass, uint32_t first) {
        return render_ao_batch(embree, ao, request.width, request.height, spp, seed, pass,
                               first, request.sampler, request.threads, request.progress);
      },
      rule, request.seed);
  result.cache_key = reference_cache_key(ao_reference_inputs(scene, request));
  annotate_ray_offset(result, scene, ao);
  return result;
}

nlohmann::json ao_reference_inputs(const Scene& scene, const AoReferenceRequest& request) {
  const AoSettings ao = settings_used(scene, request);
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
          {"spp", spp_rule_inputs(request.spp)},
          {"seed", request.seed},
          {"sampler", ao_sampler_name(request.sampler)}};
}

ReferenceResult cached_ao_reference(const Scene& scene, const AoReferenceRequest& request,
                                    const std::string& cache_dir) {
  validate_ao_request(request);
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
  auto request = reference_request<AoReferenceRequest>(width, height, settings);
  request.ao = ao;
  request.sampler = settings.ao_sampler;
  if (!settings.use_cache) return render_ao_reference(scene, request);
  return cached_ao_reference(
      scene, request, reference_cache_dir(settings.cache_dir));
}

}  // namespace ldm
