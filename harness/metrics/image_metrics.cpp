#include "harness/metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "harness/metrics/image_checks.h"
#include "harness/metrics/ssim.h"
#include "harness/util/error.h"

namespace ldm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void validate_inputs(const Image& reference, const Image& test, const MetricOptions& options) {
  if (!std::isfinite(options.ssim_exposure) || options.ssim_exposure <= 0.0)
    throw UserError("ssim_exposure must be a finite positive number, got " +
                    std::to_string(options.ssim_exposure));
  require_nonempty(reference, "reference");
  require_nonempty(test, "test");
  if (!reference.same_shape(test))
    throw UserError("images differ in shape: reference is " + shape_string(reference) +
                    ", test is " + shape_string(test) + " (width x height x channels)");
  require_finite(reference, "reference");
  require_finite(test, "test");
  if (reference.width < kSsimWindowSize || reference.height < kSsimWindowSize)
    throw UserError("images are " + shape_string(reference) + "; SSIM needs at least " +
                    std::to_string(kSsimWindowSize) + "x" + std::to_string(kSsimWindowSize) +
                    " pixels (its Gaussian window)");
}

double channel_mse(const Image& reference, const Image& test, int c) {
  double sum = 0.0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const double d = double(reference.at(x, y, c)) - double(test.at(x, y, c));
      sum += d * d;
    }
  return sum / double(reference.pixel_count());
}

// sqrt(MSE_c) / range of the reference channel; NaN for a constant reference channel.
double channel_nrmse(const Image& reference, int c, double mse) {
  float lowest = reference.at(0, 0, c), highest = lowest;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      lowest = std::min(lowest, reference.at(x, y, c));
      highest = std::max(highest, reference.at(x, y, c));
    }
  const double range = double(highest) - double(lowest);
  return range > 0.0 ? std::sqrt(mse) / range : kNaN;
}

// Mean of the defined (non-NaN) values; NaN when there are none.
double mean_of_defined(const std::vector<double>& values) {
  double sum = 0.0;
  int count = 0;
  for (double v : values)
    if (!std::isnan(v)) {
      sum += v;
      ++count;
    }
  return count > 0 ? sum / count : kNaN;
}

double mean_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / double(values.size());
}

double psnr(const Image& reference, double mse) {
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  const double peak = *std::max_element(reference.pixels.begin(), reference.pixels.end());
  if (peak <= 0.0) return kNaN;
  return 10.0 * std::log10(peak * peak / mse);
}

// Channel c of the image as SSIM sees it: value * exposure clamped to [0, 1], in double.
Plane exposed_channel(const Image& image, int c, double exposure) {
  Plane plane{image.width, image.height, std::vector<double>(image.pixel_count())};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      plane.values[size_t(y) * size_t(image.width) + size_t(x)] =
          std::clamp(double(image.at(x, y, c)) * exposure, 0.0, 1.0);
  return plane;
}

Image mean_abs_difference(const Image& reference, const Image& test) {
  Image result(reference.width, reference.height, 1);
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      double sum = 0.0;
      for (int c = 0; c < reference.channels; ++c)
        sum += std::abs(double(reference.at(x, y, c)) - double(test.at(x, y, c)));
      result.at(x, y) = float(sum / reference.channels);
    }
  return result;
}

}  // namespace

ImageComparison compare_images(const Image& reference, const Image& test,
                               const MetricOptions& options) {
  validate_inputs(reference, test, options);
  ImageComparison result;
  result.ssim_exposure = options.ssim_exposure;
  const int channels = reference.channels;

  for (int c = 0; c < channels; ++c) {
    const double mse = channel_mse(reference, test, c);
    result.mse_per_channel.push_back(mse);
    result.nrmse_per_channel.push_back(channel_nrmse(reference, c, mse));
  }
  result.mse = mean_of(result.mse_per_channel);
  result.nrmse = mean_of_defined(result.nrmse_per_channel);
  result.psnr = psnr(reference, result.mse);

  std::vector<double> ssim_sum(reference.pixel_count(), 0.0);
  for (int c = 0; c < channels; ++c) {
    const ChannelSsim ssim = channel_ssim(exposed_channel(reference, c, options.ssim_exposure),
                                          exposed_channel(test, c, options.ssim_exposure));
    result.ssim_per_channel.push_back(ssim.mean);
    for (size_t i = 0; i < ssim_sum.size(); ++i) ssim_sum[i] += ssim.map[i];
  }
  result.mssim = mean_of(result.ssim_per_channel);
  result.ssim_map = Image(reference.width, reference.height, 1);
  for (size_t i = 0; i < ssim_sum.size(); ++i)
    result.ssim_map.pixels[i] = float(ssim_sum[i] / channels);

  result.abs_diff = mean_abs_difference(reference, test);
  return result;
}

