#include "harness/metrics/ssim.h"

#include <cmath>
#include <string>

#include "harness/util/error.h"

namespace ldm {

namespace {

constexpr double kSigma = 1.5;
constexpr double kC1 = (0.01 * 1.0) * (0.01 * 1.0);  // (K1 L)^2 with data range L = 1
constexpr double kC2 = (0.03 * 1.0) * (0.03 * 1.0);  // (K2 L)^2

// scipy.ndimage 'reflect': the edge sample is repeated, (d c b a | a b c d | d c b a).
// Valid for -n <= i < 2n, which holds because planes are at least one window wide.
int reflect_index(int i, int n) {
  if (i < 0) return -i - 1;
  if (i >= n) return 2 * n - 1 - i;
  return i;
}

void require_window_fits(const Plane& plane, const char* what) {
  if (plane.width < kSsimWindowSize || plane.height < kSsimWindowSize)
    throw UserError(std::string(what) + " is " + std::to_string(plane.width) + "x" +
                    std::to_string(plane.height) + " pixels; SSIM needs at least " +
                    std::to_string(kSsimWindowSize) + "x" + std::to_string(kSsimWindowSize) +
                    " (its Gaussian window)");
}

Plane elementwise_product(const Plane& a, const Plane& b) {
  Plane product{a.width, a.height, std::vector<double>(a.values.size())};
  for (size_t i = 0; i < a.values.size(); ++i) product.values[i] = a.values[i] * b.values[i];
  return product;
}

}  // namespace

std::array<double, kSsimWindowSize> ssim_window_weights() {
  // As scipy's _gaussian_kernel1d: exp(-0.5 / sigma^2 * x^2), divided by the sum.
  std::array<double, kSsimWindowSize> weights{};
  double sum = 0.0;
  for (int i = 0; i < kSsimWindowSize; ++i) {
    const int x = i - kSsimWindowRadius;
    weights[size_t(i)] = std::exp(-0.5 / (kSigma * kSigma) * double(x * x));
    sum += weights[size_t(i)];
  }
  for (double& w : weights) w /= sum;
  return weights;
}

Plane ssim_window_filter(const Plane& plane) {
  require_window_fits(plane, "plane to filter");
  const auto weights = ssim_window_weights();
  const int w = plane.width, h = plane.height, r = kSsimWindowRadius;

  // Along x: each row is copied into a buffer padded by reflection, so the inner loop has
  // no index arithmetic.
  Plane along_x{w, h, std::vector<double>(plane.values.size())};
  std::vector<double> padded(size_t(w + 2 * r));
  for (int y = 0; y < h; ++y) {
    for (int i = -r; i < w + r; ++i) padded[size_t(i + r)] = plane.at(reflect_index(i, w), y);
    double* out = &along_x.values[size_t(y) * size_t(w)];
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int k = 0; k < kSsimWindowSize; ++k) sum += weights[size_t(k)] * padded[size_t(x + k)];
      out[x] = sum;
    }
  }

  // Along y: whole rows are accumulated at once, which keeps memory access sequential.
  Plane result{w, h, std::vector<double>(plane.values.size(), 0.0)};
  for (int y = 0; y < h; ++y) {
    double* out = &result.values[size_t(y) * size_t(w)];
    for (int k = 0; k < kSsimWindowSize; ++k) {
      const double weight = weights[size_t(k)];
      const double* in = &along_x.values[size_t(reflect_index(y + k - r, h)) * size_t(w)];
      for (int x = 0; x < w; ++x) out[x] += weight * in[x];
    }
  }
  return result;
}

ChannelSsim channel_ssim(const Plane& reference, const Plane& test) {
  require_window_fits(reference, "reference plane");
  if (test.width != reference.width || test.height != reference.height)
    throw UserError("SSIM planes differ in size: reference " + std::to_string(reference.width) +
                    "x" + std::to_string(reference.height) + ", test " +
                    std::to_string(test.width) + "x" + std::to_string(test.height));

  const Plane ux = ssim_window_filter(reference);
  const Plane uy = ssim_window_filter(test);
  const Plane uxx = ssim_window_filter(elementwise_product(reference, reference));
  const Plane uyy = ssim_window_filter(elementwise_product(test, test));
  const Plane uxy = ssim_window_filter(elementwise_product(reference, test));

  ChannelSsim result;
  result.map.resize(reference.values.size());
  for (size_t i = 0; i < result.map.size(); ++i) {
    // One product per statement, and numerator and denominator built from the same named
    // terms: for identical planes ux == uy and uxx == uxy == uyy bit for bit, so a1 == b1
    // and a2 == b2 exactly and SSIM is exactly 1, not 0.99999999. (Separate statements also
    // keep a compiler that contracts within an expression from fusing only one side.)
    const double mean_xy = ux.values[i] * uy.values[i];
    const double mean_xx = ux.values[i] * ux.values[i];
    const double mean_yy = uy.values[i] * uy.values[i];
    const double var_x = uxx.values[i] - mean_xx;
    const double var_y = uyy.values[i] - mean_yy;
    const double cov_xy = uxy.values[i] - mean_xy;
    const double a1 = 2.0 * mean_xy + kC1;
    const double a2 = 2.0 * cov_xy + kC2;
    const double b1 = mean_xx + mean_yy + kC1;
    const double b2 = var_x + var_y + kC2;
    const double numerator = a1 * a2;
    const double denominator = b1 * b2;
    result.map[i] = numerator / denominator;
  }

  // skimage averages only where the whole window lies inside the image.
  const int w = reference.width, h = reference.height, r = kSsimWindowRadius;
  double sum = 0.0;
  for (int y = r; y < h - r; ++y)
    for (int x = r; x < w - r; ++x) sum += result.map[size_t(y) * size_t(w) + size_t(x)];
  result.mean = sum / (double(w - 2 * r) * double(h - 2 * r));
  return result;
}

}  // namespace ldm
