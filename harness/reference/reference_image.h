#pragma once
// A Monte Carlo reference image with its own noise estimate (DESIGN.md, "Accuracy": no
// difference smaller than the reference's noise may be reported as a difference).
//
// Two independent half images A and B are rendered with seeds s and s + 1, spp samples per
// pixel each. The reference is their mean (2 spp samples per pixel), and
//   noise_mse = MSE(A, B) / 4
// estimates the expected MSE of that mean against the converged image: each half has
// per-pixel variance σ²/spp, so E[MSE(A, B)] = 2σ²/spp and Var(mean) = σ²/(2 spp).
//
// Automatic spp (spp_per_half = 0): both halves start with `start_spp_per_half` samples;
// while noise_mse > target_noise_mse and spp_per_half < max_spp_per_half, each half gets as
// many further samples again (a new independent pass, accumulated into the mean), doubling
// spp_per_half (the last step is capped at the maximum). noise_target_met records whether
// the target was reached. A fixed spp renders one pass per half.
#include <cstdint>
#include <functional>
#include <string>

#include "harness/image/image.h"

namespace ldm {

struct SppRule {
  uint32_t spp_per_half = 0;  // 0: automatic
  double target_noise_mse = 1e-5;
  uint32_t max_spp_per_half = 4096;
  uint32_t start_spp_per_half = 16;
};

struct ReferenceResult {
  Image image;           // mean of the halves
  Image half_a, half_b;  // independent halves, e.g. for SSIM(A, B)
  uint32_t spp_per_half = 0;
  uint32_t spp_total = 0;  // 2 * spp_per_half
  double noise_mse = 0;
  bool noise_target_met = false;
  double render_seconds = 0;
  bool from_cache = false;
  std::string cache_key;
  // Where the tracer starts secondary rays off the surface (scene units; 0: not a tracer
  // with an offset), and why that may bias the image (empty: it cannot materially).
  double ray_offset = 0;
  std::string ray_offset_warning;
};

// Renders `spp` samples per pixel of one half: seed s selects the half, `pass` a further
// batch of samples for the same half, whose first sample is sample `first` of the half
// (batches are contiguous: a sampler with a sequence continues it). Returns per-pixel means.
using HalfRenderer =
    std::function<Image(uint64_t seed, uint32_t spp, uint32_t pass, uint32_t first)>;

// The factor the automatic rule multiplies noise_mse by before comparing it with the target,
// given the halves so far: none (1) for AO, whose values lie in [0, 1]; the square of the
// SSIM exposure for radiance, which has no fixed scale (lighting_reference.h).
using NoiseScale = std::function<double(const Image& half_a, const Image& half_b)>;

// Throws UserError naming the field on a bad rule (target <= 0, max = 0, fixed spp > max).
void validate_spp_rule(const SppRule& rule);
// Throws UserError naming `what` ("AO reference") and the field: a side outside
// [1, 16384] or a negative thread count.
void validate_reference_image_request(const std::string& what, int width, int height,
                                      int threads);
ReferenceResult render_reference_pair(const HalfRenderer& render_half, const SppRule& rule,
                                      uint64_t seed, const NoiseScale& noise_scale = {});

// Mean squared difference over all pixels and channels; throws UserError on shape mismatch.
double mean_squared_error(const Image& a, const Image& b);
// Per-pixel mean of two images rendered with n_a and n_b samples per pixel.
Image weighted_mean(const Image& a, uint32_t n_a, const Image& b, uint32_t n_b);

}  // namespace ldm
