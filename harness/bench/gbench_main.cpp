// Google Benchmark front end: one benchmark per (pass, scene, structure, N, R_LDM), named
// "<pass>/<scene>/<structure>/N:<n>/R:<r>" (unique per pass, so compare.py never pools two
// passes), each running the frames of `ldmbench run` through the same measure()
// (harness/measuring/measurement.h): --ldm_warmup frames judged and discarded, then exactly
// --ldm_frames measured frames, one per iteration (fixed iterations). Sizing, trace, d_max and
// every other axis of `ldmbench run` are flags here too, from the same declarations.
//
// Each iteration is timed with ldmbench's own timer (GL timestamps on GPUs, a fenced wall
// clock on software rasterisers; see harness/measure/gpu_timer.h) and reported as manual
// time: Google Benchmark's time column is the *mean* frame time over the iterations. Every
// sub-pass (and the sums build, pass, frame) is a counter holding the *median* over the
// frames, in ms: what `ldmbench run` records. Repetitions are Google Benchmark's own
// (--benchmark_repetitions=K with its mean/median/stddev/cv aggregates and compare.py's U
// test over them); each repetition measures in a fresh GL context, as `ldmbench run
// --repetitions` does. Axes come from flags --ldm_<axis>=LIST, one per harness axis
// (harness/settings/harness_axes.h), given before or among Google Benchmark's own:
//   --ldm_scenes=cornell,atrium  --ldm_structures=all  --ldm_passes=all  --ldm_views=32
//   --ldm_r_ldm=128  --ldm_image_size=256x256  --ldm_sizing=oracle  --ldm_frames=10 ...
//   --ldm_param=OWNER:KEY=VALUE (repeatable, as `ldmbench run --param`)
// `ldmbench_gbench --help` lists them with Google Benchmark's flags. A configuration whose
// builds BuildHealth judges invalid (exactly those `ldmbench run` records as "invalid") is
// reported as an error, not as a time; a lossy one is timed, with its fragments_lost counter
// (absent when nothing was lost, as is every counter that is 0).
//
// Debian's libbenchmark is built without NDEBUG and says "Library was built as DEBUG" in
// its context: that is the harness library's build type only; ldmbench's own code is built
// Release and the timed work runs on the GPU (or llvmpipe's threads), not in the library.
// The JSON context (--benchmark_format=json) records so (library_build_type_note), with
// ldmbench's build type, version and commit, the device, and every axis's values and
// parameter the benchmarks were registered with (ldm_<axis>, ldm_param).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <map>
#include <optional>
#include <memory>
#include <set>
#include <sstream>

#include "harness/records/harness_columns.h"
#include "harness/settings/harness_axes.h"
#include "harness/measuring/measure_configuration.h"
#include "harness/measuring/measurement.h"
#include "harness/run/run_command.h"
#include "harness/gl/egl_context.h"
#include "harness/passes/pass.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/version.h"

namespace {

std::vector<std::string> structure_pass_names() {
  std::vector<std::string> names;
  for (const auto& name : ldm::pass_names())
    if (ldm::make_pass(name, ldm::StructureParams())->requirements().needs_structure) names.push_back(name);
  return names;
}

using namespace ldm;

// The flag of a harness axis: --ldm_<key> (--ldm_views, --ldm_sizing, --ldm_image_size...).
std::string flag_of(const HarnessAxis& axis) { return "--ldm_" + axis.spec.key; }

// What the benchmarks measure: ldmbench run's settings (the same axes, from the same
// declarations), gbench's own defaults, and the axes the user set (named in the benchmarks).
struct Axes {
  RunSettings settings;
  std::set<std::string> given;
  std::optional<std::string> gpu;  // --ldm_gpu=N
};

Axes default_axes() {
  Axes axes;
  RunSettings& s = axes.settings;
  s.scenes = {"cornell", "atrium"};
  s.structures = structure_names();
  // The passes that read a structure: a peer (hbao) has no build to time per structure and
  // is measured by `ldmbench run` alone.
  s.passes = structure_pass_names();
  s.frames = 10;
  return axes;
}

// What an axis accepts, short: its choices, or its range.
std::string domain_text(const AxisSpec& spec) {
  if (spec.kind == AxisKind::Choice) {
    std::vector<std::string> names = axis_choices(spec);
    if (spec.key == "structures") names.push_back("all");
    if (spec.key == "passes") names = structure_pass_names();
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : "|") + n;
    return out;
  }
  if (spec.kind == AxisKind::Bool) return "true|false";
  if (spec.kind == AxisKind::UInt || spec.kind == AxisKind::Real || spec.kind == AxisKind::ImageSize)
    return axis_range_text(spec);
  return "";
}

