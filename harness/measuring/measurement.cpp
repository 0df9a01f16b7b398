#include "harness/measuring/measurement.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

#include "harness/measuring/measurement_session.h"
#include "harness/measuring/timing_columns.h"
#include "harness/records/harness_columns.h"
#include "harness/metrics/image_checks.h"
#include "harness/passes/raster_baseline.h"
#include "harness/records/record.h"
#include "harness/util/error.h"

namespace ldm {

TimingSeries Measurement::series() const {
  TimingSeries series;
  for (const auto& frame : frames) series.add_frame(frame);
  return series;
}

std::vector<TimingSummary> Measurement::summaries() const { return series().summarize(); }

double Measurement::frames_timed_ms() const {
  double total = 0;
  for (const auto& frame : frames)
    for (const auto& [name, ms] : frame)
      if (name == "frame" || RasterBaseline::is_baseline_subpass(name)) total += ms;
  return total;
}

namespace {
constexpr const char* kSamplesHeader = "repetition,frame,subpass,ms\n";
}  // namespace

std::string frame_samples_csv(const Measurement& m, size_t repetition) {
  std::string out = kSamplesHeader;
  const std::string prefix = std::to_string(repetition) + ",";
  for (size_t frame = 0; frame < m.frames.size(); ++frame)
    for (const auto& [name, ms] : m.frames[frame])
      out += prefix + std::to_string(frame) + "," + name + "," + format_csv_value(ms) + "\n";
  return out;
}

std::string frame_samples_csv(const std::vector<TimingSeries>& repetitions) {
  std::string out = kSamplesHeader;
  for (size_t r = 0; r < repetitions.size(); ++r) {
    const TimingSeries& series = repetitions[r];
    // Frame by frame, each sub-pass that has a sample in it (subsampled ones skip frames).
    std::vector<size_t> next(series.subpasses().size(), 0);
    for (size_t frame = 0; frame < series.frames(); ++frame)
      for (size_t i = 0; i < series.subpasses().size(); ++i) {
        const std::vector<size_t>& frames = series.sample_frames(i);
        if (next[i] >= frames.size() || frames[next[i]] != frame) continue;
        out += std::to_string(r) + "," + std::to_string(frame) + "," + series.subpasses()[i] +
               "," + format_csv_value(series.samples(i)[next[i]++]) + "\n";
      }
  }
  return out;
}

std::string Measurement::status_detail() const { return columns.text(columns::kStatusDetail); }

BuildStatus Measurement::status() const {
  const std::string name = columns.text(columns::kStatus);
  for (const BuildStatus status : {BuildStatus::Ok, BuildStatus::Lossy, BuildStatus::Invalid})
    if (name == build_status_name(status)) return status;
  throw std::logic_error("a measurement without a verdict (status '" + name + "')");
}

std::vector<std::string> image_problems(const std::vector<PassImage>& images) {
  std::vector<std::string> problems;
  for (const auto& image : images) {
    try {
      require_finite(image.image, image.name + " image");
    } catch (const UserError& e) {
      problems.push_back(std::string("image not measured: ") + e.what());
    }
  }
  return problems;
}

std::string cpu_model_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    if (start != std::string::npos) return "CPU: " + line.substr(start);
  }
  return "CPU: unknown model (" + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads)";
}

namespace {

using namespace columns;

// The columns of the measured frames' times: the timing summary (timing_columns.h), the
// frames' total, the baselines' frame count and the verification's share of it.
void add_frame_time_columns(Measurement& m, const MeasurementRequest& request) {
  Record& r = m.columns;
  const TimingSeries series = m.series();
  if (const std::vector<double>* baseline = series.find(kRasterBaselineSubpass))
    r.set(kBaselineFrames, baseline->size());
  TimingOutcome timing;
  timing.summaries = series.summarize();
  timing.frames_per_repetition = {m.frames.size()};
  // A loop the caller drives (Google Benchmark's) has no precision target to miss.
  timing.target_met = request.keep_running || FrameStopRule(request.frames, request.precision).target_met(series);
  timing.precision = request.precision;
  add_timing_columns(r, timing);
  r.set(kFramesTimedMs, m.frames_timed_ms());
  set_verify_share(r);
  append_note(r, kStatusDetail, time_target_warning(timing));
}

}  // namespace

Measurement measure(const Scene& scene, const MeasurementRequest& request) {
  MeasurementSession session(scene, request);
  FrameStopRule stop_rule(request.frames, request.precision);
  TimingSeries measured;
  auto keep_running = [&]() {
    if (request.keep_running) return request.keep_running();
    return stop_rule.want_another(measured);
  };
  while (session.in_warmup()) session.run_frame();
  const ClockWarmup clock{request.read_gpu_clock, request.precision.clock_warmup_seconds};
  const auto seconds_now = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  const ClockWarmupResult warmed = warm_until_working_clock(
      clock,
      [&] {
        session.add_warmup_frame();
        session.run_frame();
      },
      seconds_now);
  if (request.before_measured_frames) request.before_measured_frames();
  while (keep_running()) {
    const FrameTimes times = session.run_frame();
    measured.add_frame(times);
    if (request.on_frame) request.on_frame(times);
  }
  if (request.after_measured_frames) request.after_measured_frames();
  if (request.count_work) session.count_work();
  Measurement m = session.result();
  m.clock_warmup = warmed;
  if (warmed.checked) {
    m.columns.set(kClockWarmupFrames, warmed.frames);
    m.columns.set(kClockWarmupSeconds, warmed.seconds);
  }
  add_frame_time_columns(m, request);
  append_note(m.columns, kStatusDetail, clock_warmup_warning(warmed));
  return m;
}

}  // namespace ldm
