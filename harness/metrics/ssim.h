#pragma once
// Structural similarity of one channel (Wang et al. 2004), computed the way
// skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5,
// use_sample_covariance=False, data_range=1.0) computes it (scikit-image 0.19, scipy.ndimage):
//
//   window   Gaussian, sigma 1.5, truncated at 3.5 sigma -> radius 5 (11 taps), weights
//            exp(-x^2 / (2 sigma^2)) normalised to sum 1, applied separably;
//   borders  scipy.ndimage 'reflect' mode: (d c b a | a b c d | d c b a);
//   moments  ux = G*x, uy = G*y, vx = G*(x x) - ux^2, vy = G*(y y) - uy^2,
//            vxy = G*(x y) - ux uy  (population, not sample, covariances);
//   SSIM     ((2 ux uy + C1)(2 vxy + C2)) / ((ux^2 + uy^2 + C1)(vx + vy + C2)),
//            C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1 (the inputs are expected in [0, 1]);
//   mean     over the map cropped by the window radius (5 pixels) on every side.
//
// Everything is in double precision.
#include <array>
#include <cstddef>
#include <vector>

namespace ldm {

inline constexpr int kSsimWindowRadius = 5;
inline constexpr int kSsimWindowSize = 2 * kSsimWindowRadius + 1;

// One channel of an image as a dense row-major plane of doubles.
struct Plane {
  int width = 0, height = 0;
  std::vector<double> values;

  double at(int x, int y) const { return values[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

struct ChannelSsim {
  double mean = 0.0;        // mean of `map` over the image cropped by kSsimWindowRadius
  std::vector<double> map;  // per-pixel SSIM, full size, row-major
};

// The 11 normalised Gaussian weights (sigma 1.5) of the SSIM window, centre at index 5.
std::array<double, kSsimWindowSize> ssim_window_weights();

// Separable Gaussian filter of the SSIM window with 'reflect' borders. The plane must be at
// least kSsimWindowSize pixels in each dimension (a single reflection then covers the window).
Plane ssim_window_filter(const Plane& plane);

// SSIM of two planes of the same size, each at least kSsimWindowSize x kSsimWindowSize.
// Identical planes give exactly 1 everywhere (see the comment in the implementation).
// Throws UserError for planes that are too small or differ in size (compare_images checks
// first, with a message naming the images).
ChannelSsim channel_ssim(const Plane& reference, const Plane& test);

}  // namespace ldm
