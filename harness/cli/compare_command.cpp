// `ldmbench compare-images`: MSE, NRMSE, PSNR and MSSIM between any two images.
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/metrics/heat_map.h"
#include "harness/metrics/image_metrics.h"
#include "harness/util/error.h"

namespace ldm::cli {
namespace {

struct CompareOptions {
  std::string reference, test, exposure = "1", ssim_map, diff_map;
  bool json = false;
};

double parse_exposure(const std::string& text, const Image& reference) {
  if (text == "auto") return exposure_for_reference(reference);
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && value > 0) return value;
  } catch (const std::exception&) {
  }
  throw UserError("--exposure: expected a positive number or 'auto', got '" + text + "'");
}

}  // namespace

Runner add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare-images",
                                 "Print MSE, NRMSE, PSNR and MSSIM of TEST against REFERENCE");
  cmd->add_option("reference", o->reference, "Reference image (EXR, PNG, ...)")->required();
  cmd->add_option("test", o->test, "Image to measure")->required();
  cmd->add_option("--exposure", o->exposure,
                  "Scale applied before SSIM's clamp to [0,1]: a number, or auto (the "
                  "reference's 99th-percentile luminance maps to 1)")
      ->capture_default_str();
  cmd->add_option("--ssim-map", o->ssim_map, "Write the SSIM map as a PNG heat map");
  cmd->add_option("--diff-map", o->diff_map, "Write |reference - test| as a PNG heat map");
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  return [o]() {
    const Image reference = read_image(o->reference);
    const Image test = read_image(o->test);
    MetricOptions options;
    options.ssim_exposure = parse_exposure(o->exposure, reference);
    const ImageComparison m = compare_images(reference, test, options);
    if (!o->ssim_map.empty()) write_png(o->ssim_map, heat_map(m.ssim_map, 1.0));
    if (!o->diff_map.empty()) {
      float peak = 0;
      for (float v : m.abs_diff.pixels) peak = std::max(peak, v);
      write_png(o->diff_map, heat_map(m.abs_diff, peak > 0 ? peak : 1.0));
    }
    if (o->json) {
      nlohmann::ordered_json j;
      auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); };
      j["mse"] = number(m.mse);
      j["nrmse"] = number(m.nrmse);
      j["psnr"] = number(m.psnr);
      j["mssim"] = number(m.mssim);
      j["ssim_exposure"] = m.ssim_exposure;
      j["mse_per_channel"] = m.mse_per_channel;
      j["ssim_per_channel"] = m.ssim_per_channel;
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << "mse: " << m.mse << "\nnrmse: " << m.nrmse << "\npsnr: " << m.psnr
                << " dB\nmssim: " << m.mssim << "\nssim exposure: " << m.ssim_exposure << "\n";
    }
    return kExitOk;
  };
}

}  // namespace ldm::cli
