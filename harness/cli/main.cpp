// ldmbench: benchmark and compare layered-depth-map structures on the GPU.
//   ldmbench run        measure structures x passes x parameters, write records and images
//   ldmbench scenes     list the built-in scenes
//   ldmbench structures list the structures
//   ldmbench info       the OpenGL device ldmbench would run on
#include <CLI/CLI.hpp>

#include <iostream>
#include <sstream>

#include "harness/app/run_command.h"
#include "harness/scene/generators.h"
#include "harness/util/error.h"
#include "ldm_impls/ldm_structure.h"

namespace {

using namespace ldm;

std::string join_args(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) out += (i ? " " : "") + std::string(argv[i]);
  return out;
}

// "structure:key=value" -> settings.structure_params[structure][key] = value
void parse_structure_param(const std::string& text, RunSettings& settings) {
  const auto colon = text.find(':');
  const auto equals = text.find('=', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || equals == std::string::npos || colon == 0 ||
      equals == colon + 1)
    throw UserError("--param: expected STRUCTURE:KEY=VALUE (e.g. psppsll:pool=grow), got '" +
                    text + "'");
  settings.structure_params[text.substr(0, colon)][text.substr(colon + 1, equals - colon - 1)] =
      text.substr(equals + 1);
}

Visibility parse_visibility(const std::string& text) {
  if (text == "scene") return Visibility::Scene;
  if (text == "attenuated") return Visibility::Attenuated;
  if (text == "unattenuated") return Visibility::Unattenuated;
  throw UserError("--visibility: expected scene, attenuated or unattenuated, got '" + text + "'");
}

void add_run_command(CLI::App& app, RunSettings& s, std::vector<std::string>& params,
                     std::vector<std::string>& visibility, std::string& platform,
                     float& normal_offset) {
  auto* run = app.add_subcommand("run", "Measure every combination of the given axes; write "
                                        "records (CSV, JSON) and images");
  run->add_option("--scene", s.scenes,
                  "Built-in scene name (see `ldmbench scenes`) or scene file path; comma list")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--structure", s.structures,
                  "LDM structure(s), comma list: psppsll, ppsll, dfbuffer, habuffer, ppfla, "
                  "psppfla, or `all` (see `ldmbench structures`)")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--pass", s.passes, "Pass(es) run on each structure: ao")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("-N,--views", s.views,
                  "Number of LDM views N (directions of the hemisphere partition); comma list")
      ->delimiter(',')
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  run->add_option("-R,--r-ldm", s.resolutions, "LDM resolution R_LDM (R x R pixels); comma list")
      ->delimiter(',')
      ->check(CLI::Range(1u, 8192u))
      ->capture_default_str();
  run->add_option("--width", s.width, "Output image width in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  run->add_option("--height", s.height, "Output image height in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  run->add_option("--d-max", s.d_max,
                  "AO attenuation distance d_max in scene units (default: the scene's); comma list")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  run->add_option("--visibility", visibility,
                  "AO visibility: attenuated (min(d/d_max,1)^2), unattenuated, or scene (the "
                  "scene file's choice); comma list")
      ->delimiter(',')
      ->check(CLI::IsMember({"scene", "attenuated", "unattenuated"}));
  run->add_option("--normal-offset", normal_offset,
                  "Normal offset of thesis §4.4.2 in LDM pixels (default: the scene's; 0 = off)")
      ->check(CLI::Range(0.0f, 1000.0f));
  run->add_option("--frames", s.frames, "Measured frames per configuration (median reported)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  run->add_option("--warmup", s.warmup, "Warm-up frames discarded before measuring")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  run->add_option("--param", params,
                  "Structure parameter STRUCTURE:KEY=VALUE, repeatable (e.g. psppsll:pool=grow)");
  run->add_option("--out", s.out_dir,
                  "Output folder for records.csv, records.json and images/ (default: "
                  "results/runs/<timestamp>)");
  run->add_flag("!--no-images", s.write_images, "Do not write the AO images");
  run->add_option("--egl-platform", platform,
                  "EGL platform: auto (NVIDIA device if present, else Mesa surfaceless), device, "
                  "surfaceless")
      ->check(CLI::IsMember({"auto", "device", "surfaceless"}))
      ->capture_default_str();
  run->add_flag("--gl-debug", s.context.debug_output, "Print OpenGL debug messages");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ldmbench: benchmark layered-depth-map structures on the GPU"};
  app.require_subcommand(1);
  RunSettings settings;
  std::vector<std::string> params, visibility;
  std::string platform = "auto";
  float normal_offset = -1.0f;
  add_run_command(app, settings, params, visibility, platform, normal_offset);
  app.add_subcommand("scenes", "List the built-in scenes");
  app.add_subcommand("structures", "List the LDM structures");
  app.add_subcommand("info", "Print the OpenGL device ldmbench runs on");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return kExitUsage;
  }

  try {
    if (app.got_subcommand("scenes")) {
      for (const auto& g : scene_generators()) std::cout << g.name << "\t" << g.description << "\n";
      return kExitOk;
    }
    if (app.got_subcommand("structures")) {
      for (const auto& name : structure_names()) std::cout << name << "\n";
      return kExitOk;
    }
    if (app.got_subcommand("info")) {
      ContextOptions options;
      auto context = HeadlessContext::create(options);
      const DeviceInfo& d = context->device();
      std::cout << "renderer: " << d.gl_renderer << "\nvendor: " << d.gl_vendor
                << "\nversion: " << d.gl_version << "\nglsl: " << d.glsl_version
                << "\negl platform: " << d.egl_platform << " (" << d.egl_vendor << ")"
                << "\nmax storage block: " << d.max_ssbo_block_bytes << " bytes"
                << "\n64-bit atomics: " << (d.has_int64_atomics ? "yes" : "no")
                << "\ntimer queries: " << (d.has_timer_queries ? "yes" : "no") << "\n";
      return kExitOk;
    }
    // run
    for (const auto& p : params) parse_structure_param(p, settings);
    if (!visibility.empty()) {
      settings.visibility.clear();
      for (const auto& v : visibility) settings.visibility.push_back(parse_visibility(v));
    }
    if (normal_offset >= 0.0f) settings.normal_offset_pixels = normal_offset;
    settings.context.platform = parse_egl_platform(platform);
    if (settings.structures.size() == 1 && settings.structures[0] == "all")
      settings.structures = structure_names();
    return run_benchmark(settings, join_args(argc, argv), std::cout);
  } catch (const UserError& e) {
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "ldmbench: failed: " << e.what() << "\n";
    return 1;
  }
}
