#pragma once
// Error of a rendered image against a reference: MSE, NRMSE, PSNR (per channel and averaged,
// as in 001_324acdd807aef684.txt §4.1) and SSIM/MSSIM (Wang et al. 2004, as skimage computes
// it). I is the reference, K the test image; both are linear float images of the same shape.
//
// Definitions (c = channel, N = width * height, averages are plain means over channels):
//   MSE_c    = (1/N) sum over pixels of (I - K)^2, on the unclamped linear values
//              (Eq. 4.1); MSE = mean of MSE_c.
//   NRMSE_c  = sqrt(MSE_c) / (max I_c - min I_c), the range of the REFERENCE channel.
//              Eq. 4.2 as extracted from 001 prints MSE / range without the root, but 001's
//              Table 6.1 only fits the root: MSE 902.23 -> NRMSE 0.1458 and MSE 160.79 ->
//              0.0616 both give a range of ~206 with sqrt(MSE), and unrelated ranges without.
//              A constant reference channel (range 0) has no defined NRMSE: NRMSE_c is NaN
//              and that channel is left out of the average; NRMSE is NaN only when every
//              reference channel is constant.
//   PSNR     = 10 log10(peak^2 / MSE), peak = the largest value of the reference over all
//              channels (about 1 for ambient occlusion in [0, 1]; for HDR radiance it is the
//              brightest reference sample). MSE == 0 gives +infinity (checked first, so two
//              identical images always give +infinity); otherwise a reference with
//              peak <= 0 gives NaN.
//   SSIM     per channel on clamp(value * ssim_exposure, 0, 1), computed as
//              skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5,
//              use_sample_covariance=False, data_range=1.0) does (details in ssim.h: 11x11
//              Gaussian window, sigma 1.5, K1 = 0.01, K2 = 0.03, 'reflect' borders);
//              MSSIM_c = mean SSIM over the image cropped by 5 pixels on every side;
//              MSSIM = mean of MSSIM_c. Identical images give exactly 1.
//
// compare_images throws UserError when the shapes differ (naming both), when either image
// holds a NaN or infinity (naming the image and the first such pixel), when the images are
// smaller than 11x11 (the SSIM window) or have no channels, and when ssim_exposure is not a
// finite positive number.
#include <vector>

#include "harness/image/image.h"

namespace ldm {

struct MetricOptions {
  // Both images are multiplied by this, then clamped to [0, 1], before SSIM (only SSIM:
  // MSE, NRMSE and PSNR use the unclamped values). exposure_for_reference gives a good value
  // for HDR references.
  double ssim_exposure = 1.0;
};

struct ImageComparison {
  double mse = 0.0, nrmse = 0.0, psnr = 0.0, mssim = 0.0;  // channel averages
  std::vector<double> mse_per_channel, nrmse_per_channel, ssim_per_channel;
  double ssim_exposure = 1.0;  // the exposure SSIM was computed with
  Image ssim_map;  // per-pixel SSIM averaged over channels; input size, 1 channel, full image
                   // (the border pixels use reflected windows, as in skimage's full map)
  Image abs_diff;  // per-pixel |I - K| averaged over channels; 1 channel, linear, unclamped
};

ImageComparison compare_images(const Image& reference, const Image& test,
                               const MetricOptions& options);

// Luminance used for exposure: for 1 channel the value itself; for 3 or 4 channels the
// Rec. 709 / sRGB luminance 0.2126 R + 0.7152 G + 0.0722 B of the first three (alpha, if
// any, is ignored). Other channel counts throw UserError.
double luminance(const Image& image, int x, int y);

// The errors over the covered pixels alone (mask != 0: where the camera sees a surface), so
// that an object covering a small share of the image is not diluted by background pixels
// both images agree on:
//   MSE     mean over covered pixels and channels of (I - K)^2;
//   NRMSE   per channel sqrt(MSE_c over covered) / (range of I_c over covered), averaged over
//           the channels where that range is not 0 (NaN when it is 0 in every channel);
//   MSSIM   mean of `whole.ssim_map` over the covered pixels inside the crop MSSIM uses
//           (kSsimWindowRadius on every side), so that with every pixel covered it equals
//           `whole.mssim` (to the map's float precision); the SSIM windows still see the neighbouring background.
// NaN for each when no pixel (or no pixel inside the crop, for MSSIM) is covered. `mask`:
// one channel, the images' size (UserError otherwise).
struct CoveredComparison {
  double mse = 0.0, nrmse = 0.0, mssim = 0.0;
};
CoveredComparison compare_covered(const Image& reference, const Image& test,
                                  const ImageComparison& whole, const Image& mask);

// The exposure that maps the reference's 99th-percentile luminance to 1, so that a few hot
// pixels (fireflies, light sources) do not darken the whole image before SSIM's clamp. The
// percentile is numpy's default ('linear'): with the n luminances sorted ascending as L[i],
// position p = 0.99 (n - 1), value L[floor p] + (p - floor p) (L[floor p + 1] - L[floor p]).
// Returns 1 when that luminance is <= 0 (a black reference has nothing to expose).
// Throws UserError for an empty reference, a NaN or infinity, or an unsupported channel count.
double exposure_for_reference(const Image& reference);

}  // namespace ldm
