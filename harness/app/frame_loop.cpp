#include "harness/app/frame_loop.h"

#include <utility>

namespace ldm {

std::vector<FrameTimes> run_frame_loop(const MeasurementRequest& request, GpuTimer& timer,
                                       const FrameLoop& loop) {
  auto keep_running = [&, measured = 0]() mutable {
    if (request.keep_running) return request.keep_running();  // Google Benchmark's loop
    return measured++ < request.frames;
  };
  std::vector<FrameTimes> frames;
  for (int frame = 0;; ++frame) {
    const bool warmup = frame < request.warmup;
    if (!warmup && !keep_running()) break;
    timer.begin_frame();
    loop.render(timer);
    FrameTimes times = timer.end_frame();
    if (loop.after_frame) loop.after_frame(warmup);
    if (warmup) continue;  // judged, but not measured
    loop.add_sums(times);
    if (request.on_frame) request.on_frame(times);
    frames.push_back(std::move(times));
  }
  return frames;
}

}  // namespace ldm
