#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "harness/measure/gpu_timer.h"

namespace ldm {

struct TimingSummary {
  std::string subpass;
  size_t samples = 0;
  double median = 0, min = 0, max = 0, mean = 0, stddev = 0;
};

double median_of(std::vector<double> values);

// The summary of `subpass`, or null when it was not timed.
const TimingSummary* find_summary(const std::vector<TimingSummary>& summaries,
                                  const std::string& subpass);

// Collects the per-frame sub-pass times of the measured frames (warm-up frames are simply
// never added) and summarises each sub-pass, in first-seen order. A sub-pass missing from a
// frame (one that only some frames run, such as a rebuild) counts 0 ms in that frame.
class TimingSeries {
 public:
  void add_frame(const FrameTimes& frame);
  std::vector<TimingSummary> summarize() const;
  size_t frames() const { return frames_; }

 private:
  std::vector<std::string> order_;
  std::vector<std::vector<double>> samples_;
  size_t frames_ = 0;
};

}  // namespace ldm
