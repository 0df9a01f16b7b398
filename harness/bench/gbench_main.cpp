// Google Benchmark front end: one benchmark per (pass, scene, structure, N, R_LDM), named
// "<pass>/<scene>/<structure>/N:<n>/R:<r>" (unique per pass, so compare.py never pools two
// passes), each running the frames of `ldmbench run` through the same measure()
// (harness/app/measurement.h): --ldm_warmup frames judged and discarded, then exactly
// --ldm_frames measured frames, one per iteration (fixed iterations).
//
// Each iteration is timed with ldmbench's own timer (GL timestamps on GPUs, a fenced wall
// clock on software rasterisers; see harness/measure/gpu_timer.h) and reported as manual
// time: Google Benchmark's time column is the *mean* frame time over the iterations. Every
// sub-pass (and the sums build, pass, frame) is a counter holding the *median* over the
// frames, in ms: what `ldmbench run` records. Repetitions are Google Benchmark's own
// (--benchmark_repetitions=K with its mean/median/stddev/cv aggregates and compare.py's U
// test over them); each repetition measures in a fresh GL context, as `ldmbench run
// --repetitions` does. Axes come from these flags, given before or among Google
// Benchmark's own:
//   --ldm_scenes=cornell,atrium  --ldm_structures=all  --ldm_passes=all  --ldm_views=32
//   --ldm_r=128  --ldm_width=256 --ldm_height=256  --ldm_frames=10  --ldm_warmup=2
//   --ldm_param=STRUCTURE:KEY=VALUE (repeatable, as `ldmbench run --param`)
// `ldmbench_gbench --help` lists them with Google Benchmark's flags. A configuration whose
// builds BuildHealth judges invalid (exactly those `ldmbench run` records as "invalid") is
// reported as an error, not as a time; a lossy one is timed, with its fragments_lost counter
// (absent when nothing was lost, as is every counter that is 0).
//
// Debian's libbenchmark is built without NDEBUG and says "Library was built as DEBUG" in
// its context: that is the harness library's build type only; ldmbench's own code is built
// Release and the timed work runs on the GPU (or llvmpipe's threads), not in the library.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "harness/app/measurement.h"
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

struct Axes {
  std::vector<std::string> scenes = {"cornell", "atrium"};
  std::vector<std::string> structures = structure_names();
  // The passes that read a structure: a peer (hbao) has no build to time per structure and
  // is measured by `ldmbench run` alone.
  std::vector<std::string> passes = structure_pass_names();
  std::vector<uint32_t> views = {32};
  std::vector<uint32_t> resolutions = {128};
  int width = 256, height = 256;
  int frames = 10, warmup = 2;
  std::map<std::string, std::map<std::string, std::string>> params;  // structure -> key -> value
};

constexpr const char* kLdmFlagsHelp =
    "ldmbench_gbench: Google Benchmark over ldmbench's configurations.\n"
    "ldmbench's own flags (before or among Google Benchmark's):\n"
    "  --ldm_scenes=LIST       scenes (built-in names or scene files), default cornell,atrium\n"
    "  --ldm_structures=LIST   structures, or all (default)\n"
    "  --ldm_passes=LIST       passes that read a structure, or all (default)\n"
    "  --ldm_views=LIST        N, default 32\n"
    "  --ldm_r=LIST            R_LDM, default 128\n"
    "  --ldm_width=W --ldm_height=H   image size, default 256x256\n"
    "  --ldm_frames=F          measured frames per benchmark (its iterations), default 10\n"
    "  --ldm_warmup=W          warm-up frames before them, default 2\n"
    "  --ldm_param=S:K=V       a structure parameter, repeatable\n"
    "Benchmarks are named <pass>/<scene>/<structure>/N:<n>/R:<r>; the time is the mean frame\n"
    "time, the counters <subpass>_ms the medians. Google Benchmark's flags follow.\n\n";

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<uint32_t> split_numbers(const std::string& flag, const std::string& text) {
  std::vector<uint32_t> out;
  for (const auto& item : split(text)) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(item.c_str(), &end, 10);
    if (*end != '\0' || v == 0 || v > 8192)
      throw UserError(flag + ": '" + item + "' is not a count in [1, 8192]");
    out.push_back(uint32_t(v));
  }
  return out;
}

// Takes the --ldm_* flags out of argv, leaving Google Benchmark's.
Axes parse_axes(int* argc, char** argv) {
  Axes axes;
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) -> const char* {
      const size_t n = std::strlen(flag);
      return arg.compare(0, n, flag) == 0 && arg.size() > n && arg[n] == '=' ? argv[i] + n + 1
                                                                             : nullptr;
    };
    if (const char* v = value("--ldm_scenes")) axes.scenes = split(v);
    else if (const char* v = value("--ldm_structures"))
      axes.structures = std::string(v) == "all" ? structure_names() : split(v);
    else if (const char* v = value("--ldm_passes"))
      axes.passes = std::string(v) == "all" ? structure_pass_names() : split(v);
    else if (const char* v = value("--ldm_views")) axes.views = split_numbers("--ldm_views", v);
    else if (const char* v = value("--ldm_r")) axes.resolutions = split_numbers("--ldm_r", v);
    else if (const char* v = value("--ldm_width")) axes.width = int(split_numbers("--ldm_width", v).at(0));
    else if (const char* v = value("--ldm_height")) axes.height = int(split_numbers("--ldm_height", v).at(0));
    else if (const char* v = value("--ldm_frames")) axes.frames = int(split_numbers("--ldm_frames", v).at(0));
    else if (const char* v = value("--ldm_warmup")) {
      const std::string text = v;
      if (text.empty() || text.size() > 6 || text.find_first_not_of("0123456789") != std::string::npos)
        throw UserError("--ldm_warmup: '" + text + "' is not a count in [0, 999999]");
      axes.warmup = std::stoi(text);
    }
    else if (const char* v = value("--ldm_param")) {
      const std::string text = v;
      const auto colon = text.find(':'), equals = text.find('=');
      if (colon == std::string::npos || equals == std::string::npos || equals < colon + 2 || colon == 0)
        throw UserError("--ldm_param: expected STRUCTURE:KEY=VALUE, got '" + text + "'");
      axes.params[text.substr(0, colon)][text.substr(colon + 1, equals - colon - 1)] =
          text.substr(equals + 1);
    }
    else if (arg.rfind("--ldm_", 0) == 0) throw UserError("unknown flag " + arg);
    else argv[kept++] = argv[i];
  }
  *argc = kept;
  return axes;
}

