// compare_images' SSIM against an independent implementation: scikit-image's
// structural_similarity, run by tests/metrics/skimage_ssim.py on the same pixels.
//
// Tolerances, derived rather than tuned: both sides compute in double from the same float32
// inputs, so they differ only in summation order. Each filtered moment is then off by a few
// 1e-16; the worst amplification is the variance uxx - ux^2 entering a denominator next to
// C2 = 9e-4, about 1e3, so SSIM values agree to ~1e-12. MSSIM is compared within 1e-9.
// The SSIM map is stored as float, whose rounding of a value in [-1, 1] is at most
// 2^-24 ~ 6e-8, so map pixels are compared within 1e-7. Any real difference in the
// algorithm (window, constants, borders, crop, covariance normalisation) is far larger.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "harness/metrics/image_metrics.h"
#include "metrics/test_images.h"
#include "support/test_support.h"

namespace ldm {
namespace {

using test::make_image;
using test::noise_image;

constexpr double kMssimTolerance = 1e-9;
constexpr double kMapTolerance = 1e-7;

struct OracleResult {
  double mssim = std::nan("");
  std::vector<double> per_channel;
  std::map<std::pair<int, int>, double> pixels;  // (x, y) -> SSIM averaged over channels
};

// The Python script reads float32 little-endian; Image stores native floats.
static_assert(std::endian::native == std::endian::little, "raw dumps assume little-endian");

void write_raw(const std::string& path, const Image& image) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(image.pixels.data()),
            std::streamsize(image.pixels.size() * sizeof(float)));
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// Border pixels (reflected windows), the first fully interior ones, and the centre.
std::vector<std::pair<int, int>> probe_pixels(int width, int height) {
  auto coordinates = [](int n) {
    return std::set<int>{0, 1, 4, 5, n / 2, n - 6, n - 5, n - 2, n - 1};
  };
  std::vector<std::pair<int, int>> pixels;
  for (int y : coordinates(height))
    for (int x : coordinates(width)) pixels.emplace_back(x, y);
  return pixels;
}

OracleResult run_skimage(const Image& reference, const Image& test, double exposure,
                         const std::vector<std::pair<int, int>>& pixels) {
  OracleResult result;
  const std::string dir = ldm::test::make_temp_dir("ldm-ssim-oracle");
  const std::string reference_path = dir + "/reference.raw", test_path = dir + "/test.raw";
  write_raw(reference_path, reference);
  write_raw(test_path, test);

  std::ostringstream command;
  command.precision(17);
  command << LDM_PYTHON << " " << quoted(std::string(LDM_TEST_SOURCE_DIR) + "/metrics/skimage_ssim.py")
          << " " << quoted(reference_path) << " " << quoted(test_path) << " " << reference.width
          << " " << reference.height << " " << reference.channels << " " << exposure;
  for (const auto& [x, y] : pixels) command << " " << x << "," << y;
  std::string output;
  const int status = ldm::test::run_command(command.str(), &output);
  std::filesystem::remove_all(dir);
  // Not a skip: CI installs numpy, scipy and scikit-image (scripts/setup.sh), so a missing
  // module is a broken environment that must be visible.
  EXPECT_EQ(status, 0) << "the skimage oracle failed (" << command.str() << "):\n" << output;
  if (status != 0) return result;

  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "mssim") {
      fields >> result.mssim;
    } else if (kind == "channel") {
      int c;
      double value;
      fields >> c >> value;
      result.per_channel.push_back(value);
    } else if (kind == "pixel") {
      int x, y;
      double value;
      fields >> x >> y >> value;
      result.pixels[{x, y}] = value;
    }
  }
  EXPECT_EQ(result.pixels.size(), pixels.size()) << "unexpected oracle output:\n" << output;
  EXPECT_EQ(result.per_channel.size(), size_t(reference.channels)) << output;
  return result;
}

