#include "harness/app/measure_configuration.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

#include "harness/app/accuracy.h"
#include "harness/app/ldm_setup.h"
#include "harness/image/image.h"
#include "harness/measure/timing_stats.h"
#include "harness/passes/ao_pass.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/raster_baseline.h"
#include "harness/util/error.h"
#include "harness/util/version.h"
#include "harness/util/hash.h"
#include "ldm_impls/common/ldm_inspector.h"

namespace ldm {
namespace {

// Sub-passes timed outside the structure's build(); everything else in a frame is the build.
bool is_harness_subpass(const std::string& name) {
  return name == "raster_baseline" || name == "gbuffer" || name == "ao";
}

AoSettings effective_ao(const Scene& scene, const Configuration& config,
                        const RunSettings& settings) {
  AoSettings ao = scene.ao;
  if (config.d_max) ao.d_max = *config.d_max;
  if (config.visibility == Visibility::Attenuated) ao.attenuated = true;
  if (config.visibility == Visibility::Unattenuated) ao.attenuated = false;
  if (settings.normal_offset_pixels) ao.normal_offset_pixels = *settings.normal_offset_pixels;
  return ao;
}

// Watches every build of a configuration for results that could silently be wrong.
class BuildHealth {
 public:
  explicit BuildHealth(const FragmentCensus& census) : census_(census) {}

  void observe(const BuildStats& stats, const LdmIntegrity& integrity) {
    ++builds_;
    max_lost_ = std::max(max_lost_, stats.fragments_lost);
    overflow_ = overflow_ || stats.overflow;
    if (stats.fragments_rasterized != census_.total_fragments)
      problem("the build rasterised " + std::to_string(stats.fragments_rasterized) +
              " fragments where the census counted " + std::to_string(census_.total_fragments));
    if (integrity.fragments != stats.fragments_stored)
      problem(std::to_string(stats.fragments_stored) + " fragments stored but " +
              std::to_string(integrity.fragments) +
              " reachable through the query API (dropped or corrupted entries)");
    if (integrity.unsorted_pixels > 0)
      problem(std::to_string(integrity.unsorted_pixels) + " pixels with unsorted depths");
    if (integrity.overlong_pixels > 0)
      problem(std::to_string(integrity.overlong_pixels) +
              " pixels longer than the census's maximum depth complexity");
    if (builds_ == 1) {
      first_checksum_ = integrity.checksum;
    } else if (integrity.checksum != first_checksum_) {
      ++checksum_changes_;
      // A lossy build may legitimately keep a different subset (first come, first stored).
      if (stats.fragments_lost == 0)
        problem("the stored lists changed between identical builds (nodes dropped or reordered)");
    }
  }

  std::string status() const {
    if (!problems_.empty()) return "invalid";
    return max_lost_ > 0 ? "lossy" : "ok";
  }
  std::string detail() const {
    std::string out;
    for (const auto& p : problems_) out += (out.empty() ? "" : "; ") + p;
    if (out.empty() && max_lost_ > 0)
      out = std::to_string(max_lost_) + " fragments lost per build (configured capacity)";
    return out;
  }
  uint64_t checksum_changes() const { return checksum_changes_; }
  uint64_t first_checksum() const { return first_checksum_; }
  bool overflow() const { return overflow_; }

