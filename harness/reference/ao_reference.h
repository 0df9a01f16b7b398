#pragma once
// The path-traced ambient-occlusion reference (thesis §4.1-4.2, Eq. 5/6 estimated with the
// cosine-weighted Eq. 9) for a scene's camera: what the GPU AO pass should converge to.
// See ao_estimator.h for the per-pixel estimator and reference_image.h for the two-half
// noise estimate and the automatic spp rule.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/reference/reference_cache.h"
#include "harness/reference/reference_image.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/scene.h"

namespace ldm {

// Bump whenever a change to the AO reference alters its images: cached entries of older
// versions then stop matching.
// 2: traced in scene-centred coordinates, ray offset from the float precision at the hit.
// 3: the sampler is an input (sobol by default: Owen-scrambled Sobol directions).
inline constexpr int kAoReferenceVersion = 3;

const char* ao_sampler_name(AoSampler sampler);
AoSampler parse_ao_sampler(const std::string& text, const std::string& what);

struct AoReferenceRequest {
  int width = 0, height = 0;
  std::optional<AoSettings> ao;  // overrides scene.ao (normal_offset_pixels is not used)
  SppRule spp;                   // samples per pixel (reference_image.h)
  uint64_t seed = 1;   // the halves use seed and seed + 1
  AoSampler sampler = AoSampler::Sobol;
  int threads = 0;     // 0: all cores; does not change the image
  bool progress = true;
};

class EmbreeScene;

// One half image: `spp` samples per pixel with seed `seed`, independent pass `pass` (random
// samples: the rtao peer's, and the tests').
Image render_ao_half(const Scene& scene, const AoSettings& ao, int width, int height,
                     uint32_t spp, uint64_t seed, uint32_t pass = 0, int threads = 0,
                     bool progress = false);
// The same in a BVH the caller built once from centred_on_bounding_sphere(scene) (the frame
// the reference traces in): the estimator the reference and the rtao peer share.
Image render_ao_half(const EmbreeScene& centred, const AoSettings& ao, int width, int height,
                     uint32_t spp, uint64_t seed, uint32_t pass = 0, int threads = 0,
                     bool progress = false);
// A batch of the reference's half `seed`: samples first .. first + spp - 1 of `sampler`.
Image render_ao_batch(const EmbreeScene& centred, const AoSettings& ao, int width, int height,
                      uint32_t spp, uint64_t seed, uint32_t pass, uint32_t first,
                      AoSampler sampler, int threads = 0, bool progress = false);

// Throws UserError naming the request field at fault.
ReferenceResult render_ao_reference(const Scene& scene, const AoReferenceRequest& request);
// As render_ao_reference, through the disk cache (reference_cache.h).
ReferenceResult cached_ao_reference(const Scene& scene, const AoReferenceRequest& request,
                                    const std::string& cache_dir = default_reference_cache_dir());
// The AO reference a run's records are scored against: `ao` at width x height under the
// run's reference settings, through the cache unless they say otherwise. Every AO-like pass
// (the LDM AO, HBAO) calls this, so one cache entry serves them all.
ReferenceResult ao_reference_for_run(const Scene& scene, const AoSettings& ao, int width,
                                     int height, const ReferenceSettings& settings);
// Everything that determines the reference image, as stored in the cache sidecar.
nlohmann::json ao_reference_inputs(const Scene& scene, const AoReferenceRequest& request);

}  // namespace ldm
