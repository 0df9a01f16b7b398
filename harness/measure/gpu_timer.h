#pragma once
// GPU time of named sub-passes, measured with GL timestamp queries around each one.
// Timestamps (not GL_TIME_ELAPSED) so that sub-passes may follow each other freely; the
// results are read once per frame, after the frame's work, so timing adds no stalls inside it.
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_api.h"

namespace ldm {

using FrameTimes = std::vector<std::pair<std::string, double>>;  // sub-pass -> milliseconds

class GpuTimer {
 public:
  GpuTimer() = default;
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin_frame();
  void begin(const std::string& subpass);
  void end();
  // Waits for this frame's queries. A name timed twice in a frame is summed.
  FrameTimes end_frame();

 private:
  GLuint query(size_t index);
  std::vector<GLuint> pool_;
  std::vector<std::string> names_;  // one per begin/end pair
  size_t used_ = 0;
  bool open_ = false;
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
