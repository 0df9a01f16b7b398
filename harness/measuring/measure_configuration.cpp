#include "harness/measuring/measure_configuration.h"

#include <cstdlib>
#include <filesystem>

#include "harness/measuring/accuracy.h"
#include "harness/settings/harness_axes.h"
#include "harness/measuring/machine_state.h"
#include "harness/measuring/measured_where.h"
#include "harness/settings/record_schema.h"
#include "harness/measuring/scene_profile.h"
#include "harness/measuring/timing_columns.h"
#include "harness/passes/raster_baseline.h"
#include "harness/records/harness_columns.h"
#include "harness/records/output_folder.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/version.h"

namespace ldm {
namespace {

using namespace columns;

TimerSource timer_source(const std::string& option, const DeviceInfo& device) {
  if (option == "gl_timestamp") return TimerSource::GpuTimestamps;
  if (option == "fenced_wall_clock") return TimerSource::FencedWallClock;
  return default_timer_source(device.gl_renderer);
}

}  // namespace

void describe_configuration(Record& r, const Configuration& config, const RunSettings& /*settings*/,
                            const DeviceInfo& device) {
  r.set(kConfigId, config.id());
  r.set(kStatus, "pending");
  r.set(kStatusDetail, "");
  // The identity columns, one per axis (harness/settings/harness_axes.h), and the parameters.
  write_axis_columns(r, config);
  r.set(kDevice, device.gl_renderer);
  r.set(kDeviceId, device.device_id);
  r.set(kGlDriver, device.gl_driver);
  r.set(kGlVendor, device.gl_vendor);
  r.set(kGlVersion, device.gl_version);
  r.set(kEglPlatform, device.egl_platform);
  r.set(kInt64Atomics, device.has_int64_atomics);
  r.set(kDriverDefects, device.driver_defects);
  describe_host(r);
  r.set(kLdmbenchVersion, ldmbench_version());
  r.set(kGitCommit, git_commit());
  if (const char* shaders = std::getenv("LDM_SHADER_DIR"); shaders && *shaders) r.set(kShaderDir, shaders);
}

MeasurementRequest measurement_request(const Configuration& config, const RunSettings& settings,
                                       const DeviceInfo& device) {
  MeasurementRequest request;
  request.configuration = config;
  request.warmup = settings.warmup;
  request.frames = settings.frames;
  request.count_work = settings.count_work;
  request.precision = settings.precision;
  request.timer = timer_source(settings.timer, device);
  request.verify = parse_verify_mode(settings.verify);
  return request;
}

void add_measurement(Record& r, const Measurement& m, const AxisValues& values, const TimePrecision& precision) {
  r.set(kSceneName, m.scene_name);
  r.set(kSceneHash, m.scene_hash);
  r.set(kTriangles, m.triangles);
  for (const auto& [key, value] : m.pass_settings) r.put(key, value);
  // Every parameter's own column, by one loop over the pass's declarations: what the
  // configuration gives, else the declared default.
  for (const auto& [column, value] : pass_parameter_values(m.pass, values)) r.put(column, value);
  for (const auto& [key, value] : m.pass_results) r.put(key, value);
  r.set(kSceneAttributes, m.scene_attributes);
  r.set(kSceneGpuBytes, m.scene_gpu_bytes);
  r.set(kPayload, m.payload);
  r.set(kFragments, m.census.fragments);
  r.set(kMaxDepthComplexity, m.census.max_depth_complexity);
  r.set(kMeanDepthComplexity, m.census.mean_depth_complexity);
  r.set(kNonemptyPixelFraction, m.census.nonempty_pixel_fraction);
  r.set(kTimer, timer_source_name(m.timer));
  if (!m.device.empty()) r.set(kDevice, m.device);  // a CPU pass: the CPU, not GL_RENDERER

  r.set(kStatus, build_status_name(m.status));
  r.set(kStatusDetail, m.status_detail);
  r.set(kFragmentsStored, m.last_build.fragments_stored);
  r.set(kFragmentsLost, m.last_build.fragments_lost);
  r.set(kOverflow, m.overflow);
  r.set(kChecksumChanges, m.checksum_changes);
  r.set(kTiedDepths, m.tied_depths);
  r.set(kListsChecksum, hex64(m.lists_checksum));
  if (!m.verify_mode.empty()) {  // a structure's builds were checked
    r.set(kVerifyMode, m.verify_mode);
    r.set(kVerifyStride, m.verify_stride);
    r.set(kVerifyFullChecks, m.verify_counts.full);
    r.set(kVerifySampledChecks, m.verify_counts.sampled);
    r.set(kVerifySampledPixels, m.verify_counts.sampled_pixels);
    r.set(kVerifyMs, m.verify_measured_ms);
    r.set(kVerifyWarmupMs, m.verify_warmup_ms);
  }
  for (const auto& [name, value] : m.last_build.counters) r.set("counter_" + name, value);
  for (const auto& [key, value] : m.sizing) r.set("sizing_" + key, value);
  r.set(kSizingRebuilds, m.sizing_rebuilds);
  r.set(kSizingRebuildsMeasured, m.sizing_rebuilds_measured);
  r.set(kSizingReallocations, m.sizing_reallocations);

  r.set(kRasterTouchFragments, m.raster_touch_fragments);
  const TimingSeries series = m.series();
  if (const std::vector<double>* baseline = series.find(kRasterBaselineSubpass))
    r.set(kBaselineFrames, baseline->size());
  TimingOutcome timing;
  timing.summaries = m.summaries();
  timing.frames_per_repetition = {m.frames.size()};
  timing.target_met = m.time_target_met;
  timing.precision = precision;
  add_timing_columns(r, timing);
  r.set(kFramesTimedMs, m.frames_timed_ms());
  set_verify_share(r);
  const std::string warning = time_target_warning(timing);
  if (!warning.empty()) {
    const RecordValue* detail = r.get(kStatusDetail);
    const std::string* text = detail ? std::get_if<std::string>(detail) : nullptr;
    r.set(kStatusDetail, (text && !text->empty() ? *text + "; " : std::string()) + warning);
  }

  for (const auto& b : m.memory) {
    r.set("mem_" + b.name + "_allocated", b.allocated);
    r.set("mem_" + b.name + "_used", b.used);
  }
  for (const auto& b : m.pass_memory) {
    r.set("mem_" + b.name + "_allocated", b.allocated);
    r.set("mem_" + b.name + "_used", b.used);
  }
  if (m.work_counted) {
    r.set(kWorkReplayMs, m.work_replay_ms);
    for (const auto& [column, value] : m.work) r.put(column, value);
  }
  r.set(kBytesAllocated, m.bytes_allocated());
  r.set(kBytesUsed, m.bytes_used());
}

Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths, Repetition repetition) {
  Record r = measurement_record();
  describe_configuration(r, config, settings, device);
  const GpuStateQuery gpu{device.gl_vendor.find("NVIDIA") != std::string::npos, 0};
  // The machine's state around the measured frames, after the warm-up (clock_warmup.h).
  MachineState before, after;
  MeasurementRequest request = measurement_request(config, settings, device);
  if (gpu.nvidia) request.read_gpu_clock = [gpu] { return read_gpu_clock(gpu); };
  request.before_measured_frames = [&] { before = sample_machine_state(gpu); };
  request.after_measured_frames = [&] { after = sample_machine_state(gpu); };
  const Measurement m = measure(scene, request);
  add_measurement(r, m, config.values, settings.precision);
  set_machine_state_columns(r, before, after);
  if (m.clock_warmup.checked) {
    r.set(kClockWarmupFrames, m.clock_warmup.frames);
    r.set(kClockWarmupSeconds, m.clock_warmup.seconds);
  }
  append_status_detail(r, clock_warmup_warning(m.clock_warmup));
  append_status_detail(r, clock_change_warning(before, after));
  add_scene_profile(r, scene, config, m);
  if (repetition.count > 1) r.set(kRepetition, repetition.index);
  // Images and accuracy once, from the first repetition: the image of an identical build
  // is identical (later repetitions' lists are checked against the first's).
  const bool whole = repetition.index == 0;

  const OutputFolder folder(paths.out_dir, paths.images_dir, paths.written);
  const std::string stem = config.id() + "-" + m.images.front().name;
  const Image& image = m.images.front().image;
  if (whole && settings.write_images) {
    r.set(kImageExr, folder.write_exr(stem + ".exr", image));
    r.set(kImagePng, folder.write_png(stem + ".png", image));
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
  r.set(kFrameSamplesCsv,
        samples.write_text(samples_file_name(config.id(), repetition), frame_samples_csv(m, repetition.index)));
  return r;
}

std::string samples_file_name(const std::string& config_id, Repetition repetition) {
  if (repetition.count <= 1) return config_id + "-frames.csv";
  return config_id + "-rep" + std::to_string(repetition.index) + "-frames.csv";
}

}  // namespace ldm
