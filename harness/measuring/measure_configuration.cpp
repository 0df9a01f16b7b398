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
  r.put_all(m.columns);  // every column measure() wrote, in its order
  set_machine_state_columns(r, before, after);
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
