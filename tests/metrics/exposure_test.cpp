// exposure_for_reference: the reference's 99th-percentile luminance maps to 1.
#include <gtest/gtest.h>

#include <limits>

#include "harness/metrics/image_metrics.h"
#include "metrics/test_images.h"

namespace ldm {
namespace {

using test::expect_user_error;

// Scatters pixel index i to position (i * 7919) mod n: 7919 is prime and does not divide
// 10000, so this is a permutation, and the sorted order is not the storage order.
int scattered(int i, int n) { return int((long long)i * 7919 % n); }

// 100x100 pixels: 9000 dim, 990 mid, 10 very bright (fireflies). The 99th percentile sits at
// sorted position 0.99 * 9999 = 9899.01, inside the mid block (ranks 9000..9989), so any
// percentile definition gives the mid value and the fireflies are ignored.
Image three_level_image(int channels, const float dim[], const float mid[], const float bright[]) {
  Image image(100, 100, channels);
  for (int i = 0; i < 10000; ++i) {
    const float* colour = i < 9000 ? dim : i < 9990 ? mid : bright;
    const int p = scattered(i, 10000);
    for (int c = 0; c < channels; ++c) image.at(p % 100, p / 100, c) = colour[c];
  }
  return image;
}

TEST(Exposure, SingleChannelPercentileMapsToOne) {
  const float dim[] = {0.1f}, mid[] = {0.5f}, bright[] = {20.0f};
  // Luminance 0.5 exactly -> exposure 2 exactly (a mean-based rule would give ~1.2).
  EXPECT_EQ(exposure_for_reference(three_level_image(1, dim, mid, bright)), 2.0);
}

TEST(Exposure, RgbUsesRec709Luminance) {
  // Mid block pure green 0.5: luminance 0.7152 * 0.5 = 0.3576, so the exposure is
  // 1 / 0.3576 = 2.7964...; the channel mean (1/6) or maximum (0.5) would give 6 or 2.
  const float dim[] = {0.1f, 0.1f, 0.1f}, mid[] = {0.0f, 0.5f, 0.0f}, bright[] = {50.0f, 0.0f, 0.0f};
  EXPECT_NEAR(exposure_for_reference(three_level_image(3, dim, mid, bright)), 1.0 / 0.3576, 1e-12);
  // Alpha is ignored: a huge alpha does not change anything.
  const float dim4[] = {0.1f, 0.1f, 0.1f, 1000.0f}, mid4[] = {0.0f, 0.5f, 0.0f, 1000.0f},
              bright4[] = {50.0f, 0.0f, 0.0f, 1000.0f};
  EXPECT_NEAR(exposure_for_reference(three_level_image(4, dim4, mid4, bright4)), 1.0 / 0.3576,
              1e-12);
  // Blue alone, to pin the third weight: (0, 0, 0.5) -> 0.0361.
  const float mid_blue[] = {0.0f, 0.0f, 0.5f};
  const float dim_black[] = {0.0f, 0.0f, 0.0f};
  EXPECT_NEAR(exposure_for_reference(three_level_image(3, dim_black, mid_blue, bright)),
              1.0 / 0.0361, 1e-10);
}

TEST(Exposure, PercentileInterpolatesLikeNumpy) {
  // Values 1..100 (scattered): numpy.percentile(range(1, 101), 99) = 99 + 0.01 * (100 - 99)
  // = 99.01. Nearest-rank definitions would give 99 or 100.
  Image image(100, 1, 1);
  for (int i = 0; i < 100; ++i) image.at(scattered(i, 100), 0) = float(i + 1);
  EXPECT_NEAR(exposure_for_reference(image), 1.0 / 99.01, 1e-15);
}

TEST(Exposure, BlackReferenceKeepsExposureOne) {
  EXPECT_EQ(exposure_for_reference(Image(16, 16, 3, 0.0f)), 1.0);
}

TEST(Exposure, RejectsBadReferences) {
  Image with_nan(16, 16, 1, 0.5f);
  with_nan.at(4, 9) = std::numeric_limits<float>::quiet_NaN();
  expect_user_error([&] { exposure_for_reference(with_nan); }, {"reference", "x=4, y=9"});
  expect_user_error([] { exposure_for_reference(Image(16, 16, 2, 0.5f)); }, {"2 channels"});
  expect_user_error([] { exposure_for_reference(Image()); }, {"empty"});
}

}  // namespace
}  // namespace ldm
