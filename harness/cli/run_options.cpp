// `ldmbench run`: the options of a sweep.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "harness/app/run_command.h"
#include "harness/cli/commands.h"
#include "harness/cli/run_options.h"
#include "harness/util/error.h"
#include "harness/passes/pass.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm::cli {
namespace {

// "structure:key=value" -> settings.structure_params[structure][key] = value
void parse_structure_param(const std::string& text, RunSettings& settings) {
  const auto colon = text.find(':');
  const auto equals = text.find('=', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || equals == std::string::npos || colon == 0 ||
      equals == colon + 1)
    throw UserError("--param: expected STRUCTURE:KEY=VALUE (e.g. ppfla:k=4), got '" +
                    text + "'");
  settings.structure_params[text.substr(0, colon)][text.substr(colon + 1, equals - colon - 1)] =
      text.substr(equals + 1);
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Visibility parse_visibility(const std::string& text) {
  if (text == "attenuated") return Visibility::Attenuated;
  if (text == "unattenuated") return Visibility::Unattenuated;
  return Visibility::Scene;
}


std::string format_g(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

// Numbers are checked after the conversion to the type the run uses (float): CLI11's range
// checks let NaN through, and 1e39 or 1e-50 only become inf or 0 when converted.
void validate_numbers(const RunOptions& o) {
  for (float d : o.settings.d_max)
    if (!(std::isfinite(d) && d > 0.0f))
      throw UserError("--d-max: the value reads as " + format_g(d) +
                      " in a 32-bit float; it must be positive and finite (1.4e-45 to 3.4e38)");
  if (o.normal_offset_option->count() &&
      !(std::isfinite(o.normal_offset) && o.normal_offset >= 0.0f && o.normal_offset <= 1000.0f))
    throw UserError("--normal-offset: " + format_g(o.normal_offset) +
                    " is not a number in [0, 1000]");
  const double noise = o.settings.reference.spp.target_noise_mse;
  if (!(std::isfinite(noise) && noise > 0.0))
    throw UserError("--reference-noise: " + format_g(noise) + " is not a positive number");
  const SppRule& reference = o.settings.reference.spp;
  if (reference.spp_per_half > reference.max_spp_per_half)  // found up front, not per record
    throw UserError("--reference-spp " + std::to_string(reference.spp_per_half) +
                    " exceeds --reference-max-spp " + std::to_string(reference.max_spp_per_half));
}

}  // namespace

void reject_empty_list_items(int argc, const char* const* argv) {
  static const char* const kListOptions[] = {"--scene", "--structure", "--pass", "-N", "--views",
                                             "-R", "--r-ldm", "--d-max", "--visibility",
                                             "--trace", "--ao-estimator", "--sizing"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    for (const char* option : kListOptions) {
      const std::string name = option;
      std::string value;
      if (arg == name && i + 1 < argc)
        value = argv[i + 1];
      else if (arg.rfind(name + "=", 0) == 0)
        value = arg.substr(name.size() + 1);
      else
        continue;
      if (value.empty() || value.front() == ',' || value.back() == ',' ||
          value.find(",,") != std::string::npos)
        throw UserError(name + " '" + value +
                        "': empty item in the comma list (a doubled, leading or trailing comma?)");
    }
  }
}

void add_run_options(CLI::App* run, RunOptions* o) {
  RunSettings& s = o->settings;
  run->add_option("--scene", s.scenes,
                  "Built-in scene name (see `ldmbench scenes`) or scene file path")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--structure", s.structures, "LDM structure(s): " + joined(structure_names()) + ", or all")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--pass", s.passes, "Pass(es) run on each structure: " + joined(pass_names()))
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("-N,--views", s.views,
                  "Number of LDM views N (regions of the hemisphere partition)")
      ->delimiter(',')
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  run->add_option("-R,--r-ldm", s.resolutions, "LDM resolution R_LDM (R x R pixels per view)")
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
                  "AO attenuation distance d_max in scene units (default: the scene's)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  run->add_option("--visibility", o->visibility,
                  "AO visibility: attenuated (min(d/d_max,1)^2), unattenuated, or scene (the "
                  "scene's own choice)")
      ->delimiter(',')
      ->check(CLI::IsMember({"scene", "attenuated", "unattenuated"}));
  run->add_option("--trace", o->traces,
                  "AO trace variant(s): listing5 (thesis Listing 5: nearest fragment is x's own "
                  "surface), interval (split at x's depth; needs --normal-offset >= ~0.7), "
                  "plane (skip x's own plane predicted from the normal; works with offset 0) "
                  "(default: " + ao_trace_name(kDefaultAoTrace) + ")")
      ->delimiter(',')
      ->check(CLI::IsMember(ao_trace_names()));
  run->add_option("--ao-estimator", o->estimators,
                  "AO estimator(s): eq13 (thesis Eq. 13, 2/N sum V|cos|, may exceed 1) or "
                  "normalized (sum V|cos| / sum |cos|) (default: eq13)")
      ->delimiter(',')
      ->check(CLI::IsMember(ao_estimator_names()));
  run->add_option("--sizing", o->sizing,
                  "Sizing policy: previous_frame (default: the last frame's own counters, "
                  "rebuild on overflow, timed), census (a timed counting pass every frame), "
                  "oracle (the untimed census before the run; free, not a renderer's cost), "
                  "budget (a fixed memory budget, overflow counted)")
      ->delimiter(',')
      ->check(CLI::IsMember({"oracle", "census", "previous_frame", "budget"}));
  run->add_option("--sizing-budget-mib", s.sizing_budget_mib,
                  "Memory budget of the budget policy per structure, MiB (all its buffers)")
      ->check(CLI::Range(0.001, 1048576.0));
  run->add_option("--sizing-initial-per-pixel", s.sizing_initial_per_pixel,
                  "previous_frame's first guess: fragments per LDM pixel")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  o->normal_offset_option = run->add_option("--normal-offset", o->normal_offset,
                  "Normal offset of thesis §4.4.2 in LDM pixels (default: the scene's; 0 = off)")
      ->check(CLI::Range(0.0f, 1000.0f));
  run->add_option("--frames", s.frames,
                  "Measured frames per repetition, at least (more until --time-target is met)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  run->add_option("--time-target", s.precision.target,
                  "Measure frames until the 95% interval of the median (order statistics) is "
                  "within this relative half-width for build and frame (0.03: +-3%), or "
                  "--time-cap; 0: exactly --frames")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  run->add_option("--time-cap", s.precision.cap_seconds,
                  "Seconds of measured frames per repetition after which it stops, target "
                  "met or not (a miss is a warning in status_detail)")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  run->add_option("--max-frames", s.precision.max_frames, "Measured frames per repetition, at most")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  run->add_option("--isolation", o->isolation,
                  "What keeps repetitions independent: context (a fresh GL context per round, "
                  "in this process) or process (a process of its own per repetition)")
      ->check(CLI::IsMember({"context", "process"}))
      ->capture_default_str();
  run->add_option("--repetitions", s.repetitions,
                  "Independent repetitions of every configuration, each in a fresh GL context, "
                  "round robin over the configurations; the record's interval is then over the "
                  "repetitions (what `ldmbench compare` needs to judge time)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  run->add_option("--warmup", s.warmup, "Warm-up frames discarded before measuring")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  run->add_option("--param", o->params,
                  "Structure parameter STRUCTURE:KEY=VALUE, repeatable (e.g. psppsll:capacity=1000, "
                  "ppfla:k=4, habuffer:load_factor=0.5)");
  run->add_option("--out", s.out_dir,
                  "Output folder for records.jsonl, records.csv, records.json and images/ "
                  "(default: results/runs/<timestamp>). A folder holding an interrupted run "
                  "of the same command is resumed: finished configurations are kept");
  run->add_flag("--overwrite", s.overwrite,
                "Replace the records and images in --out when they belong to another sweep "
                "(without it such a folder is refused; the same sweep is resumed)");
  run->add_flag("--redo-failed", s.redo_failed,
                "Resuming: measure again the configurations --out holds as failed (else kept)");
  run->add_flag("!--no-images", s.write_images, "Do not write images");
  run->add_flag("!--no-reference", s.reference.enabled,
                "Skip the path-traced reference and the image metrics");
  run->add_option("--reference-spp", s.reference.spp.spp_per_half,
                  "Reference samples per pixel per half (0: double until the noise target)")
      ->check(CLI::Range(0u, 1u << 20))
      ->capture_default_str();
  run->add_option("--reference-noise", s.reference.spp.target_noise_mse,
                  "Noise target of the automatic spp rule: the reference's expected MSE")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  run->add_option("--reference-max-spp", s.reference.spp.max_spp_per_half,
                  "Cap of the automatic spp rule (samples per pixel per half)")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  run->add_option("--reference-seed", s.reference.seed, "Seed of the reference (halves: s, s+1)")
      ->capture_default_str();
  run->add_option("--cache-dir", s.reference.cache_dir,
                  "Reference cache folder (default: results/cache/references)");
  run->add_option("--egl-platform", o->platform,
                  "EGL platform: auto (NVIDIA device if present, else Mesa surfaceless), device, "
                  "surfaceless")
      ->check(CLI::IsMember({"auto", "device", "surfaceless"}))
      ->capture_default_str();
  run->add_option("--timer", s.timer,
                  "Sub-pass timing: gl_timestamp (GPU timer queries), fenced_wall_clock "
                  "(glFinish around each sub-pass), or auto (wall clock on software "
                  "rasterisers such as llvmpipe, whose timestamps miss most of the work)")
      ->check(CLI::IsMember({"auto", "gl_timestamp", "fenced_wall_clock"}))
      ->capture_default_str();
  run->add_flag("--gl-debug", s.context.debug_output, "Print OpenGL debug messages");
}

