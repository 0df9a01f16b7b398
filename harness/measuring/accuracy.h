#pragma once
// The accuracy half of a record: a pass's image against the path-traced reference of the
// same scene, camera and settings (the pass renders or fetches it, harness/passes/pass.h),
// with the reference's own noise floor beside every error so that no difference below it is
// read as a difference.
#include <string>

#include "harness/image/image.h"
#include "harness/records/output_folder.h"
#include "harness/records/record.h"
#include "harness/reference/reference_image.h"

namespace ldm {

// Adds ref_* (spp, noise MSE and MSSIM between the two halves, render time, cache) and the
// metrics (mse, nrmse, psnr, mssim, mse_over_noise) to `record`; with `images`, writes the
// reference, SSIM-map and difference images named after `image_stem`. An image holding NaN
// or infinity is not measured: the record gets metrics_error and its status becomes
// "invalid".
// Every column name is prefixed with `column_prefix` (a further reference of the pass, e.g.
// "multi_"); SSIM sees both images scaled by `ssim_exposure`. With a non-empty `coverage`
// (Pass::coverage()), the errors over its covered pixels too: mse_covered, nrmse_covered,
// mssim_covered (compare_covered, harness/metrics/image_metrics.h).
void add_accuracy(Record& record, const ReferenceResult& reference, const Image& image,
                  const OutputFolder* images, const std::string& image_stem,
                  const std::string& column_prefix = "", double ssim_exposure = 1.0,
                  const Image* coverage = nullptr);

// Appends `text` to the record's status_detail ("; "-separated) unless it is already there.
void append_status_detail(Record& record, const std::string& text);

}  // namespace ldm
