#pragma once
// Path-traced (Embree) references of the lighting passes (issue 9, thesis §5): what the GPU
// indirect pass's images should converge to, for the scene's camera and spot light.
//
// Every pixel shades the same G-buffer point as the AO reference (the primary hit through
// the pixel centre, shading normal facing the camera; 0 where the ray misses) and holds the
// outgoing radiance toward the camera there, linear RGB in W/(sr m²). Surfaces are
// two-sided Lambertian (BRDF albedo/π), nothing emits, and the spot light is a point light
// with the radiant intensity of harness/scene/spot_light.h. Components:
//   direct         albedo/π · I(ω_l) · max(0, n·ω_l) / r² · V(x, light). Deterministic given
//                  the G-buffer point: no sample is jittered, the two halves are identical
//                  and the noise floor is 0 (the halves are still rendered, so that the
//                  result has the same shape as every other reference; spp_per_half is
//                  1 whatever the request's rule).
//   single_bounce  light → one diffuse surface y → x → eye: exactly one diffuse
//                  interreflection (what the photon method approximates, LDDE paths), the
//                  direct term NOT included. Per sample two strategies under the balance
//                  heuristic: a cosine-weighted direction from x with next-event estimation
//                  of the light at the surface y it meets, and a direction from the light,
//                  uniform in its outer cone, whose first hit y is connected to x
//                  (lighting_estimator.cpp).
//   multi_bounce   all indirect light (paths with >= 1 interreflection), direct NOT
//                  included: a cosine-weighted path from x with the single-bounce estimate
//                  at every vertex, Russian roulette (unbiased: the survival probability
//                  divides the throughput).
// Noise target: radiance has no fixed scale, so the automatic spp rule compares
//   noise_mse · e² ≤ spp.target_noise_mse,   e = lighting_ssim_exposure(current mean)
// i.e. the noise measured on the image as SSIM sees it (docs/reference/accuracy.md). `noise_mse` in
// the result stays in radiance² units, comparable with the MSE of a pass's image.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/reference/reference_cache.h"
#include "harness/reference/reference_image.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/scene.h"

namespace ldm {

// Bump whenever a change to the lighting references alters their images.
inline constexpr int kLightingReferenceVersion = 1;

enum class LightingComponent { direct, single_bounce, multi_bounce };

const char* to_string(LightingComponent component);  // "direct", "single_bounce", "multi_bounce"
// Throws UserError naming `context` and the accepted names.
LightingComponent parse_lighting_component(const std::string& text,
                                           const std::string& context = "lighting component");
// Every component's name, in enum order (for CLI choices).
const std::vector<std::string>& lighting_component_names();

// Russian roulette of the multi-bounce reference: from interreflection `start_bounce` on
// (1 = the first surface after x), a path continues with probability
// q = min(max_survival, max channel of its throughput) and its throughput is divided by q.
// `max_bounces` is a safety stop only (with albedos <= 1 every path ends with probability
// 1): a path reaching it is cut, which biases the image by less than
// max_survival^(max_bounces - start_bounce) of its indirect light (1e-23 by default).
struct RussianRoulette {
  int start_bounce = 3;
  float max_survival = 0.95f;
  int max_bounces = 1024;
};

struct LightingReferenceRequest {
  int width = 0, height = 0;
  LightingComponent component = LightingComponent::direct;
  SppRule spp;        // samples per pixel; the automatic target is relative (see above)
  uint64_t seed = 1;  // the halves use seed and seed + 1
  int threads = 0;    // 0: all cores; does not change the image
  bool progress = true;
  RussianRoulette roulette;  // multi_bounce only
};

// One half image: `spp` samples per pixel with seed `seed`, independent pass `pass`.
Image render_lighting_half(const Scene& scene, LightingComponent component, int width,
                           int height, uint32_t spp, uint64_t seed, uint32_t pass = 0,
                           int threads = 0, bool progress = false,
                           const RussianRoulette& roulette = {});

// Throws UserError naming the request field at fault.
ReferenceResult render_lighting_reference(const Scene& scene,
                                          const LightingReferenceRequest& request);
// As render_lighting_reference, through the disk cache (reference_cache.h).
ReferenceResult cached_lighting_reference(const Scene& scene,
                                          const LightingReferenceRequest& request,
                                          const std::string& cache_dir = default_reference_cache_dir());
// The lighting reference a run's records are scored against, under the run's reference
// settings, through the cache unless they say otherwise.
ReferenceResult lighting_reference_for_run(const Scene& scene, LightingComponent component,
                                           int width, int height,
                                           const ReferenceSettings& settings);
// Everything that determines the reference image, as stored in the cache sidecar: the
// component, the scene's content hash (geometry, materials, camera, light), the light's
// fields spelled out, image size, spp rule, seed, roulette (multi_bounce) and
// kLightingReferenceVersion.
nlohmann::json lighting_reference_inputs(const Scene& scene,
                                         const LightingReferenceRequest& request);

// The exposure the metrics scale lighting images by before SSIM's clamp to [0, 1]: the one
// that maps the reference's 99th-percentile luminance to 1 (exposure_for_reference,
// harness/metrics/image_metrics.h), so that only the brightest 1% of pixels clip; 1 for a
// black reference. Pass it as MetricOptions::ssim_exposure for both images.
double lighting_ssim_exposure(const Image& reference);

}  // namespace ldm