RunSettings run_settings_from(RunOptions* o) {
  {
    RunSettings& settings = o->settings;
    validate_numbers(*o);
    for (const auto& p : o->params) parse_structure_param(p, settings);
    if (!o->visibility.empty()) {
      settings.visibility.clear();
      for (const auto& v : o->visibility) settings.visibility.push_back(parse_visibility(v));
    }
    if (!o->traces.empty()) {
      settings.traces.clear();
      for (const auto& t : o->traces) settings.traces.push_back(parse_ao_trace(t));
    }
    if (!o->estimators.empty()) {
      settings.estimators.clear();
      for (const auto& e : o->estimators) settings.estimators.push_back(parse_ao_estimator(e));
    }
    if (o->normal_offset_option->count()) settings.normal_offset_pixels = o->normal_offset;
    if (!o->sizing.empty()) {
      settings.sizing.clear();
      for (const auto& name : o->sizing) settings.sizing.push_back(parse_sizing_policy(name));
    }
    settings.context.platform = parse_egl_platform(o->platform);
    settings.isolation = parse_repetition_isolation(o->isolation);
    if (settings.structures.size() == 1 && settings.structures[0] == "all")
      settings.structures = structure_names();
  }
  return o->settings;
}

Runner add_run_command(CLI::App& app, const std::string& command_line,
                       const std::vector<std::string>& arguments) {
  auto o = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand(
      "run", "Measure every combination of the given axes (comma lists); write records.csv, "
             "records.json and images");
  add_run_options(run, o.get());
  RunSettings& s = o->settings;
  run->add_option("--step", s.step,
                  "Measure only the next repetition of this configuration id and stop (what "
                  "--isolation process and `ldmbench interleave` run in each child)");
  run->add_option("--interleaved-session", s.interleaved_session,
                  "The `ldmbench interleave` session this run belongs to (recorded; compare "
                  "pairs the repetitions of two runs of one session)");
  run->add_flag("--dry-run", s.dry_run, "List the configurations (index, id, image size, frames) and write nothing");
  return [o, command_line, arguments]() {
    return run_benchmark(run_settings_from(o.get()), command_line, arguments, std::cout);
  };
}

}  // namespace ldm::cli