std::string flags_help() {
  std::string help =
      version_line("ldmbench_gbench") + "\n"
      "ldmbench_gbench: Google Benchmark over ldmbench's configurations.\n"
      "ldmbench's own flags (before or among Google Benchmark's), one per axis of `ldmbench run`\n"
      "(`ldmbench axes` describes each); a comma list is an axis:\n";
  for (const HarnessAxis& axis : harness_axes()) {
    const std::string flag = "  " + flag_of(axis) + "=" + (axis.spec.list ? "LIST" : "VALUE");
    help += flag + std::string(flag.size() < 38 ? 38 - flag.size() : 2, ' ');
    help += axis.spec.display_name();
    if (!axis.spec.unit.empty()) help += " [" + axis.spec.unit + "]";
    if (const std::string domain = domain_text(axis.spec); !domain.empty()) help += " " + domain;
    if (!axis.spec.default_value.empty()) help += " (run's default " + axis.spec.default_value + ")";
    help += "\n";
  }
  help +=
      "  --ldm_param=OWNER:KEY=VALUE         a structure's or pass's parameter, repeatable\n"
      "  --ldm_gpu=N                         the GPU, as ldmbench's --gpu (default: LDM_GPU, else 0)\n"
      "gbench's defaults: scenes cornell,atrium, every structure, every pass that reads one,\n"
      "10 frames. Benchmarks are named <pass>/<scene>/<structure>/N:<n>/R:<r>[/<axis>:<value>\n"
      "for each other axis given]; the time is the mean frame time, the counters <subpass>_ms\n"
      "the medians. Google Benchmark's flags follow.\n\n";
  return help;
}

// Takes the --ldm_* flags out of argv, leaving Google Benchmark's.
Axes parse_axes(int* argc, char** argv) {
  Axes axes = default_axes();
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--ldm_", 0) != 0) {
      argv[kept++] = argv[i];
      continue;
    }
    const auto equals = arg.find('=');
    const std::string flag = arg.substr(0, equals);
    const std::string value = equals == std::string::npos ? std::string() : arg.substr(equals + 1);
    if (flag == "--ldm_gpu") {
      axes.gpu = value;
      continue;
    }
    if (flag == "--ldm_param") {
      const auto colon = value.find(':'), eq = value.find('=');
      if (colon == std::string::npos || eq == std::string::npos || eq < colon + 2 || colon == 0)
        throw UserError("--ldm_param: expected OWNER:KEY=VALUE, got '" + value + "'");
      axes.settings.structure_params[value.substr(0, colon)][value.substr(colon + 1, eq - colon - 1)] =
          value.substr(eq + 1);
      continue;
    }
    const HarnessAxis* axis = nullptr;
    for (const HarnessAxis& a : harness_axes())
      if (flag_of(a) == flag) axis = &a;
    if (!axis) throw UserError("unknown flag " + arg + " (`ldmbench_gbench --help` lists the --ldm_* flags)");
    std::vector<std::string> values;
    for (size_t start = 0;;) {
      const size_t comma = axis->spec.list ? value.find(',', start) : std::string::npos;
      std::string item = value.substr(start, comma == std::string::npos ? comma : comma - start);
      std::vector<std::string> items = {item};
      if (axis->spec.key == "structures" && item == "all") items = structure_names();
      if (axis->spec.key == "passes" && item == "all") items = structure_pass_names();
      for (const auto& it : items) values.push_back(canonical_axis_value(axis->spec, it, flag));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    set_axis_list(axes.settings, *axis, values);
    axes.given.insert(axis->spec.key);
  }
  *argc = kept;
  return axes;
}

// <pass>/<scene>/<structure>/N:<n>/R:<r>, then /<axis>:<value> for the other axes the user
// set and the parameters, so that every configuration's name is unique.
std::string benchmark_name(const Configuration& c, const Axes& axes) {
  std::string name = c.pass + "/" + scene_id_name(c.scene) + "/" + c.structure + "/N:" +
                     std::to_string(c.views) + "/R:" + std::to_string(c.resolution);
  static const std::set<std::string> named = {"scenes", "passes", "structures", "views", "r_ldm",
                                              "image_size", "frames", "warmup"};
  for (const auto& [key, value] : c.values)
    if (!named.count(key) && (axes.given.count(key) || key.find(':') != std::string::npos))
      name += "/" + key + ":" + value;
  return name;
}

std::unique_ptr<HeadlessContext> g_context;
ContextOptions g_context_options = default_context_options();  // --ldm_gpu / LDM_GPU

// The values of an axis the benchmarks use, comma-joined: those given, else gbench's or
// run's default, else its note in parentheses ("(the scene's)").
std::string axis_values_text(const HarnessAxis& axis, const RunSettings& settings) {
  std::vector<std::string> values = axis.get ? axis.get(settings) : std::vector<std::string>();
  if (!axis.get) {
    const auto it = settings.axis_lists.find(axis.spec.key);
    if (it != settings.axis_lists.end()) values = it->second;
  }
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ",") + v;
  if (!out.empty()) return out;
  return axis.spec.default_value.empty() ? "(" + axis.spec.default_note + ")" : axis.spec.default_value;
}