void expect_matches_skimage(const Image& reference, const Image& test, double exposure) {
  MetricOptions options;
  options.ssim_exposure = exposure;
  const ImageComparison ours = compare_images(reference, test, options);
  const auto pixels = probe_pixels(reference.width, reference.height);
  const OracleResult oracle = run_skimage(reference, test, exposure, pixels);
  if (oracle.pixels.empty()) return;  // run_skimage has already failed the test

  EXPECT_NEAR(ours.mssim, oracle.mssim, kMssimTolerance);
  for (size_t c = 0; c < oracle.per_channel.size(); ++c)
    EXPECT_NEAR(ours.ssim_per_channel.at(c), oracle.per_channel[c], kMssimTolerance)
        << "channel " << c;
  for (const auto& [xy, value] : oracle.pixels)
    EXPECT_NEAR(ours.ssim_map.at(xy.first, xy.second), value, kMapTolerance)
        << "SSIM map pixel (" << xy.first << ", " << xy.second << ")";
  // The pairs are chosen to be clearly imperfect: agreeing on SSIM 1 would prove little.
  EXPECT_LT(oracle.mssim, 0.99);
}

TEST(SsimOracle, NoisyGradient) {
  const Image reference = make_image(64, 48, 1, [](int x, int, int) {
    return 0.1f + 0.8f * float(x) / 63.0f;
  });
  const Image noise = noise_image(64, 48, 1, -0.1f, 0.1f, 11);
  Image test = reference;
  for (size_t i = 0; i < test.pixels.size(); ++i) test.pixels[i] += noise.pixels[i];
  expect_matches_skimage(reference, test, 1.0);
}

TEST(SsimOracle, BlurredImage) {
  const Image reference = make_image(48, 40, 1, [](int x, int y, int) {
    return 0.5f + 0.4f * std::sin(0.7f * float(x)) * std::cos(0.45f * float(y));
  });
  // 3x3 box blur with clamped edges.
  const Image test = make_image(48, 40, 1, [&](int x, int y, int) {
    float sum = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        sum += reference.at(std::clamp(x + dx, 0, 47), std::clamp(y + dy, 0, 39));
    return sum / 9.0f;
  });
  expect_matches_skimage(reference, test, 1.0);
}

TEST(SsimOracle, ShiftedCheckerboard) {
  auto checker = [](int shift_x, int shift_y) {
    return [=](int x, int y, int) {
      return ((x + shift_x) / 4 + (y + shift_y) / 4) % 2 == 0 ? 0.9f : 0.1f;
    };
  };
  expect_matches_skimage(make_image(50, 30, 1, checker(0, 0)), make_image(50, 30, 1, checker(2, 1)),
                         1.0);
}

TEST(SsimOracle, ThreeChannelHdrWithExposure) {
  // Values in [-0.3, 2.5] scaled by 0.6: some clamp at 0, some at 1, most in between; the
  // channels differ so the per-channel results differ.
  const Image reference = make_image(37, 23, 3, [](int x, int y, int c) {
    return -0.3f + 2.8f * float((x * (c + 1) + 3 * y) % 17) / 16.0f;
  });
  const Image noise = noise_image(37, 23, 3, -0.4f, 0.4f, 5);
  Image test = reference;
  for (size_t i = 0; i < test.pixels.size(); ++i)
    test.pixels[i] = 0.9f * test.pixels[i] + noise.pixels[i] * float(i % 3 + 1);
  expect_matches_skimage(reference, test, 0.6);
}

TEST(SsimOracle, TallImageMostlyClamped) {
  const Image reference = noise_image(23, 37, 1, 0.0f, 0.8f, 3);
  const Image test = make_image(23, 37, 1, [&](int x, int y, int) {
    return reference.at(x, y) * 0.7f + 0.05f * float(y % 5);
  });
  expect_matches_skimage(reference, test, 2.5);
}

TEST(SsimOracle, SmallestImageHasOneInteriorPixel) {
  // 11x11: the crop leaves exactly one pixel, so MSSIM is that pixel's SSIM.
  const Image reference = noise_image(11, 11, 1, 0.0f, 1.0f, 21);
  const Image test = noise_image(11, 11, 1, 0.0f, 1.0f, 22);
  expect_matches_skimage(reference, test, 1.0);
}

}  // namespace
}  // namespace ldm
