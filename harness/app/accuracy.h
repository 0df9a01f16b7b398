#pragma once
// The accuracy half of a record: the pass's image against a path-traced reference of the
// same scene, camera and AO settings (cached on disk), with the reference's own noise floor
// beside every error so that no difference below it is read as a difference.
#include <string>

#include "harness/app/run_settings.h"
#include "harness/image/image.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

struct AccuracyOutputs {
  std::string out_dir;      // image paths in the record are relative to it
  std::string images_dir;
  std::string image_stem;   // e.g. the configuration id plus the pass
  bool write_images = true;
};

// Adds ref_* (spp, noise MSE and MSSIM between the two halves, render time, cache) and the
// metrics (mse, nrmse, psnr, mssim, mse_over_noise) to `record`, and writes the reference,
// SSIM-map and difference images. An image holding NaN or infinity is not measured: the
// record gets metrics_error and its status becomes "invalid".
void add_ao_accuracy(Record& record, const Scene& scene, const AoSettings& ao, const Image& image,
                     const ReferenceSettings& settings, const AccuracyOutputs& outputs);

}  // namespace ldm
