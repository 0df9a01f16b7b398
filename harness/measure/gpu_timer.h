#pragma once
// Time of named sub-passes. Two sources:
//  - GpuTimestamps: GL timestamp queries around each sub-pass (not GL_TIME_ELAPSED, so that
//    sub-passes may follow each other freely); results are read once per frame, so timing
//    adds no stalls inside it. What a GPU's own clock says.
//  - FencedWallClock: glFinish() before and after each sub-pass and the CPU's steady clock in
//    between. For software rasterisers (Mesa llvmpipe), whose timestamp queries are taken
//    when work is queued to the rasteriser threads rather than when it completes: there they
//    miss most of a pass (seen: 9 ms reported for a construction that takes 22 ms).
//  - CpuWallClock: the CPU's steady clock alone, no GL calls: for passes that run on the CPU
//    (the Embree ray-traced AO peer), whose time is CPU wall time, not a GPU's.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_api.h"

namespace ldm {

using FrameTimes = std::vector<std::pair<std::string, double>>;  // sub-pass -> milliseconds

enum class TimerSource { GpuTimestamps, FencedWallClock, CpuWallClock };

// Told where each sub-pass of a GpuTimer begins and ends (the counting replay's work
// counters attribute what the shaders count to the sub-pass running: work_counters.h).
class SubpassObserver {
 public:
  virtual ~SubpassObserver() = default;
  virtual void subpass_begun(const std::string& subpass) = 0;
  virtual void subpass_ended(const std::string& subpass) = 0;
};

// Software renderers (llvmpipe, softpipe, swrast) get the fenced wall clock, GPUs timestamps.
TimerSource default_timer_source(const std::string& gl_renderer);
const char* timer_source_name(TimerSource source);

class GpuTimer {
 public:
  explicit GpuTimer(TimerSource source = TimerSource::GpuTimestamps) : source_(source) {}
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin_frame();
  void begin(const std::string& subpass);
  void end();
  // Waits for this frame's queries. A name timed twice in a frame is summed.
  FrameTimes end_frame();
  // Told of every begin() and end() from now on (null: none); not owned.
  void set_observer(SubpassObserver* observer) { observer_ = observer; }

 private:
  GLuint query(size_t index);
  TimerSource source_;
  std::vector<GLuint> pool_;
  std::vector<double> wall_ms_;  // the wall clocks: one per begin/end pair
  std::chrono::steady_clock::time_point wall_start_;
  std::vector<std::string> names_;  // one per begin/end pair
  size_t used_ = 0;
  bool open_ = false;
  SubpassObserver* observer_ = nullptr;
};

// RAII helper: times the enclosing scope as one sub-pass.
class ScopedSubpass {
 public:
  ScopedSubpass(GpuTimer* timer, const std::string& name) : timer_(timer) {
    if (timer_) timer_->begin(name);
  }
  ~ScopedSubpass() {
    if (timer_) timer_->end();
  }
  ScopedSubpass(const ScopedSubpass&) = delete;
  ScopedSubpass& operator=(const ScopedSubpass&) = delete;

 private:
  GpuTimer* timer_;
};

}  // namespace ldm
