#pragma once
// One measurement of a (scene, structure, pass, N, R_LDM) configuration, as a value: what
// `ldmbench run` turns into a record, what `ldmbench_gbench` reports, and what the tests
// inspect. All three call measure(), so they build, time and judge alike.
//
// measure() uploads what the pass requires, takes the fragment census, prepares the
// structure and the pass, then runs frames: raster baselines │ structure build under its
// sizing policy (ldm_impls/common/sizing_driver.h) │ pass, each sub-pass timed, and after
// every frame (untimed) the inspector's read-back judged by
// BuildHealth (ldm_impls/common/build_health.h). Warm-up frames are judged but not kept.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness/measure/clock_warmup.h"
#include "harness/measure/frame_stop_rule.h"
#include "harness/measure/gpu_timer.h"
#include "harness/measure/timing_stats.h"
#include "harness/passes/pass.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"
#include "harness/settings/run_settings.h"
#include "ldm_impls/common/build_health.h"
#include "ldm_impls/common/build_verifier.h"
#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

// What a request measures unless told otherwise (tests and benchmarks set what they vary):
// the AO pass, N 32, R_LDM 128, the previous_frame sizing policy, no axis values.
inline Configuration default_measured_configuration() {
  Configuration c;
  c.pass = "ao";
  c.views = 32;
  c.resolution = 128;
  c.width = c.height = 256;
  c.sizing = {SizingPolicy::PreviousFrame};
  return c;
}

struct MeasurementRequest {
  // What is measured, as the sweep planned it (harness/settings/run_settings.h): the
  // structure and its parameters, the pass and its parameters, N, R_LDM, the image size and
  // the sizing policy read through the configuration's typed views, and every axis's value
  // (Configuration::values) handed to the pass (PassInputs::axes), where an axis declared
  // for it is read. Carried whole, never copied field by field.
  Configuration configuration = default_measured_configuration();
  // At least `frames` measured frames, then more until `precision` is met or its cap
  // reached (harness/measure/frame_stop_rule.h); precision.target 0: exactly `frames`.
  int warmup = 2, frames = 5;
  TimePrecision precision{0.0};  // exactly `frames` unless asked (`ldmbench run` asks)
  TimerSource timer = TimerSource::FencedWallClock;
  // How much of each build is checked (ldm_impls/common/build_verifier.h).
  VerifyMode verify = VerifyMode::Sampled;
  uint32_t verify_stride = kDefaultVerifyStride;
  // Decides before each measured frame whether to run it; unset: the stop rule above.
  // Google Benchmark passes its own loop (State::KeepRunning) here.
  std::function<bool()> keep_running;
  // Called with every measured frame's times (sub-passes plus "build" and "frame").
  std::function<void(const FrameTimes&)> on_frame;
  // Where the GPU's clock can be read (NVIDIA), warm-up frames after the fixed ones until it
  // reaches its working clock, for at most precision.clock_warmup_seconds
  // (harness/measure/clock_warmup.h); unset: the fixed warm-up alone.
  std::function<std::optional<GpuClockReading>()> read_gpu_clock;
  // Called right before the first and right after the last measured frame: the record's
  // machine state (harness/measuring/machine_state.h) is sampled there, around what is timed.
  std::function<void()> before_measured_frames, after_measured_frames;
  // After the measured frames, the untimed counting replay (MeasurementSession::
  // count_work): the record's work_* columns. Off only where nothing reads them.
  bool count_work = true;
};

// What measure() returns: the record columns it knows, each written once by the code that
// learns its value (the session, the counting replay, the timing summary), and beside them
// what is not a column — the frames, the images, the buffers, the census's depth profile.
// `ldmbench run` puts the columns into its record as they are (measure_configuration.h);
// the viewer, the benchmarks and the tests read them through the typed readers of Record.
struct Measurement {
  // Declared columns only (measurement_record(): an undeclared one throws at its first use).
  // Among them status and status_detail, the verdict on every build (warm-up included) and
  // on the images.
  Record columns;

  // Every measured frame, in order: each sub-pass's milliseconds, then "build" (the
  // structure's sub-passes), "pass" (the pass's own) and "frame" (everything but the raster
  // baselines).
  std::vector<FrameTimes> frames;
  std::vector<std::string> pass_subpasses;  // the pass's own, as declared
  std::vector<PassImage> images;
  Image coverage;  // Pass::coverage(): where the camera sees a surface (empty: not known)
  // The structure's and the sizing policy's buffers (the mem_* and bytes_* columns), in the
  // structure's order.
  std::vector<BufferMemory> memory;
  DepthProfile depth_profile;  // the census's list lengths (ldm_impls/common/fragment_census.h)
  // The warm-up frames added until the GPU's clock reached its working level.
  ClockWarmupResult clock_warmup;

  BuildStatus status() const;  // the status column's verdict
  std::string status_detail() const;  // the status_detail column
  // An integer or number column's value; 0 where the measurement has none (a peer pass has
  // no census).
  uint64_t count(const Column& column) const { return uint64_t(columns.integer(column).value_or(0)); }
  double number(const Column& column) const { return columns.number(column).value_or(0.0); }
  TimingSeries series() const;  // the measured frames
  // Sum over the measured frames of every timed sub-pass (the frame and the baselines).
  double frames_timed_ms() const;
  std::vector<TimingSummary> summaries() const;  // per sub-pass, first-seen order
};

// Every measured frame's times as a tidy CSV: "repetition,frame,subpass,ms", one row per
// sub-pass and sum of each frame, in order (for statistical comparisons of runs, beyond the
// summaries); `repetition` numbers the independent repetition these frames belong to.
std::string frame_samples_csv(const Measurement& measurement, size_t repetition = 0);
std::string frame_samples_csv(const std::vector<TimingSeries>& repetitions);

// Why each image cannot be measured (a NaN or infinity), one sentence each; empty when all can.
std::vector<std::string> image_problems(const std::vector<PassImage>& images);

// "CPU: <model name>" from /proc/cpuinfo (the device column of a CPU pass's record, e.g. rtao).
std::string cpu_model_name();

// Throws UserError (bad parameters, a configuration the device cannot hold) or GpuError; a
// build that is merely wrong is not an exception but an "invalid" status.
Measurement measure(const Scene& scene, const MeasurementRequest& request);

}  // namespace ldm
