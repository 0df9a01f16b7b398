// The clock warm-up (harness/measure/clock_warmup.h): warm-up frames after the fixed ones
// until the GPU's SM clock reaches its working level, with a scripted clock and time, so
// that no GPU is needed; and measure() running those frames as warm-up, not measured ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "harness/measuring/measurement.h"
#include "harness/measure/clock_warmup.h"
#include "harness/scene/scene_loader.h"
#include "support/measurement_request.h"
#include "support/test_support.h"

namespace ldm {
namespace {

// A clock that reads the next of `mhz` each time (the last one from then on), of a GPU whose
// maximum is 1980 MHz, and a time that advances by `frame_seconds` per frame run.
struct ScriptedGpu {
  std::vector<double> mhz;
  double frame_seconds = 0.03125;  // exact in binary: slices of 0.125 s hold 4 frames
  size_t reads = 0;
  double now = 0;
  int frames = 0;
  ClockWarmup warmup(double limit = 3.0) {
    return {[this]() -> std::optional<GpuClockReading> {
              const double v = mhz[std::min(reads, mhz.size() - 1)];
              ++reads;
              return GpuClockReading{v, 1980};
            },
            limit, 0.125};
  }
  ClockWarmupResult run(double limit = 3.0) {
    return warm_until_working_clock(
        warmup(limit),
        [this] {
          ++frames;
          now += frame_seconds;
        },
        [this] { return now; });
  }
};

TEST(ClockWarmup, AddsNoFrameWhenTheClockIsAlreadyAtWork) {
  ScriptedGpu gpu{{1980}};
  const ClockWarmupResult r = gpu.run();
  EXPECT_TRUE(r.checked);
  EXPECT_TRUE(r.reached);
  EXPECT_EQ(r.frames, 0);
  EXPECT_EQ(gpu.reads, 1u);
  EXPECT_EQ(clock_warmup_warning(r), "");
}

TEST(ClockWarmup, RunsSlicesOfFramesUntilTheClockRises) {
  // Idle (345), ramping, then at 1980: two slices of 0.125 s, four frames each.
  ScriptedGpu gpu{{345, 900, 1980}};
  const ClockWarmupResult r = gpu.run();
  EXPECT_TRUE(r.reached);
  EXPECT_EQ(r.frames, 8);
  EXPECT_EQ(gpu.frames, 8);
  EXPECT_EQ(gpu.reads, 3u);
  EXPECT_EQ(r.seconds, 0.25);
  EXPECT_EQ(r.last.mhz, 1980);
  // A frame longer than a slice: one frame per reading.
  ScriptedGpu slow{{345, 1980}, 0.5};
  EXPECT_EQ(slow.run().frames, 1);
}

TEST(ClockWarmup, AcceptsASteadyClockHeldBelowItsMaximum) {
  // A power limit holds 1600 MHz (81 % of 1980): steady over two readings is enough.
  ScriptedGpu capped{{345, 1600, 1600}};
  const ClockWarmupResult r = capped.run();
  EXPECT_TRUE(r.reached);
  EXPECT_EQ(capped.reads, 3u);
  // Steady at an idle-like 800 MHz (40 %) is not working: warm until the limit.
  ScriptedGpu stuck{{800}};
  const ClockWarmupResult s = stuck.run(1.0);
  EXPECT_FALSE(s.reached);
  EXPECT_EQ(s.seconds, 1.0);  // 8 slices
  EXPECT_NE(clock_warmup_warning(s).find("800 MHz of its 1980 MHz maximum"), std::string::npos)
      << clock_warmup_warning(s);
}

TEST(ClockWarmup, DoesNothingWhereTheClockCannotBeReadOrWhenOff) {
  int frames = 0;
  const auto frame = [&] { ++frames; };
  const auto now = [] { return 0.0; };
  EXPECT_FALSE(warm_until_working_clock({}, frame, now).checked);
  const ClockWarmup unreadable{[]() -> std::optional<GpuClockReading> { return std::nullopt; }, 3.0, 0.1};
  EXPECT_FALSE(warm_until_working_clock(unreadable, frame, now).checked);
  ScriptedGpu idle{{345}};
  EXPECT_FALSE(warm_until_working_clock(idle.warmup(0.0), frame, now).checked);  // --clock-warmup 0
  EXPECT_EQ(frames, 0);
  // No maximum to judge against: nothing to wait for.
  EXPECT_TRUE(at_working_clock({345, 0}, std::nullopt));
}

TEST(ClockWarmup, MeasureRunsTheAddedFramesAsWarmUpAndSamplesAroundTheMeasuredOnes) {
  MeasurementRequest request = test::measurement_request("psppsll", 2, 16, 16, 1, 3);
  std::vector<double> clocks = {345, 345, 1980};
  size_t reads = 0;
  request.read_gpu_clock = [&]() -> std::optional<GpuClockReading> {
    return GpuClockReading{clocks[std::min(reads++, clocks.size() - 1)], 1980};
  };
  request.precision.clock_warmup_seconds = 60;
  std::vector<std::string> order;
  request.before_measured_frames = [&] { order.push_back("before"); };
  request.on_frame = [&](const FrameTimes&) { order.push_back("frame"); };
  request.after_measured_frames = [&] { order.push_back("after"); };
  const Measurement m = measure(load_scene("cornell"), request);
  EXPECT_EQ(m.status(), BuildStatus::Ok) << m.status_detail();
  EXPECT_TRUE(m.clock_warmup.checked);
  EXPECT_TRUE(m.clock_warmup.reached);
  EXPECT_GE(m.clock_warmup.frames, 2);  // at least one frame per slice, two slices
  EXPECT_EQ(m.frames.size(), 3u);       // the added frames are not measured
  EXPECT_EQ(order, (std::vector<std::string>{"before", "frame", "frame", "frame", "after"}));
  // The raster yardsticks still fall on the first measured frame.
  std::map<std::string, double> first(m.frames[0].begin(), m.frames[0].end());
  EXPECT_EQ(first.count("raster_baseline"), 1u);
}

}  // namespace
}  // namespace ldm
