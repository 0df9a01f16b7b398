#include "harness/reference/reference_image.h"

#include <algorithm>
#include <chrono>

#include "harness/util/error.h"

namespace ldm {

void validate_spp_rule(const SppRule& rule) {
  if (!(rule.target_noise_mse > 0.0))
    throw UserError("reference: target_noise_mse must be positive");
  if (rule.max_spp_per_half == 0) throw UserError("reference: max_spp_per_half must be >= 1");
  if (rule.start_spp_per_half == 0)
    throw UserError("reference: start_spp_per_half must be >= 1");
  if (rule.spp_per_half > rule.max_spp_per_half)
    throw UserError("reference: spp_per_half (" + std::to_string(rule.spp_per_half) +
                    ") exceeds max_spp_per_half (" + std::to_string(rule.max_spp_per_half) +
                    ")");
}

void validate_reference_image_request(const std::string& what, int width, int height,
                                      int threads) {
  // Larger images are a typo, not a reference anyone can wait for.
  constexpr int kMaxImageSide = 16384;
  if (width <= 0 || width > kMaxImageSide)
    throw UserError(what + ": width must lie in [1, " + std::to_string(kMaxImageSide) +
                    "] (got " + std::to_string(width) + ")");
  if (height <= 0 || height > kMaxImageSide)
    throw UserError(what + ": height must lie in [1, " + std::to_string(kMaxImageSide) +
                    "] (got " + std::to_string(height) + ")");
  if (threads < 0) throw UserError(what + ": threads must be >= 0");
}

double mean_squared_error(const Image& a, const Image& b) {
  if (!a.same_shape(b)) throw UserError("mean_squared_error: images differ in shape");
  if (a.pixels.empty()) throw UserError("mean_squared_error: images are empty");
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = double(a.pixels[i]) - double(b.pixels[i]);
    sum += d * d;
  }
  return sum / double(a.pixels.size());
}

Image weighted_mean(const Image& a, uint32_t n_a, const Image& b, uint32_t n_b) {
  if (!a.same_shape(b)) throw UserError("weighted_mean: images differ in shape");
  Image out(a.width, a.height, a.channels);
  const double total = double(n_a) + double(n_b);
  for (size_t i = 0; i < a.pixels.size(); ++i)
    out.pixels[i] = float((double(a.pixels[i]) * n_a + double(b.pixels[i]) * n_b) / total);
  return out;
}

ReferenceResult render_reference_pair(const HalfRenderer& render_half, const SppRule& rule,
                                      uint64_t seed, const NoiseScale& noise_scale) {
  validate_spp_rule(rule);
  const auto start = std::chrono::steady_clock::now();
  const bool automatic = rule.spp_per_half == 0;
  ReferenceResult r;
  r.spp_per_half = automatic ? std::min(rule.start_spp_per_half, rule.max_spp_per_half)
                             : rule.spp_per_half;
  r.half_a = render_half(seed, r.spp_per_half, 0, 0);
  r.half_b = render_half(seed + 1, r.spp_per_half, 0, 0);
  r.noise_mse = mean_squared_error(r.half_a, r.half_b) / 4.0;
  auto scaled_noise = [&] {
    return r.noise_mse * (noise_scale ? noise_scale(r.half_a, r.half_b) : 1.0);
  };
  for (uint32_t pass = 1; automatic && scaled_noise() > rule.target_noise_mse &&
                          r.spp_per_half < rule.max_spp_per_half;
       ++pass) {
    const uint32_t more = std::min(r.spp_per_half, rule.max_spp_per_half - r.spp_per_half);
    const uint32_t first = r.spp_per_half;
    r.half_a = weighted_mean(r.half_a, r.spp_per_half, render_half(seed, more, pass, first), more);
    r.half_b = weighted_mean(r.half_b, r.spp_per_half, render_half(seed + 1, more, pass, first), more);
    r.spp_per_half += more;
    r.noise_mse = mean_squared_error(r.half_a, r.half_b) / 4.0;
  }
  r.image = weighted_mean(r.half_a, 1, r.half_b, 1);
  r.spp_total = 2 * r.spp_per_half;
  r.noise_target_met = scaled_noise() <= rule.target_noise_mse;
  r.render_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace ldm
