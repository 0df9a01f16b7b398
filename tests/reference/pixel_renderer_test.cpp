// The per-pixel Monte Carlo engine: coverage, determinism, means, errors, progress display.
#include <atomic>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "harness/reference/hemisphere.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/reference/progress.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

PixelRenderSettings small_settings(int threads, uint64_t seed = 7) {
  PixelRenderSettings s;
  s.width = 37;  // not a multiple of the tile size
  s.height = 23;
  s.spp = 16;
  s.seed = seed;
  s.threads = threads;
  s.progress = false;
  return s;
}

TEST(Pcg32, MatchesTheReferenceImplementation) {
  // pcg32-demo: pcg32_srandom_r(&rng, 42u, 54u), first six pcg32_random_r outputs.
  Pcg32 rng(42u, 54u);
  const uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                               0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  for (uint32_t e : expected) EXPECT_EQ(rng.next_u32(), e);
}

TEST(Pcg32, PixelStreamsDependOnSeedPassAndPixel) {
  const uint32_t base = pixel_stream(1, 0, 5).next_u32();
  EXPECT_NE(pixel_stream(2, 0, 5).next_u32(), base);
  EXPECT_NE(pixel_stream(1, 1, 5).next_u32(), base);
  EXPECT_NE(pixel_stream(1, 0, 6).next_u32(), base);
  EXPECT_EQ(pixel_stream(1, 0, 5).next_u32(), base);
}

TEST(Hemisphere, FrameIsOrthonormalForAnyNormal) {
  Pcg32 rng(3, 4);
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 n(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    if (i == 0) n = {0, 0, -1};  // the branch cut of the construction
    if (i == 1) n = {0, 0, 1};
    if (glm::length(n) < 1e-3f) continue;
    n = glm::normalize(n);
    const NormalFrame f(n);
    EXPECT_NEAR(glm::length(f.tangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.bitangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.tangent, f.bitangent), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.tangent, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.bitangent, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.to_world({0, 0, 1}), n), 1.0f, 1e-5f);
  }
}

TEST(Hemisphere, CosineWeightedMomentsMatch) {
  // With pdf cos(theta)/pi: E[cos] = 2/3, E[cos^2] = 1/2, E[x] = E[y] = 0.
  Pcg32 rng(11, 12);
  const int n = 200000;
  double sum_z = 0, sum_z2 = 0, sum_x = 0;
  for (int i = 0; i < n; ++i) {
    const float u1 = rng.next_float(), u2 = rng.next_float();
    const glm::vec3 d = cosine_weighted_direction(u1, u2);
    ASSERT_GT(d.z, 0.0f);
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    sum_z += d.z;
    sum_z2 += d.z * d.z;
    sum_x += d.x;
  }
  // Each variable lies in [-1, 1]: standard error <= 1/sqrt(n); allow 5 of them.
  const double tolerance = 5.0 / std::sqrt(double(n));
  EXPECT_NEAR(sum_z / n, 2.0 / 3.0, tolerance);
  EXPECT_NEAR(sum_z2 / n, 0.5, tolerance);
  EXPECT_NEAR(sum_x / n, 0.0, tolerance);
}

TEST(PixelRenderer, VisitsEveryPixelExactlyOnce) {
  std::atomic<int> calls{0};
  const Image image = render_pixels(small_settings(3), 2,
                                    [&](int x, int y, uint32_t spp, Pcg32&, float* mean) {
                                      ++calls;
                                      mean[0] = float(x);
                                      mean[1] = float(y * 1000 + int(spp));
                                    });
  EXPECT_EQ(calls, 37 * 23);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) {
      EXPECT_EQ(image.at(x, y, 0), float(x));
      EXPECT_EQ(image.at(x, y, 1), float(y * 1000 + 16));
    }
}

TEST(PixelRenderer, ImageDoesNotDependOnThreadCount) {
  auto sample = [](int, int, Pcg32& rng) { return rng.next_float(); };
  const Image one = render_sample_mean(small_settings(1), sample);
  const Image two = render_sample_mean(small_settings(2), sample);
  const Image five = render_sample_mean(small_settings(5), sample);
  EXPECT_EQ(one.pixels, two.pixels);
  EXPECT_EQ(one.pixels, five.pixels);
  EXPECT_NE(one.pixels, render_sample_mean(small_settings(2, 8), sample).pixels);
  PixelRenderSettings next_pass = small_settings(2);
  next_pass.pass = 1;
  EXPECT_NE(one.pixels, render_sample_mean(next_pass, sample).pixels);
}

TEST(PixelRenderer, SampleMeanConvergesToTheExpectation) {
  PixelRenderSettings s = small_settings(2);
  s.spp = 64;
  // (u, u^2, 1) with u uniform: means 1/2 and 1/3 (variances 1/12 and 4/45), and exactly 1.
  const Image image = render_sample_mean(s, [](int, int, Pcg32& rng) {
    const float u = rng.next_float();
    return glm::vec3(u, u * u, 1.0f);
  });
  ASSERT_EQ(image.channels, 3);
  double mean_u = 0, mean_u2 = 0;
  for (size_t p = 0; p < image.pixel_count(); ++p) {
    mean_u += image.pixels[3 * p];
    mean_u2 += image.pixels[3 * p + 1];
    EXPECT_EQ(image.pixels[3 * p + 2], 1.0f);
  }
  const double n = double(image.pixel_count()) * s.spp;
  mean_u /= double(image.pixel_count());
  mean_u2 /= double(image.pixel_count());
  EXPECT_NEAR(mean_u, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(mean_u2, 1.0 / 3.0, 5.0 * std::sqrt(4.0 / 45.0 / n));
}

TEST(PixelRenderer, RejectsBadSettingsNamingThem) {
  auto nothing = [](int, int, uint32_t, Pcg32&, float*) {};
  PixelRenderSettings s = small_settings(1);
  s.width = 0;
  EXPECT_THROW(render_pixels(s, 1, nothing), UserError);
  s = small_settings(1);
  s.spp = 0;
  try {
    render_pixels(s, 1, nothing);
    FAIL() << "spp = 0 accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("spp"), std::string::npos);
  }
  s = small_settings(-1);
  EXPECT_THROW(render_pixels(s, 1, nothing), UserError);
}

TEST(PixelRenderer, RethrowsTheEstimatorsException) {
  EXPECT_THROW(render_pixels(small_settings(2), 1,
                             [](int x, int y, uint32_t, Pcg32&, float*) {
                               if (x == 20 && y == 10) throw std::runtime_error("boom");
                             }),
               std::runtime_error);
}

TEST(ProgressDisplay, ShowsPercentageAndEtaThenEndsTheLine) {
  std::ostringstream out;
  ProgressDisplay progress("AO", &out, /*delay_seconds=*/0.0, /*interval_seconds=*/0.0);
  progress.update(0.5);
  EXPECT_NE(out.str().find("\rAO:  50.0%  ETA"), std::string::npos) << out.str();
  progress.finish();
  EXPECT_NE(out.str().find("100.0%"), std::string::npos);
  EXPECT_EQ(out.str().back(), '\n');
}

TEST(ProgressDisplay, StaysSilentForShortRendersAndWhenDisabled) {
  std::ostringstream out;
  ProgressDisplay quick("AO", &out, /*delay_seconds=*/3600.0);
  quick.update(0.5);
  quick.finish();
  EXPECT_TRUE(out.str().empty());
  ProgressDisplay disabled("AO", nullptr, 0.0, 0.0);
  disabled.update(0.5);  // must not crash
  disabled.finish();
}

}  // namespace
}  // namespace ldm
