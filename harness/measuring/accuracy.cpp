#include "harness/measuring/accuracy.h"

#include <algorithm>
#include <cmath>

#include "harness/metrics/heat_map.h"
#include "harness/records/harness_columns.h"
#include "harness/metrics/image_metrics.h"
#include "harness/util/error.h"

namespace ldm {

using namespace columns;

void append_status_detail(Record& r, const std::string& text) {
  const RecordValue* detail = r.get(kStatusDetail.name);
  const std::string before = detail ? std::get<std::string>(*detail) : "";
  if (before.find(text) != std::string::npos) return;
  r.set(kStatusDetail, before.empty() ? text : before + "; " + text);
}

namespace {

// Every column under a reference's prefix; status and its detail are the record's own.
struct PrefixedRecord {
  Record& r;
  const std::string& prefix;
  template <typename T>
  void set(const Column& column, T value) {
    if (column.name == columns::kStatus.name) r.set(column, value);
    else r.set(prefix + column.name, value);
  }
};

}  // namespace

void add_accuracy(Record& record, const ReferenceResult& reference, const Image& image,
                  const OutputFolder* images, const std::string& stem,
                  const std::string& prefix, double ssim_exposure, const Image* coverage) {
  PrefixedRecord r{record, prefix};
  // The noise floor: how far two independent halves of the reference differ.
  MetricOptions options;
  options.ssim_exposure = ssim_exposure;
  const ImageComparison noise = compare_images(reference.half_a, reference.half_b, options);
  r.set(kRefSpp, reference.spp_total);
  r.set(kRefNoiseMse, reference.noise_mse);
  r.set(kRefNoiseMssim, noise.mssim);
  r.set(kRefNoiseTargetMet, reference.noise_target_met);
  r.set(kRefRenderSeconds, reference.render_seconds);
  r.set(kRefFromCache, reference.from_cache);
  r.set(kRefCacheKey, reference.cache_key);
  if (reference.ray_offset > 0) {
    r.set(kRefRayOffset, reference.ray_offset);
    r.set(kRefRayOffsetOk, reference.ray_offset_warning.empty());
    if (!reference.ray_offset_warning.empty()) append_status_detail(record, reference.ray_offset_warning);
  }
  if (!reference.noise_target_met) {
    // Not an invalid measurement, but its error floor is higher than asked: say so where a
    // reader of the record looks first.
    append_status_detail(record, prefix + "reference noise target not met at the spp cap (see " +
                                     prefix + "ref_noise_mse)");
  }

  ImageComparison metrics;
  try {
    metrics = compare_images(reference.image, image, options);
  } catch (const UserError& e) {
    r.set(kMetricsError, e.what());
    r.set(kStatus, "invalid");
    append_status_detail(record, std::string("image not measured: ") + e.what());
    return;
  }
  r.set(kMse, metrics.mse);
  r.set(kNrmse, metrics.nrmse);
  r.set(kPsnr, metrics.psnr);
  r.set(kMssim, metrics.mssim);
  r.set(kSsimExposure, metrics.ssim_exposure);
  if (coverage && !coverage->pixels.empty()) {
    // Beside the whole image's: a model covering a small share of the image would otherwise
    // have its error diluted by background pixels both images agree on.
    const CoveredComparison covered = compare_covered(reference.image, image, metrics, *coverage);
    r.set(kMseCovered, covered.mse);
    r.set(kNrmseCovered, covered.nrmse);
    r.set(kMssimCovered, covered.mssim);
  }
  // MSE against the converged image is about mse - ref_noise_mse; below a few times the
  // floor, differences between configurations are noise of the reference.
  r.set(kMseOverNoise, reference.noise_mse > 0 ? metrics.mse / reference.noise_mse : INFINITY);
  // The error's systematic part (issue 20): the mean difference over every pixel and
  // channel, whose square is the part of the MSE no amount of averaging removes, and the
  // image's mean over the reference's.
  double difference = 0, reference_sum = 0, image_sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    difference += double(image.pixels[i]) - reference.image.pixels[i];
    reference_sum += reference.image.pixels[i];
    image_sum += image.pixels[i];
  }
  const double bias = image.pixels.empty() ? 0.0 : difference / double(image.pixels.size());
  r.set(kBias, bias);
  r.set(kBiasShare, metrics.mse > 0 ? bias * bias / metrics.mse : 0.0);
  r.set(kMeanRatio, reference_sum > 0 ? image_sum / reference_sum : (image_sum > 0 ? INFINITY : 1.0));
  // The ratio's standard error from the reference's noise alone (the image is deterministic):
  // the reference's mean has variance noise_mse / n with independent pixels and channels.
  if (reference_sum > 0 && !image.pixels.empty())
    r.set(kMeanRatioSe, image_sum / reference_sum *
                               std::sqrt(reference.noise_mse / double(image.pixels.size())) /
                               (reference_sum / double(image.pixels.size())));

  if (images) {
    // One file per reference (a sweep shares it), named by its cache key.
    const std::string name = "reference-" + reference.cache_key;
    if (!images->contains(name + ".exr")) {
      images->write_exr(name + ".exr", reference.image);
      images->write_png(name + ".png", reference.image);
    }
    r.set(kReferenceExr, images->record_path(name + ".exr"));
    r.set(kSsimMapPng, images->write_png(stem + "-ssim.png", heat_map(metrics.ssim_map, 1.0)));
    const float max_diff = *std::max_element(metrics.abs_diff.pixels.begin(),
                                             metrics.abs_diff.pixels.end());
    images->write_exr(stem + "-diff.exr", metrics.abs_diff);
    r.set(kDiffPng, images->write_png(stem + "-diff.png",
                                        heat_map(metrics.abs_diff, max_diff > 0 ? max_diff : 1.0)));
    r.set(kDiffPngMax, double(max_diff));
  }
}

}  // namespace ldm
