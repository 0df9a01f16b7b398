#pragma once
// The frame loop every measurement runs (measure() with a structure, measure_peer() without):
// `request.warmup` warm-up frames, then measured frames while request.keep_running says so
// (unset: exactly request.frames), each frame timed sub-pass by sub-pass between
// begin_frame() and end_frame(). Warm-up frames are judged (after_frame) but not kept.
#include <functional>
#include <vector>

#include "harness/app/measurement.h"
#include "harness/measure/gpu_timer.h"

namespace ldm {

struct FrameLoop {
  // One frame's GPU (or CPU) work, every sub-pass timed by `timer`.
  std::function<void(GpuTimer& timer)> render;
  // Untimed, after every frame, warm-up included (verification of what the frame built).
  std::function<void(bool warmup)> after_frame;
  // Adds the sums ("build", "frame") to a measured frame's times.
  std::function<void(FrameTimes& times)> add_sums;
};

// Runs the frames of `request` and returns the measured ones, each also given to
// request.on_frame as it completes.
std::vector<FrameTimes> run_frame_loop(const MeasurementRequest& request, GpuTimer& timer,
                                       const FrameLoop& loop);

}  // namespace ldm
