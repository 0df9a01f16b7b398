// `ldmbench reference`: a path-traced reference image on its own.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <iostream>
#include <memory>

#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/metrics/image_metrics.h"
#include "harness/passes/pass.h"
#include "harness/metrics/image_metrics.h"
#include "harness/reference/convex_single_bounce.h"
#include "harness/reference/lighting_reference.h"
#include "harness/reference/reference_cache.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/scene_loader.h"
#include "harness/reference/ao_reference.h"
#include "harness/util/error.h"

namespace ldm::cli {
namespace {

struct ReferenceOptions {
  std::string scene = "cornell", pass = "ao", out, visibility = "scene";
  std::string kind = "pass";  // the pass's own reference, or a lighting component
  int width = 256, height = 256;
  float d_max = 0;
  ReferenceSettings reference;
};

// The pass parameters these options stand for (the same keys `ldmbench run` hands a pass).
std::map<std::string, std::string> pass_params(const ReferenceOptions& o) {
  std::map<std::string, std::string> params;
  if (o.d_max > 0) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(o.d_max));
    params["d_max"] = text;
  }
  if (o.visibility != "scene") params["visibility"] = o.visibility;
  return params;
}

}  // namespace

Runner add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  auto* cmd = app.add_subcommand("reference", "Render the path-traced (Embree) reference of a "
                                              "pass for a scene's camera");
  cmd->add_option("--scene", o->scene, "Built-in scene name or scene file path")
      ->capture_default_str();
  cmd->add_option("--pass", o->pass, "Pass whose reference to render (see `ldmbench passes`)")
      ->check(CLI::IsMember(pass_names()))
      ->capture_default_str();
  std::vector<std::string> kinds = {"pass"};
  for (const auto& name : lighting_component_names()) kinds.push_back(name);
  kinds.push_back("closed_form");
  cmd->add_option("--kind", o->kind,
                  "What to render: `pass` (the reference --pass is scored against), a "
                  "lighting component of the scene's spot light (direct, single_bounce, "
                  "multi_bounce: outgoing radiance, RGB; see docs/reference/accuracy.md), or "
                  "closed_form: single_bounce without noise by quadrature, for a closed convex "
                  "mesh around the light (closed-sphere as tessellated; docs/measured/indirect.md)")
      ->check(CLI::IsMember(kinds))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "Image width")->check(CLI::Range(1, 16384))->capture_default_str();
  cmd->add_option("--height", o->height, "Image height")->check(CLI::Range(1, 16384))->capture_default_str();
  cmd->add_option("--spp", o->reference.spp.spp_per_half,
                  "Samples per pixel per half (0: double until the noise target)")
      ->check(CLI::Range(0u, 1u << 20))
      ->capture_default_str();
  cmd->add_option("--noise", o->reference.spp.target_noise_mse,
                  "Noise target (expected MSE; for a lighting --kind, of the image times its "
                  "SSIM exposure)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-spp", o->reference.spp.max_spp_per_half,
                  "Cap of the automatic rule, per half")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  cmd->add_option("--seed", o->reference.seed, "Seed (the halves use seed and seed + 1)")
      ->capture_default_str();
  cmd->add_option_function<std::string>(
         "--sampler",
         [o](const std::string& text) { o->reference.ao_sampler = parse_ao_sampler(text, "--sampler"); },
         "AO reference directions: sobol (Owen-scrambled Sobol per pixel, the default) or random "
         "(independent PCG32 numbers, as before issue 21)")
      ->check(CLI::IsMember({"sobol", "random"}));
  cmd->add_option("--d-max", o->d_max, "AO attenuation distance (default: the scene's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--visibility", o->visibility, "attenuated, unattenuated or scene")
      ->check(CLI::IsMember({"scene", "attenuated", "unattenuated"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output EXR path (a PNG is written beside it)")->required();
  cmd->add_option("--cache-dir", o->reference.cache_dir,
                  "Reference cache folder (default: $XDG_CACHE_HOME/ldmbench/references, else "
                  "~/.cache/ldmbench/references)");
  cmd->add_flag("!--no-cache", o->reference.use_cache, "Render even if a cached reference exists");
  return [o]() {
    if (std::filesystem::path(o->out).extension() != ".exr")
      throw UserError("--out: '" + o->out + "' must end in .exr (linear float output)");
    if (o->kind != "pass" && (o->d_max > 0 || o->visibility != "scene"))
      throw UserError("--d-max and --visibility set AO's reference; --kind " + o->kind +
                      " renders the spot light's, which has neither");
    const Scene scene = load_scene(o->scene);
    if (o->kind == "closed_form") {
      const Image image = convex_single_bounce_image(scene, o->width, o->height);
      write_exr(o->out, image);
      const auto png = std::filesystem::path(o->out).replace_extension(".png").string();
      const double exposure = lighting_ssim_exposure(image);
      write_png(png, image, float(exposure));
      const ConvexSingleBounce closed(centred_on_bounding_sphere(scene));
      double sum = 0, sum_sq = 0, lowest = INFINITY, highest = 0;
      size_t covered = 0;
      for (size_t i = 0; i < image.pixel_count(); ++i) {
        const double v = (double(image.pixels[3 * i]) + image.pixels[3 * i + 1] + image.pixels[3 * i + 2]) / 3.0;
        if (v == 0.0) continue;
        ++covered;
        sum += v;
        sum_sq += v * v;
        lowest = std::min(lowest, v);
        highest = std::max(highest, v);
      }
      std::cout << "closed form (tessellated geometry, single bounce): " << o->out << " and " << png << "\n"
                << "covered pixels: " << covered << "\n";
      if (covered) {
        const double mean = sum / double(covered);
        std::cout << "mean " << mean << ", min " << lowest << ", max " << highest << "\n";
        if (const double ideal = closed.ideal_sphere_radiance(); ideal > 0) {
          // rms of (v - ideal) / ideal over the covered pixels
          const double rms = std::sqrt(std::max(0.0, sum_sq / covered - 2 * ideal * mean + ideal * ideal)) / ideal;
          std::cout << "ideal sphere rho^2 Phi / (4 pi^2 R^2): " << ideal << "; mean / ideal - 1: "
                    << mean / ideal - 1.0 << "; rms relative deviation: " << rms << "\n";
        }
      }
      return kExitOk;
    }
    ReferenceResult result;
    double exposure = 1.0;  // of the PNG; radiance has no fixed scale
    if (o->kind == "pass") {
      const auto pass =
          make_pass(o->pass, StructureParams(pass_params(*o), "--pass " + o->pass));
      result = pass->reference(scene, o->width, o->height, o->reference);
    } else {
      result = lighting_reference_for_run(scene, parse_lighting_component(o->kind, "--kind"),
                                          o->width, o->height, o->reference);
      exposure = lighting_ssim_exposure(result.image);
    }
    write_exr(o->out, result.image);
    const auto png = std::filesystem::path(o->out).replace_extension(".png").string();
    write_png(png, result.image, float(exposure));
    MetricOptions metric_options;
    metric_options.ssim_exposure = exposure;
    const ImageComparison noise = compare_images(result.half_a, result.half_b, metric_options);
    std::cout << "reference: " << o->out << " and " << png << "\n"
              << "spp: " << result.spp_total << " (" << result.spp_per_half << " per half)\n"
              << "noise MSE (expected, of the mean): " << result.noise_mse
              << (result.noise_target_met ? "" : "  (target NOT met: raise --max-spp)") << "\n";
    if (o->kind != "pass")
      std::cout << "exposure (SSIM and PNG): " << exposure
                << "; noise MSE x exposure^2 (what --noise bounds): "
                << result.noise_mse * exposure * exposure << "\n";
    std::cout << "noise MSSIM between halves: " << noise.mssim << "\n"
              << "render time: " << result.render_seconds << " s"
              << (result.from_cache ? " (from cache)" : "") << "\n";
    return kExitOk;
  };
}

}  // namespace ldm::cli