// The JSON context of a run: what was measured, with which build, on which device.
void add_context(const RunSettings& s, const DeviceInfo& device) {
  benchmark::AddCustomContext("ldmbench_version", ldmbench_version());
  benchmark::AddCustomContext("git_commit", git_commit());
  benchmark::AddCustomContext("git_dirty", git_tree_dirty() ? "true" : "false");
  benchmark::AddCustomContext("ldmbench_build_type", LDM_BUILD_TYPE);
  benchmark::AddCustomContext(
      "library_build_type_note",
      "library_build_type is libbenchmark's own (Debian builds it without NDEBUG, hence 'debug' "
      "and its DEBUG warning); ldmbench's code is built as ldmbench_build_type and the timed work "
      "runs on the GL device, so the frame times are not a debug build's");
  benchmark::AddCustomContext("gl_renderer", device.gl_renderer);
  benchmark::AddCustomContext("gl_vendor", device.gl_vendor);
  benchmark::AddCustomContext("gl_version", device.gl_version);
  benchmark::AddCustomContext("glsl_version", device.glsl_version);
  benchmark::AddCustomContext("device_id", device.device_id);
  benchmark::AddCustomContext("gl_driver", device.gl_driver);
  benchmark::AddCustomContext("egl_platform", device.egl_platform + " (" + device.egl_vendor + ")");
  benchmark::AddCustomContext("timer", timer_source_name(default_timer_source(device.gl_renderer)));
  for (const HarnessAxis& axis : harness_axes())
    benchmark::AddCustomContext("ldm_" + axis.spec.key, axis_values_text(axis, s));
  std::string params;
  for (const auto& [owner, values] : s.structure_params)
    for (const auto& [key, value] : values) params += (params.empty() ? "" : ";") + owner + ":" + key + "=" + value;
  benchmark::AddCustomContext("ldm_param", params);
}

// One benchmark: a whole configuration's frames through the same measure() as `ldmbench
// run`, every build judged by the same BuildHealth, so a configuration `ldmbench run` marks
// invalid is an error here, never a time.
void run_measurement(benchmark::State& state, const Scene* scene, Configuration config,
                     const RunSettings* settings) {
  try {
    // A fresh context per run of the benchmark: Google Benchmark's repetitions are then
    // independent the way `ldmbench run --repetitions` makes them.
    g_context.reset();
    g_context = HeadlessContext::create(g_context_options);
    MeasurementRequest request = measurement_request(config, *settings, g_context->device());
    // Fixed iterations: exactly the frames asked for, no adaptive stopping.
    request.precision.target = 0;
    request.timer = default_timer_source(g_context->device().gl_renderer);
    request.keep_running = [&state] { return state.KeepRunning(); };
    request.count_work = false;  // Google Benchmark reports times only
    request.on_frame = [&state](const FrameTimes& times) {
      for (const auto& [name, ms] : times)
        if (name == "frame") state.SetIterationTime(ms * 1e-3);
    };
    const Measurement m = measure(*scene, request);
    if (m.status() == BuildStatus::Invalid) {
      state.SkipWithError(("invalid build: " + m.status_detail()).c_str());
      return;
    }
    // Counters that are 0 in every repetition are left out: Google Benchmark's cv aggregate
    // of them is 0/0, which it writes as a NaN that is not JSON (compare.py then fails).
    for (const TimingSummary& s : m.summaries())
      if (s.median > 0) state.counters[s.subpass + "_ms"] = s.median;
    state.counters["fragments"] = m.number(columns::kFragments);
    if (m.count(columns::kFragmentsLost) > 0) state.counters["fragments_lost"] = m.number(columns::kFragmentsLost);
    state.counters["bytes_allocated"] = m.number(columns::kBytesAllocated);
    state.SetLabel(g_context->device().gl_renderer);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") std::cout << flags_help();
  Axes axes;
  std::vector<Configuration> configurations;
  std::map<std::string, Scene> scenes;
  try {
    axes = parse_axes(&argc, argv);
    for (const auto& p : axes.settings.passes)
      if (!make_pass(p, StructureParams())->requirements().needs_structure)
        throw UserError("--ldm_passes: pass '" + p +
                        "' reads no LDM structure; measure it with `ldmbench run`");
    validate_axes(axes.settings);  // the checks of `ldmbench run`, parameters included
    g_context_options.gpu = gpu_request_from_environment(axes.gpu, "--ldm_gpu");
    configurations = expand_configurations(axes.settings);
    for (const auto& scene : axes.settings.scenes) scenes.emplace(scene, load_scene(scene));
  } catch (const UserError& e) {
    std::cerr << "ldmbench_gbench: error: " << e.what() << "\n";
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  try {
    g_context = HeadlessContext::create(g_context_options);
  } catch (const UserError& e) {  // a --ldm_gpu or LDM_GPU no device answers
    std::cerr << "ldmbench_gbench: error: " << e.what() << "\n";
    return 2;
  }
  const DeviceInfo device = g_context->device();
  const RunSettings& s = axes.settings;
  add_context(s, device);
  for (const Configuration& c : configurations)
    benchmark::RegisterBenchmark(benchmark_name(c, axes).c_str(), run_measurement, &scenes.at(c.scene), c, &s)
        ->UseManualTime()
        ->Iterations(s.frames)
        ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_context.reset();
  return 0;
}
