#include "harness/app/measure_configuration.h"

#include <filesystem>

#include "harness/app/accuracy.h"
#include "harness/app/machine_state.h"
#include "harness/app/measured_where.h"
#include "harness/app/scene_profile.h"
#include "harness/app/timing_columns.h"
#include "harness/passes/raster_baseline.h"
#include "harness/records/output_folder.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/version.h"

namespace ldm {
namespace {

TimerSource timer_source(const std::string& option, const DeviceInfo& device) {
  if (option == "gl_timestamp") return TimerSource::GpuTimestamps;
  if (option == "fenced_wall_clock") return TimerSource::FencedWallClock;
  return default_timer_source(device.gl_renderer);
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
  // A pass that reads no LDM sizes no structure.
  r.set("sizing_policy", config.structure == kNoStructure ? std::string(kNoStructure)
                                                          : sizing_policy_name(config.sizing.policy));
  r.set("frames", settings.frames);
  r.set("warmup", settings.warmup);
  r.set("device", device.gl_renderer);
  r.set("device_id", device.device_id);
  r.set("gl_driver", device.gl_driver);
  r.set("gl_vendor", device.gl_vendor);
  r.set("gl_version", device.gl_version);
  r.set("egl_platform", device.egl_platform);
  r.set("int64_atomics", device.has_int64_atomics);
  r.set("driver_defects", device.driver_defects);
  describe_host(r);
  r.set("ldmbench_version", ldmbench_version());
  r.set("git_commit", git_commit());
}

MeasurementRequest measurement_request(const Configuration& config, const RunSettings& settings,
                                       const DeviceInfo& device) {
  MeasurementRequest request;
  request.structure = config.structure;
  request.structure_params = config.params;
  request.sizing = config.sizing;
  request.pass = config.pass;
  request.pass_params = config.pass_params;
  request.views = config.views;
  request.resolution = config.resolution;
  request.width = settings.width;
  request.height = settings.height;
  request.warmup = settings.warmup;
  request.frames = settings.frames;
  request.precision = settings.precision;
  request.timer = timer_source(settings.timer, device);
  request.verify = parse_verify_mode(settings.verify);
  return request;
}

void add_measurement(Record& r, const Measurement& m, const TimePrecision& precision) {
  r.set("scene_name", m.scene_name);
  r.set("scene_hash", m.scene_hash);
  r.set("triangles", m.triangles);
  for (const auto& [key, value] : m.pass_settings) r.put(key, value);
  for (const auto& [key, value] : m.pass_results) r.put(key, value);
  r.set("scene_attributes", m.scene_attributes);
  r.set("scene_gpu_bytes", m.scene_gpu_bytes);
  r.set("payload", m.payload);
  r.set("fragments", m.census.fragments);
  r.set("max_depth_complexity", m.census.max_depth_complexity);
  r.set("mean_depth_complexity", m.census.mean_depth_complexity);
  r.set("nonempty_pixel_fraction", m.census.nonempty_pixel_fraction);
  r.set("timer", timer_source_name(m.timer));
  if (!m.device.empty()) r.set("device", m.device);  // a CPU pass: the CPU, not GL_RENDERER

  r.set("status", build_status_name(m.status));
  r.set("status_detail", m.status_detail);
  r.set("fragments_stored", m.last_build.fragments_stored);
  r.set("fragments_lost", m.last_build.fragments_lost);
  r.set("overflow", m.overflow);
  r.set("checksum_changes", m.checksum_changes);
  r.set("tied_depths", m.tied_depths);
  r.set("lists_checksum", hex64(m.lists_checksum));
  if (!m.verify_mode.empty()) {  // a structure's builds were checked
    r.set("verify_mode", m.verify_mode);
    r.set("verify_stride", m.verify_stride);
    r.set("verify_full_checks", m.verify_counts.full);
    r.set("verify_sampled_checks", m.verify_counts.sampled);
    r.set("verify_sampled_pixels", m.verify_counts.sampled_pixels);
    r.set("verify_ms", m.verify_measured_ms);
    r.set("verify_warmup_ms", m.verify_warmup_ms);
  }
  for (const auto& [name, value] : m.last_build.counters) r.set("counter_" + name, value);
  for (const auto& [key, value] : m.sizing) r.set("sizing_" + key, value);
  r.set("sizing_rebuilds", m.sizing_rebuilds);
  r.set("sizing_rebuilds_measured", m.sizing_rebuilds_measured);
  r.set("sizing_reallocations", m.sizing_reallocations);

  r.set("raster_touch_fragments", m.raster_touch_fragments);
  const TimingSeries series = m.series();
  if (const std::vector<double>* baseline = series.find(kRasterBaselineSubpass))
    r.set("baseline_frames", baseline->size());
  TimingOutcome timing;
  timing.summaries = m.summaries();
  timing.frames_per_repetition = {m.frames.size()};
  timing.target_met = m.time_target_met;
  timing.precision = precision;
  add_timing_columns(r, timing);
  r.set("frames_timed_ms", m.frames_timed_ms());
  set_verify_share(r);
  const std::string warning = time_target_warning(timing);
  if (!warning.empty()) {
    const RecordValue* detail = r.get("status_detail");
    const std::string* text = detail ? std::get_if<std::string>(detail) : nullptr;
    r.set("status_detail", (text && !text->empty() ? *text + "; " : std::string()) + warning);
  }

  for (const auto& b : m.memory) {
    r.set("mem_" + b.name + "_allocated", b.allocated);
    r.set("mem_" + b.name + "_used", b.used);
  }
  for (const auto& b : m.pass_memory) {
    r.set("mem_" + b.name + "_allocated", b.allocated);
    r.set("mem_" + b.name + "_used", b.used);
  }
  r.set("bytes_allocated", m.bytes_allocated());
  r.set("bytes_used", m.bytes_used());
}

Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths, Repetition repetition) {
  Record r;
  describe_configuration(r, config, settings, device);
  const GpuStateQuery gpu{device.gl_vendor.find("NVIDIA") != std::string::npos, 0};
  const MachineState before = sample_machine_state(gpu);
  const Measurement m = measure(scene, measurement_request(config, settings, device));
  const MachineState after = sample_machine_state(gpu);
  add_measurement(r, m, settings.precision);
  set_machine_state_columns(r, before, after);
  append_status_detail(r, clock_change_warning(before, after));
  add_scene_profile(r, scene, config, m);
  if (repetition.count > 1) r.set("repetition", repetition.index);
  // Images and accuracy once, from the first repetition: the image of an identical build
  // is identical (later repetitions' lists are checked against the first's).
  const bool whole = repetition.index == 0;

  const OutputFolder folder(paths.out_dir, paths.images_dir, paths.written);
  const std::string stem = config.id() + "-" + m.images.front().name;
  const Image& image = m.images.front().image;
  if (whole && settings.write_images) {
    r.set("image_exr", folder.write_exr(stem + ".exr", image));
    r.set("image_png", folder.write_png(stem + ".png", image));
    // The pass's further images (e.g. the indirect pass's direct light and sum), unscored.
    for (size_t i = 1; i < m.images.size(); ++i) {
      const std::string other = config.id() + "-" + m.images[i].name;
      r.set("image_" + m.images[i].name + "_exr", folder.write_exr(other + ".exr", m.images[i].image));
      r.set("image_" + m.images[i].name + "_png", folder.write_png(other + ".png", m.images[i].image));
    }
  }
  if (whole && settings.reference.enabled) {
    const auto pass = make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
    for (const auto& scored : pass->references(scene, image.width, image.height, settings.reference))
      add_accuracy(r, scored.reference, image, settings.write_images ? &folder : nullptr,
                   stem + (scored.column_prefix.empty() ? "" : "-" + scored.column_prefix),
                   scored.column_prefix, scored.ssim_exposure, &m.coverage);
  }
  flag_degenerate_measurement(r);
  // Last, so that a configuration abandoned on the way (an interrupted reference) leaves no
  // samples behind, as it leaves no record.
  const OutputFolder samples(paths.out_dir,
                             (std::filesystem::path(paths.out_dir) / "samples").string(), paths.written);
  r.set("frame_samples_csv",
        samples.write_text(samples_file_name(config.id(), repetition), frame_samples_csv(m, repetition.index)));
  return r;
}

std::string samples_file_name(const std::string& config_id, Repetition repetition) {
  if (repetition.count <= 1) return config_id + "-frames.csv";
  return config_id + "-rep" + std::to_string(repetition.index) + "-frames.csv";
}

}  // namespace ldm
