#pragma once
// Summaries of sub-pass times, with their uncertainty, at the level that carries it:
//   one repetition (one GL context): the median of its frames, and the distribution-free
//     order-statistic interval of that median (it assumes only that frames are independent
//     draws, which they are not across processes; hence repetitions);
//   K >= 2 repetitions: the median of the repetitions' medians, and a Student t interval
//     on their logarithms (K - 1 degrees of freedom), whose width carries the process-to-
//     process spread that no number of frames in one context can show.
// harness/stats/intervals.h holds the statistics.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "harness/measure/gpu_timer.h"
#include "harness/stats/intervals.h"

namespace ldm {

inline constexpr double kTimeConfidence = 0.95;

// The raster yardsticks (harness/passes/raster_baseline.h): sub-passes timed on a subset of
// the measured frames only. A frame without them holds no sample of them (where a frame
// without a rebuild holds a 0 ms one).
inline constexpr const char* kRasterBaselineSubpass = "raster_baseline";
inline constexpr const char* kRasterTouchSubpass = "raster_touch";
inline bool is_subsampled_subpass(const std::string& name) {
  return name == kRasterBaselineSubpass || name == kRasterTouchSubpass;
}

// How a summary's interval was made (the record's time_interval column).
inline constexpr const char* kFrameInterval = "order_statistics_of_frames";
inline constexpr const char* kRepetitionInterval = "t_on_log_repetition_medians";

struct TimingSummary {
  std::string subpass;
  size_t samples = 0;      // frames, over every repetition
  size_t repetitions = 1;
  double median = 0, min = 0, max = 0, mean = 0, stddev = 0;  // stddev: of the frames
  Interval interval;       // kTimeConfidence interval of the median (see above)
  std::vector<double> repetition_medians;  // one per repetition
  // Standard deviation of the logs of the repetitions' medians (about the relative spread
  // between repetitions); NaN with one repetition.
  double repetition_spread = std::numeric_limits<double>::quiet_NaN();
};

double median_of(std::vector<double> values);

// The summary of `subpass`, or null when it was not timed.
const TimingSummary* find_summary(const std::vector<TimingSummary>& summaries,
                                  const std::string& subpass);

// Collects the per-frame sub-pass times of the measured frames (warm-up frames are simply
// never added) and summarises each sub-pass, in first-seen order. A sub-pass missing from a
// frame (one that only some frames run, such as a rebuild) counts 0 ms in that frame,
// unless it is subsampled (is_subsampled_subpass): then the frame holds no sample of it.
class TimingSeries {
 public:
  void add_frame(const FrameTimes& frame);
  // Every sub-pass's frames, in first-seen order (absent ones as 0 ms, except subsampled).
  const std::vector<std::string>& subpasses() const { return order_; }
  const std::vector<double>& samples(size_t subpass) const { return samples_[subpass]; }
  // The frame each of samples(subpass) was taken in (0, 1, 2, ... but for subsampled ones).
  const std::vector<size_t>& sample_frames(size_t subpass) const { return sample_frames_[subpass]; }
  // The samples of `subpass`, or null when it was never timed.
  const std::vector<double>* find(const std::string& subpass) const;
  std::vector<TimingSummary> summarize() const;  // one repetition
  size_t frames() const { return frames_; }

 private:
  std::vector<std::string> order_;
  std::vector<std::vector<double>> samples_;
  std::vector<std::vector<size_t>> sample_frames_;
  size_t frames_ = 0;
};

// One summary per sub-pass over K repetitions (each a series of frames): K = 1 is
// TimingSeries::summarize(); a sub-pass some repetition never timed counts 0 ms there.
std::vector<TimingSummary> summarize_repetitions(const std::vector<TimingSeries>& repetitions);

}  // namespace ldm
