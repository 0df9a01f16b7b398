#include "harness/measure/timing_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ldm {

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
  ++frames_;
  for (const auto& [name, ms] : frame) {
    auto it = std::find(order_.begin(), order_.end(), name);
    size_t index = size_t(it - order_.begin());
    if (it == order_.end()) {
      order_.push_back(name);
      samples_.emplace_back(frames_ - 1, 0.0);  // absent from the earlier frames: 0 ms there
    }
    samples_[index].push_back(ms);
  }
  // A sub-pass that only some frames run (a rebuild, a reallocation) took 0 ms in the rest.
  for (auto& values : samples_)
    if (values.size() < frames_) values.push_back(0.0);
}

std::vector<TimingSummary> TimingSeries::summarize() const {
  std::vector<TimingSummary> out;
  for (size_t i = 0; i < order_.size(); ++i) {
    const auto& values = samples_[i];
    TimingSummary s;
    s.subpass = order_[i];
    s.samples = values.size();
    s.median = median_of(values);
    s.min = *std::min_element(values.begin(), values.end());
    s.max = *std::max_element(values.begin(), values.end());
    s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
    double square = 0;
    for (double v : values) square += (v - s.mean) * (v - s.mean);
    s.stddev = values.size() > 1 ? std::sqrt(square / double(values.size() - 1)) : 0.0;
    out.push_back(s);
  }
  return out;
}

}  // namespace ldm