std::unique_ptr<HeadlessContext> g_context;

// One benchmark: a whole configuration's frames through the same measure() as `ldmbench
// run`, every build judged by the same BuildHealth, so a configuration `ldmbench run` marks
// invalid is an error here, never a time.
void run_measurement(benchmark::State& state, const Scene* scene, std::string structure,
                     std::map<std::string, std::string> params, std::string pass, uint32_t views,
                     uint32_t resolution, const Axes* axes) {
  try {
    // A fresh context per run of the benchmark: Google Benchmark's repetitions are then
    // independent the way `ldmbench run --repetitions` makes them.
    g_context.reset();
    g_context = HeadlessContext::create(default_context_options());
    MeasurementRequest request;
    request.structure = structure;
    request.structure_params = params;
    request.pass = pass;
    request.views = views;
    request.resolution = resolution;
    request.width = axes->width;
    request.height = axes->height;
    request.warmup = axes->warmup;
    request.frames = axes->frames;
    request.timer = default_timer_source(g_context->device().gl_renderer);
    request.keep_running = [&state] { return state.KeepRunning(); };
    request.on_frame = [&state](const FrameTimes& times) {
      for (const auto& [name, ms] : times)
        if (name == "frame") state.SetIterationTime(ms * 1e-3);
    };
    const Measurement m = measure(*scene, request);
    if (m.status == BuildStatus::Invalid) {
      state.SkipWithError(("invalid build: " + m.status_detail).c_str());
      return;
    }
    // Counters that are 0 in every repetition are left out: Google Benchmark's cv aggregate
    // of them is 0/0, which it writes as a NaN that is not JSON (compare.py then fails).
    for (const TimingSummary& s : m.summaries())
      if (s.median > 0) state.counters[s.subpass + "_ms"] = s.median;
    state.counters["fragments"] = double(m.census.fragments);
    if (m.last_build.fragments_lost > 0) state.counters["fragments_lost"] = double(m.last_build.fragments_lost);
    state.counters["bytes_allocated"] = double(m.bytes_allocated());
    state.SetLabel(g_context->device().gl_renderer);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") std::cout << kLdmFlagsHelp;
  Axes axes;
  std::map<std::string, Scene> scenes;
  try {
    axes = parse_axes(&argc, argv);
    for (const auto& s : axes.structures)
      make_structure(s, StructureParams(axes.params[s], "--ldm_param " + s));
    for (const auto& [s, p] : axes.params)
      if (std::find(axes.structures.begin(), axes.structures.end(), s) == axes.structures.end())
        throw UserError("--ldm_param " + s + ":...: structure '" + s + "' is not benchmarked");
    for (const auto& p : axes.passes)
      if (!make_pass(p, StructureParams())->requirements().needs_structure)
        throw UserError("--ldm_passes: pass '" + p +
                        "' reads no LDM structure; measure it with `ldmbench run`");
    for (const auto& scene : axes.scenes) scenes.emplace(scene, load_scene(scene));
  } catch (const UserError& e) {
    std::cerr << "ldmbench_gbench: error: " << e.what() << "\n";
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  g_context = HeadlessContext::create(default_context_options());
  const DeviceInfo device = g_context->device();
  benchmark::AddCustomContext("gl_renderer", device.gl_renderer);
  benchmark::AddCustomContext("gl_version", device.gl_version);
  benchmark::AddCustomContext("timer", timer_source_name(default_timer_source(device.gl_renderer)));
  benchmark::AddCustomContext("ldmbench_version", ldmbench_version());
  benchmark::AddCustomContext("git_commit", git_commit());
  benchmark::AddCustomContext("ldm_frames", std::to_string(axes.frames));
  benchmark::AddCustomContext("ldm_warmup", std::to_string(axes.warmup));
  benchmark::AddCustomContext("ldm_image", std::to_string(axes.width) + "x" + std::to_string(axes.height));
  for (const auto& scene : axes.scenes)
    for (const auto& structure : axes.structures)
      for (const auto& pass : axes.passes)
        for (uint32_t n : axes.views)
          for (uint32_t r : axes.resolutions) {
            const std::string name = pass + "/" + scene + "/" + structure + "/N:" + std::to_string(n) +
                                     "/R:" + std::to_string(r);
            benchmark::RegisterBenchmark(name.c_str(), run_measurement, &scenes.at(scene), structure,
                                         axes.params[structure], pass, n, r, &axes)
                ->UseManualTime()
                ->Iterations(axes.frames)
                ->Unit(benchmark::kMillisecond);
          }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_context.reset();
  return 0;
}
