// Google Benchmark front end: construction time of every structure and the time of each
// sub-pass of every pass, per (scene, structure, pass, N, R_LDM), in Google Benchmark's
// formats so that its compare.py tool works on the JSON (--benchmark_out=FILE
// --benchmark_out_format=json). Each benchmark runs the frames of `ldmbench run` through
// the same measure() (harness/app/measurement.h), one frame per iteration.
//
// Each iteration is timed with ldmbench's own timer (GL timestamps on GPUs, a fenced wall
// clock on software rasterisers; see harness/measure/gpu_timer.h) and reported as manual
// time. Axes come from these flags, given before or among Google Benchmark's own:
//   --ldm_scenes=cornell,atrium  --ldm_structures=all  --ldm_passes=all  --ldm_views=32
//   --ldm_r=128  --ldm_width=256 --ldm_height=256
//   --ldm_param=STRUCTURE:KEY=VALUE (repeatable, as `ldmbench run --param`)
// A configuration whose builds BuildHealth judges invalid (exactly those `ldmbench run`
// records as "invalid") is reported as an error, not as a time; a lossy one is timed, with
// its fragments_lost counter.
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
  std::map<std::string, std::map<std::string, std::string>> params;  // structure -> key -> value
};

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

HeadlessContext* g_context = nullptr;

// One benchmark times one sub-pass sum of the frame `ldmbench run` measures (raster
// baseline, structure build, pass), through the same measure(): "build" (the structure's
// sub-passes) or one of the pass's own. Every build is judged by the same BuildHealth, so a
// configuration `ldmbench run` marks invalid is an error here, never a time.
void run_measurement(benchmark::State& state, const Scene* scene, std::string structure,
                     std::map<std::string, std::string> params, std::string pass, std::string timed, uint32_t views, uint32_t resolution,
                     int width, int height) {
  try {
    MeasurementRequest request;
    request.structure = structure;
    request.structure_params = params;
    request.pass = pass;
    request.views = views;
    request.resolution = resolution;
    request.width = width;
    request.height = height;
    request.warmup = 1;
    request.timer = default_timer_source(g_context->device().gl_renderer);
    request.keep_running = [&state] { return state.KeepRunning(); };
    request.on_frame = [&state, &timed](const FrameTimes& times) {
      for (const auto& [name, ms] : times)
        if (name == timed) state.SetIterationTime(ms * 1e-3);
    };
    const Measurement m = measure(*scene, request);
    if (m.status == BuildStatus::Invalid) {
      state.SkipWithError(("invalid build: " + m.status_detail).c_str());
      return;
    }
    state.counters["fragments"] = double(m.census.fragments);
    state.counters["fragments_lost"] = double(m.last_build.fragments_lost);
    state.counters["bytes_allocated"] = double(m.bytes_allocated());
    if (timed == "build")
      state.counters["fragments_per_second"] = benchmark::Counter(
          double(m.census.fragments), benchmark::Counter::kIsIterationInvariantRate);
    else
      state.counters["pixels_per_second"] = benchmark::Counter(
          double(width) * height, benchmark::Counter::kIsIterationInvariantRate);
    state.SetLabel(g_context->device().gl_renderer);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
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
  const auto context = HeadlessContext::create(default_context_options());
  g_context = context.get();
  benchmark::AddCustomContext("gl_renderer", context->device().gl_renderer);
  benchmark::AddCustomContext("gl_version", context->device().gl_version);
  benchmark::AddCustomContext("timer", timer_source_name(default_timer_source(context->device().gl_renderer)));
  for (const auto& scene : axes.scenes)
    for (const auto& structure : axes.structures)
      for (const auto& pass : axes.passes)
        for (uint32_t n : axes.views)
          for (uint32_t r : axes.resolutions) {
            const std::string suffix = "/" + scene + "/" + structure + "/N:" + std::to_string(n) +
                                       "/R:" + std::to_string(r);
            // "build" and each sub-pass the pass declares, e.g. Build/..., ao:gbuffer/...
            std::vector<std::pair<std::string, std::string>> timed = {{"Build", "build"}};
            for (const auto& s : make_pass(pass, StructureParams())->subpasses())
              if (s.every_frame) timed.emplace_back(pass + ":" + s.name, s.name);
            for (const auto& [label, subpass] : timed)
              benchmark::RegisterBenchmark((label + suffix).c_str(), run_measurement,
                                           &scenes.at(scene), structure, axes.params[structure],
                                           pass, subpass, n, r,
                                           axes.width, axes.height)
                  ->UseManualTime()
                  ->Unit(benchmark::kMillisecond);
          }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
