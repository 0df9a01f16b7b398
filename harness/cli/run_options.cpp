// `ldmbench run`: the options of a sweep.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "harness/settings/axis_options.h"
#include "harness/settings/harness_axes.h"
#include "harness/settings/run_setting_options.h"
#include "harness/run/run_command.h"
#include "harness/cli/commands.h"
#include "harness/cli/run_options.h"
#include "harness/util/error.h"
#include "harness/passes/pass.h"
#include "harness/util/text.h"
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
  const std::string owner = text.substr(0, colon), key = text.substr(colon + 1, equals - colon - 1);
  auto& params = settings.structure_params[owner];
  // A second --param of one key used to replace the first without a word.
  if (params.count(key))
    throw UserError("--param " + owner + ":" + key + " is given twice (" + params[key] + " and " +
                    text.substr(equals + 1) + "); give several values as one comma list, " + owner +
                    ":" + key + "=" + params[key] + "," + text.substr(equals + 1));
  params[key] = text.substr(equals + 1);
}

// "psppsll: capacity, atomic_reads; ppfla: k; ..." of every declared parameter.
std::string declared_parameters() {
  std::vector<std::string> owners;
  auto add = [&owners](const std::string& owner, const std::vector<AxisSpec>& specs) {
    std::vector<std::string> keys;
    for (const auto& s : specs)
      if (s.pass_parameter.empty()) keys.push_back(s.key);
    if (!keys.empty()) owners.push_back(owner + ": " + joined(keys));
  };
  for (const auto& name : structure_names()) add(name, structure_parameters(name));
  for (const auto& name : pass_names()) add(name, pass_parameters(name));
  std::string out;
  for (const auto& o : owners) out += (out.empty() ? "" : "; ") + o;
  return out;
}

std::string format_g(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

void validate_numbers(const RunOptions& o) {
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
  std::vector<std::string> list_options;
  for (const HarnessAxis& axis : harness_axes()) {
    if (!axis.spec.list || axis.spec.flags.empty()) continue;
    for (size_t start = 0;;) {
      const size_t comma = axis.spec.flags.find(',', start);
      list_options.push_back(axis.spec.flags.substr(start, comma == std::string::npos ? comma : comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    for (const std::string& name : list_options) {
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

void reject_empty_paths(int argc, const char* const* argv) {
  static const char* const kPathOptions[] = {"--out", "--cache-dir", "--scene"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    for (const char* option : kPathOptions) {
      const std::string name = option;
      const bool separate = arg == name && i + 1 < argc;
      const bool joined = arg.rfind(name + "=", 0) == 0;
      if ((separate && std::string(argv[i + 1]).empty()) || (joined && arg.size() == name.size() + 1))
        throw UserError(name + " \"\": an empty path (leave the option out for its default)");
    }
  }
}

void add_run_options(CLI::App* run, RunOptions* o) {
  RunSettings& s = o->settings;
  // Every harness axis's option, from its declaration (harness/settings/harness_axes.cpp).
  add_axis_options(run, o->axes);
  run->add_option("--width", o->width, "Output image width in pixels (with --height: --image-size)")
      ->check(CLI::Range(16, 16384));
  run->add_option("--height", o->height, "Output image height in pixels (with --width: --image-size)")
      ->check(CLI::Range(16, 16384));
  // Every run-wide setting's option, from its declaration (harness/settings/run_setting_table.cpp).
  add_run_setting_options(run, s, o->setting_options);
  run->add_option("--param", o->params,
                  "A structure's or pass's parameter OWNER:KEY=VALUE, repeatable; a comma list "
                  "is an axis (`ldmbench axes` describes each): " + declared_parameters());
  run->add_option("--out", s.out_dir,
                  "Output folder for records.jsonl, records.csv, records.json and images/ "
                  "(default: results/runs/<timestamp>). A folder holding an interrupted run "
                  "of the same command is resumed: finished configurations are kept");
  run->add_flag("--overwrite", s.overwrite,
                "Replace the records and images in --out when they belong to another sweep "
                "(without it such a folder is refused; the same sweep is resumed)");
  run->add_flag("--redo-failed", s.redo_failed,
                "Resuming: measure again the configurations --out holds as failed (else kept)");
  run->add_option("--cache-dir", s.reference.cache_dir,
                  "Reference cache folder (default: $XDG_CACHE_HOME/ldmbench/references, else "
                  "~/.cache/ldmbench/references)");
  run->add_option("--egl-platform", o->platform,
                  "EGL platform: auto (NVIDIA device if present, else Mesa surfaceless), device, "
                  "surfaceless")
      ->check(CLI::IsMember({"auto", "device", "surfaceless"}))
      ->capture_default_str();
  add_gpu_option(run, o->gpu);
  run->add_flag("--gl-debug", s.context.debug_output, "Print OpenGL debug messages");
}

void add_gpu_option(CLI::App* command, GpuOption& gpu) {
  gpu.option = command->add_option(
      "--gpu", gpu.value,
      "The GPU to run on (default: LDM_GPU, else 0). On NVIDIA the CUDA ordinal: 0 is the first "
      "GPU CUDA_VISIBLE_DEVICES leaves visible (a Slurm task's --gres=gpu:1 GPU); elsewhere the "
      "N-th EGL device that makes a context. `ldmbench info` lists the devices");
}

void export_gpu_option(const GpuOption& gpu) {
  if (const auto request = gpu_request_from_environment(gpu.text()))
    ::setenv("LDM_GPU", std::to_string(request->n).c_str(), 1);
}

RunSettings run_settings_from(RunOptions* o) {
  RunSettings& settings = o->settings;
  validate_numbers(*o);
  for (const auto& p : o->params) parse_structure_param(p, settings);
  apply_axis_options(o->axes, settings);
  if (o->width || o->height) {
    if (o->axes.given("image_size"))
      throw UserError("--width/--height and --image-size: give the image size once");
    settings.width = o->width ? o->width : settings.width;
    settings.height = o->height ? o->height : settings.height;
  }
  settings.context.platform = parse_egl_platform(o->platform);
  settings.context.gpu = gpu_request_from_environment(o->gpu.text());
  apply_run_setting_options(o->setting_options, settings);
  return settings;
}

Runner add_run_command(CLI::App& app, const std::string& command_line,
                       const std::vector<std::string>& arguments) {
  auto o = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand(
      "run", "Measure every combination of the given axes (comma lists); write records.csv, "
             "records.json and images");
  add_run_options(run, o.get());
  RunSettings& s = o->settings;
  run->add_option("--calibration", s.calibration,
                  "The run-to-run spread that widens every time interval so that it holds another "
                  "run's median: auto (this machine's cached probe, probed again when older than a "
                  "day or measured at another load; `ldmbench calibrate`), skip (within-run "
                  "intervals, said in each record), or a FILE from `ldmbench calibrate --out` "
                  "(default: LDM_CALIBRATION, else auto)");
  run->add_option("--step", s.step,
                  "Measure only the next repetition of each of these configuration ids "
                  "(ID[,ID...]) and stop (what --isolation process and `ldmbench interleave` run in "
                  "each child)");
  run->add_option("--interleaved-session", s.interleaved_session,
                  "The `ldmbench interleave` session this run belongs to (recorded; compare "
                  "pairs the repetitions of two runs of one session)");
  run->add_flag("--dry-run", s.dry_run, "List the configurations (index, id, image size, frames) and write nothing");
  return [o, command_line, arguments]() {
    return run_benchmark(run_settings_from(o.get()), command_line, arguments, std::cout);
  };
}

}  // namespace ldm::cli
