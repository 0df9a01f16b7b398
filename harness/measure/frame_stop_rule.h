#pragma once
// How many frames one repetition measures: at least `min_frames`, then more until the
// median's kTimeConfidence interval (order statistics, harness/stats/intervals.h) is within
// `target` of the median, relatively, for every watched sub-pass ("build" and "frame", the
// sums a record leads with), or until the measured frames have taken `cap_seconds`, or
// `max_frames` are reached. nvbench stops the same way on its noise estimate (--max-noise,
// --timeout); this rule watches the interval of the median instead of the standard
// deviation, because frame times are skewed and the record reports medians.
//
// A repetition that stops without meeting the target says so (target_met() false): the
// record warns in status_detail, as it does for a missed reference noise target.
#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "harness/measure/timing_stats.h"

namespace ldm {

struct TimePrecision {
  // Relative half-width of the median's interval to reach; 0 measures exactly min frames.
  double target = 0.03;
  double cap_seconds = 2.0;  // wall time of one repetition's measured frames
  int max_frames = 1000;
  // Where the GPU's clock can be read (NVIDIA): warm-up frames after the fixed ones until it
  // reaches its working clock, for at most this long (harness/measure/clock_warmup.h; 0: off).
  double clock_warmup_seconds = 3.0;
  // The least target worth reaching on this machine (frame_precision_floor(),
  // harness/measure/run_to_run_spread.h: a third of the spread between processes); 0: none.
  double spread_floor = 0.0;

  // The target the frames aim at: `target` raised to `spread_floor` (0 stays 0: exactly
  // the minimum frames).
  double effective_target() const { return target > 0 ? std::max(target, spread_floor) : 0.0; }
};

class FrameStopRule {
 public:
  FrameStopRule(int min_frames, const TimePrecision& precision);
  // Before each measured frame: whether to measure another.
  bool want_another(const TimingSeries& measured);
  // After the last frame: whether every watched sub-pass met the target (true when off).
  bool target_met(const TimingSeries& measured) const;
  // The largest relative half-width among the watched sub-passes (0 with no frames).
  static double worst_half_width(const TimingSeries& measured);

 private:
  int min_frames_;
  TimePrecision precision_;
  std::chrono::steady_clock::time_point started_;
  bool started_clock_ = false;
};

// The sub-passes whose precision the rule watches.
const std::vector<std::string>& watched_subpasses();

}  // namespace ldm