CoveredComparison compare_covered(const Image& reference, const Image& test,
                                  const ImageComparison& whole, const Image& mask) {
  if (mask.channels != 1 || mask.width != reference.width || mask.height != reference.height ||
      !reference.same_shape(test))
    throw UserError("coverage mask is " + shape_string(mask) + ", the images " +
                    shape_string(reference) + " and " + shape_string(test) +
                    " (expected one channel of the images' size)");
  CoveredComparison out;
  const int channels = reference.channels;
  std::vector<double> squared(size_t(channels), 0.0), lowest(size_t(channels), INFINITY),
      highest(size_t(channels), -INFINITY);
  uint64_t covered = 0;
  double ssim_sum = 0.0;
  uint64_t ssim_pixels = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      if (mask.at(x, y) == 0.0f) continue;
      ++covered;
      for (int c = 0; c < channels; ++c) {
        const double d = double(reference.at(x, y, c)) - double(test.at(x, y, c));
        squared[size_t(c)] += d * d;
        lowest[size_t(c)] = std::min(lowest[size_t(c)], double(reference.at(x, y, c)));
        highest[size_t(c)] = std::max(highest[size_t(c)], double(reference.at(x, y, c)));
      }
      const bool in_crop = x >= kSsimWindowRadius && y >= kSsimWindowRadius &&
                           x < reference.width - kSsimWindowRadius &&
                           y < reference.height - kSsimWindowRadius;
      if (in_crop) {
        ssim_sum += whole.ssim_map.at(x, y);
        ++ssim_pixels;
      }
    }
  if (covered == 0) return {kNaN, kNaN, kNaN};
  std::vector<double> mse(static_cast<size_t>(channels)), nrmse(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    mse[size_t(c)] = squared[size_t(c)] / double(covered);
    const double range = highest[size_t(c)] - lowest[size_t(c)];
    nrmse[size_t(c)] = range > 0.0 ? std::sqrt(mse[size_t(c)]) / range : kNaN;
  }
  out.mse = mean_of(mse);
  out.nrmse = mean_of_defined(nrmse);
  out.mssim = ssim_pixels > 0 ? ssim_sum / double(ssim_pixels) : kNaN;
  return out;
}

double luminance(const Image& image, int x, int y) {
  if (image.channels == 1) return image.at(x, y);
  if (image.channels == 3 || image.channels == 4)
    return 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
  throw UserError("luminance is defined for 1, 3 or 4 channels; the image has " +
                  std::to_string(image.channels));
}

double exposure_for_reference(const Image& reference) {
  require_nonempty(reference, "reference");
  require_finite(reference, "reference");
  if (reference.channels != 1 && reference.channels != 3 && reference.channels != 4)
    throw UserError("exposure_for_reference needs a 1, 3 or 4 channel reference; it has " +
                    std::to_string(reference.channels) + " channels");

  std::vector<double> values;
  values.reserve(reference.pixel_count());
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) values.push_back(luminance(reference, x, y));

  // numpy's 'linear' percentile needs only the two order statistics around the position.
  const double position = 0.99 * double(values.size() - 1);
  const size_t below = size_t(std::floor(position));
  const double fraction = position - double(below);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(below), values.end());
  const double low = values[below];
  double high = low;
  if (below + 1 < values.size())  // the next order statistic is the smallest value above
    high = *std::min_element(values.begin() + std::ptrdiff_t(below) + 1, values.end());
  const double percentile = low + fraction * (high - low);
  return percentile > 0.0 ? 1.0 / percentile : 1.0;
}

}  // namespace ldm
