#pragma once
// The convergence check of a Monte Carlo AO image against the exact AO, shared by the
// reference renderer's tests (tests/reference/ao_analytic_test.cpp) and the GPU peer's
// (tests/peers/rtao_gpu_test.cpp); each names its own arithmetic's rounding and how many
// pixels its closed forms must cover.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "harness/image/image.h"

namespace ldm::test {

struct AoConvergence {
  double rounding;       // the arithmetic's own error, added to each bound (float: 1e-6; GPU: 1e-5)
  double min_coverage;   // the least share of the pixels `expected` must name
};

// The mean of `samples` samples of V in [0, 1] lies within 5 standard errors
// sqrt(AO (1 - AO) / samples) (+ rounding) of the exact AO in every pixel, and is the exact AO
// where the variance is 0 (every sample is it); the sum of the deviations lies within 5 of
// its own standard errors (+ rounding per pixel). `expected(x, y)` is the exact AO of a pixel,
// or nothing to skip it.
inline void expect_ao_converged(const Image& image, uint32_t samples, AoConvergence tolerance,
                                const std::function<std::optional<double>(int, int)>& expected) {
  double deviation_sum = 0.0, variance_sum = 0.0;
  int checked = 0, varying = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto e = expected(x, y);
      if (!e) continue;
      ++checked;
      const double value = image.at(x, y);
      const double variance = std::max(0.0, *e * (1.0 - *e)) / samples;
      if (variance == 0.0) {
        EXPECT_EQ(value, *e) << "pixel " << x << ", " << y;
        continue;
      }
      EXPECT_NEAR(value, *e, 5.0 * std::sqrt(variance) + tolerance.rounding) << "pixel " << x << ", " << y;
      deviation_sum += value - *e;
      variance_sum += variance;
      ++varying;
    }
  EXPECT_GE(checked, image.width * image.height * tolerance.min_coverage) << "too few pixels checked";
  EXPECT_LE(std::abs(deviation_sum), 5.0 * std::sqrt(variance_sum) + tolerance.rounding * varying)
      << "mean deviation " << deviation_sum / std::max(varying, 1);
}

}  // namespace ldm::test
