// The reference's Owen-scrambled Sobol points (harness/reference/sobol_sampler.h): each
// pixel's first 2^k points are a (0, k, 2)-net (one point in every elementary interval), the
// render's contiguous batches extend one net, a point is uniform over scrambles (so a pixel's
// mean is unbiased), and different seeds scramble independently.
#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "harness/reference/sobol_sampler.h"

namespace ldm {
namespace {

// Whether points[first .. first + 2^k) hold one point in each of the 2^k intervals of size
// 2^-j x 2^-(k-j), for every j.
bool is_net(const ScrambledSobol2D& s, uint32_t first, int k) {
  const uint32_t n = 1u << k;
  for (int j = 0; j <= k; ++j) {
    std::set<uint32_t> cells;
    for (uint32_t i = first; i < first + n; ++i) {
      const glm::vec2 p = s.point(i);
      if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f)) return false;
      const uint32_t cx = uint32_t(p.x * float(1u << j)), cy = uint32_t(p.y * float(1u << (k - j)));
      cells.insert(cx << (k - j) | cy);
    }
    if (cells.size() != n) return false;
  }
  return true;
}

TEST(SobolSampler, EveryPowerOfTwoPrefixIsANet) {
  for (uint64_t pixel : {0ull, 1ull, 12345ull})
    for (uint64_t seed : {1ull, 2ull}) {
      const ScrambledSobol2D s(seed, pixel);
      for (int k = 0; k <= 10; ++k) EXPECT_TRUE(is_net(s, 0, k)) << "k " << k << " pixel " << pixel;
    }
}

TEST(SobolSampler, TheRendersBatchesExtendOneNet) {
  // The automatic rule renders [0, 16), then [16, 32), [32, 64), ...: each batch is a net of
  // its own size and every union so far is one.
  const ScrambledSobol2D s(7, 99);
  for (uint32_t start = 16; start <= 512; start *= 2) {
    EXPECT_TRUE(is_net(s, start, int(std::log2(start)))) << "batch at " << start;
    EXPECT_TRUE(is_net(s, 0, int(std::log2(start)) + 1)) << "prefix of " << 2 * start;
  }
}

TEST(SobolSampler, APointIsUniformOverScramblesSoMeansAreUnbiased) {
  // f(x, y) = x y + (x < 0.3): its integral is 0.25 + 0.3. The mean of 8 points of one
  // scramble, averaged over 4000 scrambles (pixels), is within 4 standard errors.
  double sum = 0, sum2 = 0;
  constexpr int kScrambles = 4000;
  for (int pixel = 0; pixel < kScrambles; ++pixel) {
    const ScrambledSobol2D s(3, uint64_t(pixel));
    double mean = 0;
    for (uint32_t i = 0; i < 8; ++i) {
      const glm::vec2 p = s.point(i);
      mean += (double(p.x) * p.y + (p.x < 0.3f ? 1.0 : 0.0)) / 8.0;
    }
    sum += mean;
    sum2 += mean * mean;
  }
  const double mean = sum / kScrambles, variance = sum2 / kScrambles - mean * mean;
  EXPECT_NEAR(mean, 0.55, 4.0 * std::sqrt(variance / kScrambles));
  // And better than independent samples: f's variance is about 0.25, so 8 random points
  // would spread by 0.25 / 8 = 0.031; the stratified ones by far less.
  EXPECT_LT(variance, 0.031 / 4);
}

TEST(SobolSampler, SeedsScrambleIndependently) {
  // Halves A and B (seeds s, s + 1) of the same pixel: their first points are uncorrelated.
  double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  constexpr int kPixels = 4000;
  for (int pixel = 0; pixel < kPixels; ++pixel) {
    const double a = ScrambledSobol2D(1, uint64_t(pixel)).point(0).x;
    const double b = ScrambledSobol2D(2, uint64_t(pixel)).point(0).x;
    sxy += a * b, sx += a, sy += b, sxx += a * a, syy += b * b;
  }
  const double n = kPixels;
  const double correlation = (sxy / n - sx / n * sy / n) /
                             std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  EXPECT_LT(std::abs(correlation), 4.0 / std::sqrt(n)) << correlation;
}

}  // namespace
}  // namespace ldm
