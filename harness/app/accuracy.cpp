#include "harness/app/accuracy.h"

#include <algorithm>
#include <filesystem>

#include "harness/metrics/heat_map.h"
#include "harness/metrics/image_metrics.h"
#include "harness/reference/ao_reference.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

void append_status_detail(Record& r, const std::string& text) {
  const RecordValue* detail = r.get("status_detail");
  const std::string before = detail ? std::get<std::string>(*detail) : "";
  r.set("status_detail", before.empty() ? text : before + "; " + text);
}

void write_heat_map(const Image& image, double max_value, const AccuracyOutputs& out,
                    const std::string& suffix) {
  const auto path = std::filesystem::path(out.images_dir) / (out.image_stem + suffix + ".png");
  write_png(path.string(), heat_map(image, max_value));
}

}  // namespace

void add_ao_accuracy(Record& r, const Scene& scene, const AoSettings& ao, const Image& image,
                     const ReferenceSettings& settings, const AccuracyOutputs& out) {
  AoReferenceRequest request;
  request.width = image.width;
  request.height = image.height;
  request.ao = ao;
  request.spp_per_half = settings.spp_per_half;
  request.target_noise_mse = settings.target_noise_mse;
  request.max_spp_per_half = settings.max_spp_per_half;
  request.seed = settings.seed;
  const ReferenceResult reference = cached_ao_reference(
      scene, request, settings.cache_dir.empty() ? kDefaultReferenceCacheDir : settings.cache_dir);
  // The noise floor: how far two independent halves of the reference differ.
  const ImageComparison noise = compare_images(reference.half_a, reference.half_b, {});
  r.set("ref_spp", reference.spp_total);
  r.set("ref_noise_mse", reference.noise_mse);
  r.set("ref_noise_mssim", noise.mssim);
  r.set("ref_noise_target_met", reference.noise_target_met);
  r.set("ref_render_seconds", reference.render_seconds);
  r.set("ref_from_cache", reference.from_cache);
  r.set("ref_cache_key", reference.cache_key);
  if (!reference.noise_target_met) {
    // Not an invalid measurement, but its error floor is higher than asked: say so where a
    // reader of the record looks first.
    append_status_detail(r, "reference noise target not met at the spp cap (see ref_noise_mse)");
  }

  ImageComparison metrics;
  try {
    metrics = compare_images(reference.image, image, {});
  } catch (const UserError& e) {
    r.set("metrics_error", e.what());
    r.set("status", "invalid");
    append_status_detail(r, std::string("image not measured: ") + e.what());
    return;
  }
  r.set("mse", metrics.mse);
  r.set("nrmse", metrics.nrmse);
  r.set("psnr", metrics.psnr);
  r.set("mssim", metrics.mssim);
  r.set("ssim_exposure", metrics.ssim_exposure);
  // MSE against the converged image is about mse - ref_noise_mse; below a few times the
  // floor, differences between configurations are noise of the reference.
  r.set("mse_over_noise", reference.noise_mse > 0 ? metrics.mse / reference.noise_mse : INFINITY);

  if (out.write_images) {
    // One file per reference (a sweep shares it), named by its cache key.
    const std::string name = "reference-" + reference.cache_key;
    const auto path = std::filesystem::path(out.images_dir) / name;
    if (!std::filesystem::exists(path.string() + ".exr")) {
      write_exr(path.string() + ".exr", reference.image);
      write_png(path.string() + ".png", reference.image);
    }
    r.set("reference_exr",
          (std::filesystem::relative(out.images_dir, out.out_dir) / (name + ".exr")).string());
    write_heat_map(metrics.ssim_map, 1.0, out, "-ssim");
    r.set("ssim_map_png", (std::filesystem::relative(out.images_dir, out.out_dir) /
                           (out.image_stem + "-ssim.png")).string());
    const float max_diff = *std::max_element(metrics.abs_diff.pixels.begin(),
                                             metrics.abs_diff.pixels.end());
    write_exr((std::filesystem::path(out.images_dir) / (out.image_stem + "-diff.exr")).string(),
              metrics.abs_diff);
    write_heat_map(metrics.abs_diff, max_diff > 0 ? max_diff : 1.0, out, "-diff");
    r.set("diff_png", (std::filesystem::relative(out.images_dir, out.out_dir) /
                       (out.image_stem + "-diff.png")).string());
    r.set("diff_png_max", double(max_diff));
  }
}

}  // namespace ldm
