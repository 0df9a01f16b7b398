#include "harness/measure/timing_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ldm {
namespace {

TimingSummary frame_summary(const std::string& subpass, const std::vector<double>& values) {
  TimingSummary s;
  s.subpass = subpass;
  s.samples = values.size();
  s.median = median_of(values);
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
  double square = 0;
  for (double v : values) square += (v - s.mean) * (v - s.mean);
  s.stddev = values.size() > 1 ? std::sqrt(square / double(values.size() - 1)) : 0.0;
  s.interval = median_interval(values, kTimeConfidence);
  s.repetition_medians = {s.median};
  return s;
}

}  // namespace

double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const TimingSummary* find_summary(const std::vector<TimingSummary>& summaries,
                                  const std::string& subpass) {
  for (const auto& s : summaries)
    if (s.subpass == subpass) return &s;
  return nullptr;
}

void TimingSeries::add_frame(const FrameTimes& frame) {
  const size_t index_of_frame = frames_++;
  std::vector<bool> seen(order_.size(), false);
  for (const auto& [name, ms] : frame) {
    auto it = std::find(order_.begin(), order_.end(), name);
    size_t index = size_t(it - order_.begin());
    if (it == order_.end()) {
      order_.push_back(name);
      seen.push_back(false);
      // Absent from the earlier frames: 0 ms there (no sample, for a subsampled one).
      const bool zeros = !is_subsampled_subpass(name);
      samples_.emplace_back(zeros ? index_of_frame : 0, 0.0);
      sample_frames_.emplace_back();
      if (zeros)
        for (size_t f = 0; f < index_of_frame; ++f) sample_frames_.back().push_back(f);
    }
    if (seen[index]) {  // a name timed twice in one frame (end_frame() sums, but be safe)
      samples_[index].back() += ms;
      continue;
    }
    seen[index] = true;
    samples_[index].push_back(ms);
    sample_frames_[index].push_back(index_of_frame);
  }
  // A sub-pass that only some frames run (a rebuild, a reallocation) took 0 ms in the rest.
  for (size_t i = 0; i < order_.size(); ++i)
    if (!seen[i] && !is_subsampled_subpass(order_[i])) {
      samples_[i].push_back(0.0);
      sample_frames_[i].push_back(index_of_frame);
    }
}

const std::vector<double>* TimingSeries::find(const std::string& subpass) const {
  const auto it = std::find(order_.begin(), order_.end(), subpass);
  return it == order_.end() ? nullptr : &samples_[size_t(it - order_.begin())];
}

std::vector<TimingSummary> TimingSeries::summarize() const {
  std::vector<TimingSummary> out;
  for (size_t i = 0; i < order_.size(); ++i)
    if (!samples_[i].empty()) out.push_back(frame_summary(order_[i], samples_[i]));
  return out;
}

std::vector<TimingSummary> summarize_repetitions(const std::vector<TimingSeries>& repetitions) {
  if (repetitions.size() == 1) return repetitions.front().summarize();
  std::vector<std::string> order;
  for (const auto& r : repetitions)
    for (const auto& name : r.subpasses())
      if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
  std::vector<TimingSummary> out;
  for (const auto& name : order) {
    std::vector<double> pooled, medians;
    for (const auto& r : repetitions) {
      const std::vector<double>* values = r.find(name);
      // Never timed there: 0 ms a frame, or no sample for a subsampled sub-pass.
      const std::vector<double> zeros(is_subsampled_subpass(name) ? 0 : r.frames(), 0.0);
      const std::vector<double>& v = values ? *values : zeros;
      if (v.empty()) continue;
      pooled.insert(pooled.end(), v.begin(), v.end());
      medians.push_back(median_of(v));
    }
    if (pooled.empty()) continue;
    TimingSummary s = frame_summary(name, pooled);
    s.repetitions = repetitions.size();
    s.repetition_medians = medians;
    s.median = median_of(medians);
    const bool positive = std::all_of(medians.begin(), medians.end(), [](double m) { return m > 0; });
    if (positive) {
      s.interval = log_t_interval(medians, kTimeConfidence);
      s.repetition_spread = log_moments(medians).stddev;
    } else {
      // A sub-pass most frames skip (a rebuild) has zero medians: no log scale; the
      // distribution-free interval over the repetitions' medians instead.
      s.interval = median_interval(medians, kTimeConfidence);
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace ldm
