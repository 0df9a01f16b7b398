#include "harness/measure/gpu_timer.h"

#include "harness/util/error.h"

namespace ldm {

TimerSource default_timer_source(const std::string& gl_renderer) {
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "SwiftShader", "lavapipe"})
    if (gl_renderer.find(software) != std::string::npos) return TimerSource::FencedWallClock;
  return TimerSource::GpuTimestamps;
}

const char* timer_source_name(TimerSource source) {
  switch (source) {
    case TimerSource::GpuTimestamps: return "gl_timestamp";
    case TimerSource::CpuWallClock: return "cpu_wall";
    default: return "fenced_wall_clock";
  }
}

GpuTimer::~GpuTimer() {
  if (!pool_.empty()) glDeleteQueries(GLsizei(pool_.size()), pool_.data());
}

GLuint GpuTimer::query(size_t index) {
  while (pool_.size() <= index) {
    GLuint id = 0;
    glGenQueries(1, &id);
    pool_.push_back(id);
  }
  return pool_[index];
}

void GpuTimer::begin_frame() {
  names_.clear();
  wall_ms_.clear();
  used_ = 0;
  open_ = false;
}

void GpuTimer::begin(const std::string& subpass) {
  if (open_) throw GpuError("GpuTimer: sub-pass '" + subpass + "' begun inside another");
  names_.push_back(subpass);
  if (source_ == TimerSource::GpuTimestamps) {
    glQueryCounter(query(used_++), GL_TIMESTAMP);
  } else {
    if (source_ == TimerSource::FencedWallClock) glFinish();
    wall_start_ = std::chrono::steady_clock::now();
  }
  open_ = true;
  if (observer_) observer_->subpass_begun(subpass);
}

void GpuTimer::end() {
  if (!open_) throw GpuError("GpuTimer: end() without begin()");
  if (observer_) observer_->subpass_ended(names_.back());
  if (source_ == TimerSource::GpuTimestamps) {
    glQueryCounter(query(used_++), GL_TIMESTAMP);
  } else {
    if (source_ == TimerSource::FencedWallClock) glFinish();
    wall_ms_.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_start_)
            .count());
  }
  open_ = false;
}

FrameTimes GpuTimer::end_frame() {
  if (open_) throw GpuError("GpuTimer: frame ended inside sub-pass '" + names_.back() + "'");
  FrameTimes times;
  for (size_t i = 0; i < names_.size(); ++i) {
    double ms = 0;
    if (source_ == TimerSource::GpuTimestamps) {
      GLuint64 start = 0, stop = 0;
      glGetQueryObjectui64v(pool_[2 * i], GL_QUERY_RESULT, &start);
      glGetQueryObjectui64v(pool_[2 * i + 1], GL_QUERY_RESULT, &stop);
      ms = double(stop - start) * 1e-6;
    } else {
      ms = wall_ms_[i];
    }
    bool merged = false;
    for (auto& [name, total] : times) {
      if (name == names_[i]) {
        total += ms;
        merged = true;
      }
    }
    if (!merged) times.emplace_back(names_[i], ms);
  }
  return times;
}

}  // namespace ldm
