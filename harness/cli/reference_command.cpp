// `ldmbench reference`: a path-traced reference image on its own.
#include <filesystem>
#include <iostream>
#include <memory>

#include "harness/app/run_command.h"
#include "harness/cli/commands.h"
#include "harness/metrics/image_metrics.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"

namespace ldm::cli {
namespace {

struct ReferenceOptions {
  std::string scene = "cornell", pass = "ao", out, cache_dir = kDefaultReferenceCacheDir;
  std::string visibility = "scene";
  int width = 256, height = 256;
  float d_max = 0;
  bool use_cache = true;
  AoReferenceRequest request;
};

}  // namespace

Runner add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  auto* cmd = app.add_subcommand("reference", "Render the path-traced (Embree) reference of a "
                                              "pass for a scene's camera");
  cmd->add_option("--scene", o->scene, "Built-in scene name or scene file path")
      ->capture_default_str();
  cmd->add_option("--pass", o->pass, "Pass whose reference to render: ao")
      ->check(CLI::IsMember({"ao"}))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "Image width")->check(CLI::Range(1, 16384))->capture_default_str();
  cmd->add_option("--height", o->height, "Image height")->check(CLI::Range(1, 16384))->capture_default_str();
  cmd->add_option("--spp", o->request.spp_per_half,
                  "Samples per pixel per half (0: double until the noise target)")
      ->check(CLI::Range(0u, 1u << 20))
      ->capture_default_str();
  cmd->add_option("--noise", o->request.target_noise_mse, "Noise target (expected MSE)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-spp", o->request.max_spp_per_half, "Cap of the automatic rule, per half")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  cmd->add_option("--seed", o->request.seed, "Seed (the halves use seed and seed + 1)")
      ->capture_default_str();
  cmd->add_option("--d-max", o->d_max, "AO attenuation distance (default: the scene's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--visibility", o->visibility, "attenuated, unattenuated or scene")
      ->check(CLI::IsMember({"scene", "attenuated", "unattenuated"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output EXR path (a PNG is written beside it)")->required();
  cmd->add_option("--cache-dir", o->cache_dir, "Reference cache folder")->capture_default_str();
  cmd->add_flag("!--no-cache", o->use_cache, "Render even if a cached reference exists");
  return [o]() {
    if (std::filesystem::path(o->out).extension() != ".exr")
      throw UserError("--out: '" + o->out + "' must end in .exr (linear float output)");
    const Scene scene = load_scene(o->scene);
    AoSettings ao = scene.ao;
    if (o->d_max > 0) ao.d_max = o->d_max;
    if (o->visibility != "scene") ao.attenuated = o->visibility == "attenuated";
    AoReferenceRequest request = o->request;
    request.width = o->width;
    request.height = o->height;
    request.ao = ao;
    const ReferenceResult result = o->use_cache ? cached_ao_reference(scene, request, o->cache_dir)
                                                : render_ao_reference(scene, request);
    write_exr(o->out, result.image);
    const auto png = std::filesystem::path(o->out).replace_extension(".png").string();
    write_png(png, result.image);
    const ImageComparison noise = compare_images(result.half_a, result.half_b, {});
    std::cout << "reference: " << o->out << " and " << png << "\n"
              << "spp: " << result.spp_total << " (" << result.spp_per_half << " per half)\n"
              << "noise MSE (expected, of the mean): " << result.noise_mse
              << (result.noise_target_met ? "" : "  (target NOT met: raise --max-spp)") << "\n"
              << "noise MSSIM between halves: " << noise.mssim << "\n"
              << "render time: " << result.render_seconds << " s"
              << (result.from_cache ? " (from cache)" : "") << "\n";
    return kExitOk;
  };
}

}  // namespace ldm::cli
