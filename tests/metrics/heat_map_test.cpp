// heat_map: viridis false colour, linear output that write_png's sRGB encoding turns back into
// the ramp's colours.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "harness/metrics/heat_map.h"
#include "metrics/test_images.h"

namespace ldm {
namespace {

using test::expect_user_error;

// The encoding write_png applies (harness/image/image.cpp), in double.
double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::array<double, 3> encoded_colour(const Image& image, int x) {
  return {srgb_encode(image.at(x, 0, 0)), srgb_encode(image.at(x, 0, 1)),
          srgb_encode(image.at(x, 0, 2))};
}

// Float storage of the linear value and the round trip through the sRGB curve keep the
// encoded colour within ~1e-6 of matplotlib's table (6 decimals).
constexpr double kColourTolerance = 2e-6;

void expect_colour(const std::array<double, 3>& actual, const std::array<double, 3>& expected) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[size_t(c)], expected[size_t(c)], kColourTolerance) << c;
}

TEST(HeatMap, EndsAndMiddleAreViridis) {
  // Values 0, 2 (half of max 4), 4, 9 (above max: clamps) and -3 (below 0: clamps).
  Image values(5, 1, 1);
  values.at(0, 0) = 0.0f;
  values.at(1, 0) = 2.0f;
  values.at(2, 0) = 4.0f;
  values.at(3, 0) = 9.0f;
  values.at(4, 0) = -3.0f;
  const Image colours = heat_map(values, 4.0);
  ASSERT_EQ(colours.width, 5);
  ASSERT_EQ(colours.channels, 3);
  const std::array<double, 3> first{0.267004, 0.004874, 0.329415};  // matplotlib viridis(0)
  const std::array<double, 3> middle{0.127568, 0.566949, 0.550556};  // viridis(0.5)
  const std::array<double, 3> last{0.993248, 0.906157, 0.143936};    // viridis(1)
  expect_colour(encoded_colour(colours, 0), first);
  expect_colour(encoded_colour(colours, 1), middle);
  expect_colour(encoded_colour(colours, 2), last);
  expect_colour(encoded_colour(colours, 3), last);
  expect_colour(encoded_colour(colours, 4), first);
}

TEST(HeatMap, LuminanceIncreasesAlongTheRamp) {
  // A perceptually ordered ramp: brighter means larger, so luminance must rise strictly.
  Image ramp(256, 1, 1);
  for (int x = 0; x < 256; ++x) ramp.at(x, 0) = float(x) / 255.0f;
  const Image colours = heat_map(ramp, 1.0);
  double previous = -1.0;
  for (int x = 0; x < 256; ++x) {
    const double luminance = 0.2126 * colours.at(x, 0, 0) + 0.7152 * colours.at(x, 0, 1) +
                             0.0722 * colours.at(x, 0, 2);
    EXPECT_GT(luminance, previous) << "at ramp position " << x;
    previous = luminance;
  }
}

TEST(HeatMap, RejectsBadInput) {
  expect_user_error([] { heat_map(Image(4, 4, 3), 1.0); }, {"1 channel", "4x4x3"});
  expect_user_error([] { heat_map(Image(4, 4, 1), 0.0); }, {"max_value"});
  expect_user_error([] { heat_map(Image(4, 4, 1), std::numeric_limits<double>::infinity()); },
                    {"max_value"});
  Image with_nan(4, 4, 1);
  with_nan.at(2, 3) = std::numeric_limits<float>::quiet_NaN();
  expect_user_error([&] { heat_map(with_nan, 1.0); }, {"x=2, y=3"});
}

}  // namespace
}  // namespace ldm
