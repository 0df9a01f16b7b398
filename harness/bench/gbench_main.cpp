// Google Benchmark front end: construction and AO-trace time of every structure, per
// (scene, structure, N, R_LDM), in Google Benchmark's formats so that its compare.py tool
// works on the JSON (--benchmark_out=FILE --benchmark_out_format=json).
//
// Each iteration is timed with ldmbench's own timer (GL timestamps on GPUs, a fenced wall
// clock on software rasterisers; see harness/measure/gpu_timer.h) and reported as manual
// time. Axes come from these flags, given before or among Google Benchmark's own:
//   --ldm_scenes=cornell,atrium  --ldm_structures=all  --ldm_views=32  --ldm_r=128
//   --ldm_width=256 --ldm_height=256
// A build that loses fragments or fails its integrity check is reported as an error, not
// as a time.
#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "harness/app/ldm_setup.h"
#include "harness/gl/egl_context.h"
#include "harness/passes/ao_pass.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "ldm_impls/common/ldm_inspector.h"

namespace {

using namespace ldm;

struct Axes {
  std::vector<std::string> scenes = {"cornell", "atrium"};
  std::vector<std::string> structures = structure_names();
  std::vector<uint32_t> views = {32};
  std::vector<uint32_t> resolutions = {128};
  int width = 256, height = 256;
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
    else if (const char* v = value("--ldm_views")) axes.views = split_numbers("--ldm_views", v);
    else if (const char* v = value("--ldm_r")) axes.resolutions = split_numbers("--ldm_r", v);
    else if (const char* v = value("--ldm_width")) axes.width = int(split_numbers("--ldm_width", v).at(0));
    else if (const char* v = value("--ldm_height")) axes.height = int(split_numbers("--ldm_height", v).at(0));
    else if (arg.rfind("--ldm_", 0) == 0) throw UserError("unknown flag " + arg);
    else argv[kept++] = argv[i];
  }
  *argc = kept;
  return axes;
}

HeadlessContext* g_context = nullptr;

// Setups are shared by the benchmarks of one (scene, N, R): the census runs once.
const LdmSetup& setup_for(const std::string& scene, uint32_t views, uint32_t resolution) {
  static std::map<std::string, std::unique_ptr<LdmSetup>> cache;
  const std::string key = scene + "/" + std::to_string(views) + "/" + std::to_string(resolution);
  auto& slot = cache[key];
  if (!slot) {
    AttributeSet attributes;
    attributes.normals = true;
    slot = std::make_unique<LdmSetup>(load_scene(scene), attributes, views, resolution);
  }
  return *slot;
}

void report_common(benchmark::State& state, const LdmSetup& setup, const LdmStructure& s) {
  uint64_t allocated = 0;
  for (const auto& m : s.memory()) allocated += m.allocated;
  state.counters["fragments"] = double(setup.census.total_fragments);
  state.counters["bytes_allocated"] = double(allocated);
  state.SetLabel(g_context->device().gl_renderer);
}

// True when the last build stored every fragment and reads back intact.
bool build_is_sound(benchmark::State& state, const LdmSetup& setup, LdmStructure& s) {
  const BuildStats stats = s.stats();
  const LdmIntegrity integrity = LdmInspector(s, *setup.inputs).check();
  if (stats.fragments_lost > 0 || integrity.fragments != setup.census.total_fragments ||
      integrity.unsorted_pixels > 0) {
    state.SkipWithError("build lost fragments or failed its integrity check");
    return false;
  }
  return true;
}

void run_build(benchmark::State& state, std::string scene, std::string structure, uint32_t views,
               uint32_t resolution) {
  try {
    const LdmSetup& setup = setup_for(scene, views, resolution);
    auto s = setup.prepare(structure);
    GpuTimer timer(default_timer_source(g_context->device().gl_renderer));
    for (auto _ : state) {
      timer.begin_frame();
      s->build(*setup.inputs, &timer);
      double ms = 0;
      for (const auto& [name, t] : timer.end_frame()) ms += t;
      state.SetIterationTime(ms * 1e-3);
    }
    if (!build_is_sound(state, setup, *s)) return;
    report_common(state, setup, *s);
    state.counters["fragments_per_second"] = benchmark::Counter(
        double(setup.census.total_fragments), benchmark::Counter::kIsIterationInvariantRate);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

void run_ao_trace(benchmark::State& state, std::string scene, std::string structure,
                  uint32_t views, uint32_t resolution, int width, int height) {
  try {
    const LdmSetup& setup = setup_for(scene, views, resolution);
    auto s = setup.prepare(structure);
    s->build(*setup.inputs, nullptr);
    if (!build_is_sound(state, setup, *s)) return;
    GBufferPass gbuffer(width, height);
    gbuffer.render(*setup.gpu_scene, setup.scene, nullptr);
    AoPass ao(*s, *setup.inputs, width, height, setup.scene.ao);
    GpuTimer timer(default_timer_source(g_context->device().gl_renderer));
    for (auto _ : state) {
      timer.begin_frame();
      ao.render(gbuffer, &timer);
      state.SetIterationTime(timer.end_frame().at(0).second * 1e-3);
    }
    report_common(state, setup, *s);
    state.counters["pixels_per_second"] =
        benchmark::Counter(double(width) * height, benchmark::Counter::kIsIterationInvariantRate);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  Axes axes;
  try {
    axes = parse_axes(&argc, argv);
    for (const auto& s : axes.structures) make_structure(s, StructureParams());
    for (const auto& scene : axes.scenes) load_scene(scene);
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
      for (uint32_t n : axes.views)
        for (uint32_t r : axes.resolutions) {
          const std::string suffix = "/" + scene + "/" + structure + "/N:" + std::to_string(n) +
                                     "/R:" + std::to_string(r);
          benchmark::RegisterBenchmark(("Build" + suffix).c_str(), run_build, scene, structure, n, r)
              ->UseManualTime()
              ->Unit(benchmark::kMillisecond);
          benchmark::RegisterBenchmark(("AoTrace" + suffix).c_str(), run_ao_trace, scene, structure,
                                       n, r, axes.width, axes.height)
              ->UseManualTime()
              ->Unit(benchmark::kMillisecond);
        }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
