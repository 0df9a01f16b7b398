#include "harness/measure/frame_stop_rule.h"

#include <algorithm>

namespace ldm {

const std::vector<std::string>& watched_subpasses() {
  static const std::vector<std::string> names = {"build", "frame"};
  return names;
}

FrameStopRule::FrameStopRule(int min_frames, const TimePrecision& precision)
    : min_frames_(std::max(1, min_frames)), precision_(precision) {}

double FrameStopRule::worst_half_width(const TimingSeries& measured) {
  double worst = 0;
  for (const auto& name : watched_subpasses()) {
    const std::vector<double>* values = measured.find(name);
    if (!values || values->empty()) continue;
    const Interval interval = median_interval(*values, kTimeConfidence);
    // Too few frames for the confidence: not yet known to be precise.
    const double width = interval.reached ? relative_half_width(interval, median_of(*values))
                                          : std::numeric_limits<double>::infinity();
    worst = std::max(worst, width);
  }
  return worst;
}

bool FrameStopRule::target_met(const TimingSeries& measured) const {
  return precision_.effective_target() <= 0 || worst_half_width(measured) <= precision_.effective_target();
}

bool FrameStopRule::want_another(const TimingSeries& measured) {
  if (!started_clock_) {
    started_ = std::chrono::steady_clock::now();
    started_clock_ = true;
  }
  const int frames = int(measured.frames());
  if (frames < min_frames_) return true;
  if (precision_.effective_target() <= 0 || frames >= precision_.max_frames) return false;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  if (elapsed >= precision_.cap_seconds) return false;
  return !target_met(measured);
}

}  // namespace ldm