 private:
  void problem(const std::string& p) {
    if (std::find(problems_.begin(), problems_.end(), p) == problems_.end()) problems_.push_back(p);
  }
  const FragmentCensus& census_;
  uint64_t builds_ = 0, max_lost_ = 0, checksum_changes_ = 0, first_checksum_ = 0;
  bool overflow_ = false;
  std::vector<std::string> problems_;
};

void add_timings(Record& r, const std::vector<TimingSummary>& summaries) {
  for (const auto& s : summaries) {
    r.set(s.subpass + "_ms_median", s.median);
    r.set(s.subpass + "_ms_min", s.min);
    r.set(s.subpass + "_ms_max", s.max);
    r.set(s.subpass + "_ms_stddev", s.stddev);
  }
}

const TimingSummary* find_summary(const std::vector<TimingSummary>& summaries,
                                  const std::string& name) {
  for (const auto& s : summaries)
    if (s.subpass == name) return &s;
  return nullptr;
}

}  // namespace

void describe_configuration(Record& r, const Configuration& config, const RunSettings& settings,
                            const DeviceInfo& device) {
  r.set("config_id", config.id());
  r.set("status", "pending");
  r.set("status_detail", "");
  r.set("scene", config.scene);
  r.set("structure", config.structure);
  r.set("pass", config.pass);
  r.set("n_views", config.views);
  r.set("r_ldm", config.resolution);
  r.set("width", settings.width);
  r.set("height", settings.height);
  std::string params;
  for (const auto& [key, value] : config.params) params += (params.empty() ? "" : ";") + key + "=" + value;
  r.set("structure_params", params);
  r.set("frames", settings.frames);
  r.set("warmup", settings.warmup);
  r.set("device", device.gl_renderer);
  r.set("gl_vendor", device.gl_vendor);
  r.set("gl_version", device.gl_version);
  r.set("egl_platform", device.egl_platform);
  r.set("int64_atomics", device.has_int64_atomics);
  r.set("ldmbench_version", ldmbench_version());
  r.set("git_commit", git_commit());
}

Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths) {
  Record r;
  describe_configuration(r, config, settings, device);
  if (config.pass != "ao") throw UserError("--pass: unknown pass '" + config.pass + "' (known: ao)");
  const AoSettings ao = effective_ao(scene, config, settings);
  r.set("scene_name", scene.name);
  r.set("scene_hash", hex64(scene.content_hash()));
  r.set("triangles", uint64_t(scene.mesh.triangle_count()));
  r.set("visibility", ao.attenuated ? "attenuated" : "unattenuated");
  r.set("d_max", ao.d_max);
  r.set("falloff_exponent", ao.falloff_exponent);
  r.set("normal_offset_pixels", ao.normal_offset_pixels);

  // AO reads positions (every pass) and normals (the G-buffer); nothing else is uploaded,
  // and the structures store depth alone.
  AttributeSet attributes;
  attributes.normals = true;
  const LdmSetup setup(scene, attributes, config.views, config.resolution, FragmentPayload{});
  const FragmentCensus& census = setup.census;
  const BuildInputs& in = *setup.inputs;
  r.set("scene_attributes", attributes.describe());
  r.set("scene_gpu_bytes", setup.gpu_scene->bytes());
  r.set("payload", in.payload.describe());
  r.set("fragments", census.total_fragments);
  r.set("max_depth_complexity", census.max_depth_complexity);
  r.set("mean_depth_complexity", census.mean_depth_complexity());
  r.set("nonempty_pixel_fraction",
        census.total_pixels ? double(census.nonempty_pixels) / double(census.total_pixels) : 0.0);

  auto structure = setup.prepare(config.structure, config.params);
  const RasterBaseline baseline(config.resolution);
  GBufferPass gbuffer(settings.width, settings.height);
  AoPass ao_pass(*structure, in, settings.width, settings.height, ao);
  const LdmInspector inspector(*structure, in);

  const TimerSource timer_source =
      settings.timer == "auto"           ? default_timer_source(device.gl_renderer)
      : settings.timer == "gl_timestamp" ? TimerSource::GpuTimestamps
                                         : TimerSource::FencedWallClock;
  r.set("timer", timer_source_name(timer_source));
  GpuTimer timer(timer_source);
  TimingSeries series;
  BuildHealth health(census);
  BuildStats last_stats;
  for (int frame = 0; frame < settings.warmup + settings.frames; ++frame) {
    timer.begin_frame();
    baseline.render(*setup.gpu_scene, *setup.gpu_views, &timer);
    structure->build(in, &timer);
    gbuffer.render(*setup.gpu_scene, scene, &timer);
    ao_pass.render(gbuffer, &timer);
    FrameTimes times = timer.end_frame();
    last_stats = structure->stats();
    health.observe(last_stats, inspector.check());
    if (frame < settings.warmup) continue;  // warm-up frames are discarded
    double build_ms = 0, frame_ms = 0;
    for (const auto& [name, ms] : times) {
      if (name == "raster_baseline") continue;
      frame_ms += ms;
      if (!is_harness_subpass(name)) build_ms += ms;
    }
    times.emplace_back("build", build_ms);
    times.emplace_back("frame", frame_ms);
    series.add_frame(times);
  }

  r.set("status", health.status());
  r.set("status_detail", health.detail());
  r.set("fragments_stored", last_stats.fragments_stored);
  r.set("fragments_lost", last_stats.fragments_lost);
  r.set("overflow", health.overflow());
  r.set("checksum_changes", health.checksum_changes());
  r.set("lists_checksum", hex64(health.first_checksum()));
  for (const auto& [name, value] : last_stats.counters) r.set("counter_" + name, value);
  for (const auto& [key, value] : structure->sizing()) r.set("sizing_" + key, value);

  const auto summaries = series.summarize();
  add_timings(r, summaries);
  const TimingSummary* build = find_summary(summaries, "build");
  const TimingSummary* raster = find_summary(summaries, "raster_baseline");
  if (build && raster && raster->median > 0)
    r.set("build_vs_raster", build->median / raster->median);
  if (build && build->median > 0)
    r.set("fragments_per_second", double(census.total_fragments) / (build->median * 1e-3));

  uint64_t allocated = 0, used = 0;
  for (const auto& m : structure->memory()) {
    r.set("mem_" + m.name + "_allocated", m.allocated);
    r.set("mem_" + m.name + "_used", m.used);
    allocated += m.allocated;
    used += m.used;
  }
  r.set("bytes_allocated", allocated);
  r.set("bytes_used", used);

  const Image image = ao_pass.read_image();
  const std::string stem = config.id() + "-ao";
  if (settings.write_images) {
    write_exr((std::filesystem::path(paths.images_dir) / (stem + ".exr")).string(), image);
    write_png((std::filesystem::path(paths.images_dir) / (stem + ".png")).string(), image);
    const auto relative = std::filesystem::relative(paths.images_dir, paths.out_dir);
    r.set("image_exr", (relative / (stem + ".exr")).string());
    r.set("image_png", (relative / (stem + ".png")).string());
  }
  if (settings.reference.enabled)
    add_ao_accuracy(r, scene, ao, image, settings.reference,
                    {paths.out_dir, paths.images_dir, stem, settings.write_images});
  return r;
}

}  // namespace ldm
