#pragma once
// A per-pixel Monte Carlo rendering engine: the image is cut into tiles that std::thread
// workers take in turn; each pixel draws from its own PCG32 stream seeded from (seed, pass,
// pixel index), so the image is bit-identical for any thread count or schedule.
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>

#include <glm/glm.hpp>

#include "harness/image/image.h"
#include "harness/reference/pcg32.h"

namespace ldm {

struct PixelRenderSettings {
  int width = 0, height = 0;
  uint32_t spp = 1;     // samples per pixel
  uint64_t seed = 1;
  uint32_t pass = 0;    // further independent samples with the same seed use another pass
  int threads = 0;      // 0: std::thread::hardware_concurrency()
  bool progress = true; // percentage and ETA on stderr for renders longer than ~2 s
  std::string label = "render";
};

// The settings of one half or batch of a reference render, labelled
// "<what> reference (seed S, pass P, K spp)".
PixelRenderSettings reference_render_settings(const std::string& what, int width, int height,
                                              uint32_t spp, uint64_t seed, uint32_t pass,
                                              int threads, bool progress);

// Called once per pixel: draws `spp` samples from `rng` and writes the per-channel mean into
// `mean[0 .. channels)`. Per-pixel work shared by all samples (a primary ray) is done once,
// and the samples may be traced in batches. Called concurrently from several threads.
using PixelEstimator =
    std::function<void(int x, int y, uint32_t spp, Pcg32& rng, float* mean)>;

// The worker threads render_pixels() starts for `threads` (0: all cores) on a width x height
// image: never more than it has tiles.
int render_worker_count(int threads, int width, int height);

// Throws UserError on a non-positive size, spp = 0 or a negative thread count; rethrows the
// first exception an estimator throws.
Image render_pixels(const PixelRenderSettings& settings, int channels,
                    const PixelEstimator& estimator);

// The simple form: `sample(x, y, rng)` returns one float or glm::vec3 sample and runs `spp`
// times per pixel; the image holds the per-pixel mean (1 or 3 channels).
template <typename SampleFunction>
Image render_sample_mean(const PixelRenderSettings& settings, SampleFunction sample) {
  using Value = std::invoke_result_t<SampleFunction&, int, int, Pcg32&>;
  static_assert(std::is_same_v<Value, float> || std::is_same_v<Value, glm::vec3>,
                "a sample is a float or a glm::vec3");
  constexpr int channels = std::is_same_v<Value, float> ? 1 : 3;
  return render_pixels(settings, channels,
                       [&sample](int x, int y, uint32_t spp, Pcg32& rng, float* mean) {
                         // Double sums: thousands of float samples would lose digits.
                         glm::dvec3 sum(0.0);
                         for (uint32_t i = 0; i < spp; ++i) sum += glm::dvec3(sample(x, y, rng));
                         for (int c = 0; c < channels; ++c) mean[c] = float(sum[c] / spp);
                       });
}

}  // namespace ldm
