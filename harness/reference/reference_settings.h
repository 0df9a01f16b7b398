#pragma once
// How `ldmbench run` asks for the references its records are scored against: shared by
// every pass (each renders its own kind of reference, harness/passes/pass.h).
#include <cstdint>
#include <string>

#include "harness/reference/reference_image.h"

namespace ldm {

// Where an AO reference pixel's directions come from: independent random numbers (PCG32 per
// pixel), or its own Owen-scrambled Sobol sequence (sobol_sampler.h), which reaches the same
// noise with fewer rays (docs/measured/reference-sampling/).
enum class AoSampler { Random, Sobol };

struct ReferenceSettings {
  bool enabled = true;
  SppRule spp;            // samples per pixel: fixed, or doubling until the noise target
  uint64_t seed = 1;      // the halves use seed and seed + 1
  AoSampler ao_sampler = AoSampler::Sobol;  // the AO reference's (lighting's: random)
  std::string cache_dir;  // empty: default_reference_cache_dir() (reference_cache.h)
  bool use_cache = true;  // false: render even when the cache holds a matching entry
  bool progress = true;   // progress with ETA on a terminal
};

// A reference request (AoReferenceRequest, LightingReferenceRequest) for a width x height
// image with the settings' samples per pixel, seed and progress.
template <typename Request>
Request reference_request(int width, int height, const ReferenceSettings& settings) {
  Request request;
  request.width = width;
  request.height = height;
  request.spp = settings.spp;
  request.seed = settings.seed;
  request.progress = settings.progress;
  return request;
}

}  // namespace ldm
