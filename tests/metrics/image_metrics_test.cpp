// MSE, NRMSE, PSNR and the SSIM edge cases of compare_images, checked against values worked
// out by hand. Pixel values are multiples of 1/8 so that every difference and square is exact
// in float and double: the expected numbers below are exact unless a comment says otherwise.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "harness/metrics/image_metrics.h"
#include "metrics/test_images.h"

namespace ldm {
namespace {

using test::expect_user_error;
using test::make_image;
using test::noise_image;

const MetricOptions kDefaults;

TEST(ImageMetrics, SingleChannelHandComputed) {
  // Reference ((x + y) mod 5) / 4 takes the values 0, 1/4, 1/2, 3/4, 1: range 1, peak 1.
  // The test image is the reference +1/8 and -1/8 on alternate pixels, so its own range
  // (1.25) and peak (1.125) differ from the reference's: using them would change the result.
  const Image reference = make_image(16, 16, 1, [](int x, int y, int) {
    return float((x + y) % 5) / 4.0f;
  });
  const Image test = make_image(16, 16, 1, [&](int x, int y, int) {
    return reference.at(x, y) + ((x + y) % 2 == 0 ? 0.125f : -0.125f);
  });
  const ImageComparison result = compare_images(reference, test, kDefaults);

  // MSE = (1/8)^2 = 1/64 at every pixel.
  EXPECT_EQ(result.mse, 0.015625);
  ASSERT_EQ(result.mse_per_channel.size(), 1u);
  EXPECT_EQ(result.mse_per_channel[0], 0.015625);
  // NRMSE = sqrt(1/64) / (1 - 0) = 1/8.
  EXPECT_EQ(result.nrmse, 0.125);
  // PSNR = 10 log10(1^2 / (1/64)) = 60 log10(2) = 18.06179973983887; log10 is within an ulp
  // or two, hence the 1e-12.
  EXPECT_NEAR(result.psnr, 18.06179973983887, 1e-12);
  // |I - K| = 1/8 everywhere.
  ASSERT_EQ(result.abs_diff.channels, 1);
  for (float v : result.abs_diff.pixels) ASSERT_EQ(v, 0.125f);
}

TEST(ImageMetrics, ThreeChannelsAverageThePerChannelErrors) {
  // Channel 0: reference in {0, 1/4, ..., 1} (range 1), test = reference + 1/8:
  //            MSE 1/64, NRMSE 1/8.
  // Channel 1: reference ((x y) mod 3) / 4 in {0, 1/4, 1/2} (range 1/2), test = reference - 1/4:
  //            MSE 1/16, NRMSE (1/4) / (1/2) = 1/2.
  // Channel 2: reference x mod 3 in {0, 1, 2} (range 2, the peak over all channels), test
  //            equal: MSE 0, NRMSE 0.
  const Image reference = make_image(16, 16, 3, [](int x, int y, int c) {
    if (c == 0) return float((x + y) % 5) / 4.0f;
    if (c == 1) return float((x * y) % 3) / 4.0f;
    return float(x % 3);
  });
  const Image test = make_image(16, 16, 3, [&](int x, int y, int c) {
    const float offsets[3] = {0.125f, -0.25f, 0.0f};
    return reference.at(x, y, c) + offsets[c];
  });
  const ImageComparison result = compare_images(reference, test, kDefaults);

  EXPECT_EQ(result.mse_per_channel, (std::vector<double>{0.015625, 0.0625, 0.0}));
  EXPECT_EQ(result.nrmse_per_channel, (std::vector<double>{0.125, 0.5, 0.0}));
  // MSE = (1/64 + 1/16 + 0) / 3 = 5/192; NRMSE = (1/8 + 1/2 + 0) / 3 = 5/24. Dividing by 3
  // rounds, so compare to within a few ulps.
  EXPECT_DOUBLE_EQ(result.mse, 5.0 / 192.0);
  EXPECT_DOUBLE_EQ(result.nrmse, 5.0 / 24.0);
  // PSNR = 10 log10(2^2 / (5/192)) = 10 log10(153.6) = 21.86391215695493.
  EXPECT_NEAR(result.psnr, 21.86391215695493, 1e-12);
  // Mean |I - K| over channels = (1/8 + 1/4 + 0) / 3 = 1/8, exact in float.
  for (float v : result.abs_diff.pixels) ASSERT_EQ(v, 0.125f);
}

TEST(ImageMetrics, ConstantReferenceChannelHasNoNrmse) {
  // Channel 1 of the reference is constant 1/2 (range 0): its NRMSE is NaN and the average
  // is over channels 0 and 2 only: (1/8 + 1/8) / 2 = 1/8, where including channel 1 as 0
  // would give 1/12. Its MSE (test 3/4: (1/4)^2 = 1/16) still counts.
  const Image reference = make_image(16, 16, 3, [](int x, int y, int c) {
    return c == 1 ? 0.5f : float((x + y) % 5) / 4.0f;
  });
  const Image test = make_image(16, 16, 3, [&](int x, int y, int c) {
    return c == 1 ? 0.75f : reference.at(x, y, c) + 0.125f;
  });
  const ImageComparison result = compare_images(reference, test, kDefaults);
  EXPECT_EQ(result.mse_per_channel[1], 0.0625);
  EXPECT_TRUE(std::isnan(result.nrmse_per_channel[1]));
  EXPECT_EQ(result.nrmse_per_channel[0], 0.125);
  EXPECT_EQ(result.nrmse_per_channel[2], 0.125);
  EXPECT_EQ(result.nrmse, 0.125);
}

TEST(ImageMetrics, AllConstantReferenceGivesNanNrmseButFiniteRest) {
  const Image reference(16, 16, 1, 0.375f);
  const Image test = noise_image(16, 16, 1, 0.0f, 1.0f, 7);
  const ImageComparison result = compare_images(reference, test, kDefaults);
  EXPECT_TRUE(std::isnan(result.nrmse));
  EXPECT_TRUE(std::isfinite(result.mse));
  EXPECT_GT(result.mse, 0.0);
  EXPECT_TRUE(std::isfinite(result.psnr));
  EXPECT_TRUE(std::isfinite(result.mssim));
}

TEST(ImageMetrics, PsnrNeedsAPositivePeakUnlessImagesAreIdentical) {
  // Black reference, grey test: peak 0, MSE 1/64 -> no meaningful PSNR.
  const Image black(16, 16, 1, 0.0f);
  EXPECT_TRUE(std::isnan(compare_images(black, Image(16, 16, 1, 0.125f), kDefaults).psnr));
  // Identical black images: no error at all, +infinity (MSE == 0 is checked first).
  EXPECT_EQ(compare_images(black, black, kDefaults).psnr, std::numeric_limits<double>::infinity());
}

TEST(ImageMetrics, IdenticalImagesAreExactlyPerfect) {
  // HDR values beyond [0, 1] on both sides, and an exposure that is not a power of two, so
  // the clamp and the scaling are exercised; 3 channels so the channel averaging is too.
  const Image image = noise_image(40, 30, 3, -0.2f, 2.5f, 1);
  MetricOptions options;
  options.ssim_exposure = 0.7;
  const ImageComparison result = compare_images(image, image, options);
  EXPECT_EQ(result.mse, 0.0);
  EXPECT_EQ(result.psnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(result.mssim, 1.0);
  EXPECT_EQ(result.ssim_per_channel, (std::vector<double>{1.0, 1.0, 1.0}));
  EXPECT_EQ(result.ssim_exposure, 0.7);
  ASSERT_EQ(result.ssim_map.width, 40);
  ASSERT_EQ(result.ssim_map.height, 30);
  ASSERT_EQ(result.ssim_map.channels, 1);
  for (float v : result.ssim_map.pixels) ASSERT_EQ(v, 1.0f);
  for (float v : result.abs_diff.pixels) ASSERT_EQ(v, 0.0f);

  // A smooth single-channel image at exposure 1.
  const Image gradient = make_image(64, 17, 1, [](int x, int y, int) {
    return 0.01f * float(x) + 0.003f * float(y);
  });
  EXPECT_EQ(compare_images(gradient, gradient, kDefaults).mssim, 1.0);
}

TEST(ImageMetrics, ConstantImagesGiveFiniteSsim) {
  // Both constant: every window has zero variance, so the structure term is C2 / C2 = 1 and
  // SSIM = (2 a b + C1) / (a^2 + b^2 + C1) with C1 = 1e-4. The variances come out as
  // rounding noise of order 1e-17 next to C2 = 9e-4, hence the 1e-12.
  const double a = double(0.2f), b = double(0.6f);
  const double expected = (2 * a * b + 1e-4) / (a * a + b * b + 1e-4);  // ~0.60009997
  const ImageComparison result =
      compare_images(Image(16, 16, 1, 0.2f), Image(16, 16, 1, 0.6f), kDefaults);
  EXPECT_NEAR(result.mssim, expected, 1e-12);
  for (float v : result.ssim_map.pixels) ASSERT_NEAR(v, expected, 1e-7);  // stored as float

  // Black against white: C1 / (1 + C1), tiny but finite.
  const ImageComparison extreme =
      compare_images(Image(16, 16, 1, 0.0f), Image(16, 16, 1, 1.0f), kDefaults);
  EXPECT_NEAR(extreme.mssim, 1e-4 / (1.0 + 1e-4), 1e-15);
  // Black against black: C1/C1 * C2/C2, exactly 1.
  EXPECT_EQ(compare_images(Image(16, 16, 1, 0.0f), Image(16, 16, 1, 0.0f), kDefaults).mssim, 1.0);
}

// The error over the covered pixels (compare_covered): a 16x16 image whose left 4 columns
// are background, identical in both images; the covered pixels differ by +-1/8 or 3/8.
TEST(ImageMetrics, CoveredErrorIsOverTheCoveredPixelsAlone) {
  const Image mask = make_image(16, 16, 1, [](int x, int, int) { return x >= 4 ? 1.0f : 0.0f; });
  const Image reference = make_image(16, 16, 1, [](int x, int y, int) {
    return x < 4 ? 0.0f : float((x + y) % 5) / 4.0f;
  });
  const Image test = make_image(16, 16, 1, [&](int x, int y, int) {
    if (x < 4) return 0.0f;
    return reference.at(x, y) + (y % 2 == 0 ? 0.125f : -0.375f);
  });
  const ImageComparison whole = compare_images(reference, test, kDefaults);
  const CoveredComparison covered = compare_covered(reference, test, whole, mask);
  // Covered: 12 x 16 = 192 pixels, half at (1/8)^2 = 1/64, half at (3/8)^2 = 9/64: the mean is
  // 5/64. Over the whole image the 64 background pixels add nothing: 192/256 x 5/64 = 15/256.
  EXPECT_EQ(covered.mse, 5.0 / 64.0);
  EXPECT_EQ(whole.mse, 15.0 / 256.0);
  // NRMSE: sqrt(5/64) over the reference's range on the covered pixels, 1 - 0.
  EXPECT_DOUBLE_EQ(covered.nrmse, std::sqrt(5.0 / 64.0));
  // MSSIM: the map's mean over covered pixels inside the 5-pixel crop (x in [5, 10], y in
  // [5, 10]: 6 x 6 pixels), by hand from the map.
  double sum = 0;
  for (int y = 5; y <= 10; ++y)
    for (int x = 5; x <= 10; ++x) sum += whole.ssim_map.at(x, y);
  EXPECT_DOUBLE_EQ(covered.mssim, sum / 36.0);
  EXPECT_NE(covered.mssim, whole.mssim);
  // Every pixel covered: the whole image's numbers (the MSSIM to the map's float precision).
  const Image all = make_image(16, 16, 1, [](int, int, int) { return 1.0f; });
  const CoveredComparison every = compare_covered(reference, test, whole, all);
  EXPECT_EQ(every.mse, whole.mse);
  EXPECT_DOUBLE_EQ(every.nrmse, whole.nrmse);
  EXPECT_NEAR(every.mssim, whole.mssim, 1e-6);
  // No pixel covered: nothing to measure.
  const Image none = make_image(16, 16, 1, [](int, int, int) { return 0.0f; });
  EXPECT_TRUE(std::isnan(compare_covered(reference, test, whole, none).mse));
  const Image small = make_image(8, 8, 1, [](int, int, int) { return 1.0f; });
  expect_user_error([&] { compare_covered(reference, test, whole, small); }, {"coverage mask is 8x8x1"});
}

TEST(ImageMetrics, ShapeMismatchNamesBothShapes) {
  expect_user_error([] { compare_images(Image(16, 16, 3), Image(16, 12, 3), kDefaults); },
                    {"reference is 16x16x3", "test is 16x12x3"});
  expect_user_error([] { compare_images(Image(16, 16, 3), Image(16, 16, 1), kDefaults); },
                    {"16x16x3", "16x16x1"});
}

TEST(ImageMetrics, NonFiniteValuesNameImageAndFirstPixel) {
  Image reference(16, 16, 3, 0.5f), test(16, 16, 3, 0.5f);
  test.at(3, 5, 1) = std::numeric_limits<float>::quiet_NaN();
  test.at(9, 9, 0) = std::numeric_limits<float>::quiet_NaN();  // later: must not be named
  expect_user_error([&] { compare_images(reference, test, kDefaults); },
                    {"test image", "x=3, y=5, channel=1"});

  reference.at(12, 2, 2) = std::numeric_limits<float>::infinity();
  reference.at(0, 7, 0) = -std::numeric_limits<float>::infinity();
  expect_user_error([&] { compare_images(reference, test, kDefaults); },
                    {"reference image", "x=12, y=2, channel=2", "inf"});
}

TEST(ImageMetrics, RejectsImagesSmallerThanTheSsimWindow) {
  expect_user_error([] { compare_images(Image(10, 16, 1), Image(10, 16, 1), kDefaults); },
                    {"10x16x1", "11x11"});
  expect_user_error([] { compare_images(Image(16, 10, 1), Image(16, 10, 1), kDefaults); },
                    {"16x10x1", "11x11"});
  expect_user_error([] { compare_images(Image(), Image(), kDefaults); }, {"empty"});
  // The smallest allowed size works.
  EXPECT_EQ(compare_images(Image(11, 11, 1, 0.5f), Image(11, 11, 1, 0.5f), kDefaults).mssim, 1.0);
}

TEST(ImageMetrics, RejectsBadExposure) {
  for (double exposure : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()}) {
    MetricOptions options;
    options.ssim_exposure = exposure;
    expect_user_error([&] { compare_images(Image(16, 16, 1), Image(16, 16, 1), options); },
                      {"ssim_exposure"});
  }
}

}  // namespace
}  // namespace ldm
