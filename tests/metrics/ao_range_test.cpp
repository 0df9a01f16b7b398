// ao_max and ao_fraction_above_1 of the records, on a hand-made image.
#include <gtest/gtest.h>

#include "harness/metrics/ao_range.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

Image make(int w, int h, int channels, std::vector<float> values) {
  Image image;
  image.width = w;
  image.height = h;
  image.channels = channels;
  image.pixels = std::move(values);
  return image;
}

TEST(AoRange, CountsCoveredPixelsOnlyAndFindsTheMaximum) {
  // 2x2: a background pixel holding 5 (must be ignored), 1.25, 1.0 (not above 1), 0.5.
  const Image ao = make(2, 2, 1, {5.0f, 1.25f, 1.0f, 0.5f});
  const Image positions = make(2, 2, 4, {0, 0, 0, 0,  0, 0, 0, 1,  0, 0, 0, 1,  0, 0, 0, 1});
  const AoRange r = ao_range(ao, positions);
  EXPECT_EQ(r.covered, 3u);
  EXPECT_EQ(r.max, 1.25);
  EXPECT_DOUBLE_EQ(r.fraction_above_1, 1.0 / 3.0);
}

TEST(AoRange, NoCoveredPixelGivesZeros) {
  const AoRange r = ao_range(make(1, 1, 1, {2.0f}), make(1, 1, 4, {0, 0, 0, 0}));
  EXPECT_EQ(r.covered, 0u);
  EXPECT_EQ(r.max, 0.0);
  EXPECT_EQ(r.fraction_above_1, 0.0);
}

TEST(AoRange, RejectsMismatchedShapes) {
  EXPECT_THROW(ao_range(make(2, 1, 1, {0, 0}), make(1, 1, 4, {0, 0, 0, 1})), UserError);
}

}  // namespace
}  // namespace ldm
