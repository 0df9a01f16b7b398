#pragma once
// Intervals of a time estimate, at the two levels where timing variance lives (Kalibera &
// Jones, "Rigorous benchmarking in reasonable time", 2013): the frames of one repetition,
// and the repetitions (independent GL contexts) of one configuration.
//
//   median_interval       the median of one repetition's frames: the distribution-free
//                         interval between two order statistics, whose coverage follows
//                         from the binomial distribution (no assumption on the shape of the
//                         frame times, only that frames are independent draws).
//   log_t_interval        the typical time over repetitions: a Student t interval on the
//                         logarithms of the repetitions' medians (times are ratio-scale and
//                         right-skewed; a log makes the spread relative), i.e. an interval of
//                         their geometric mean with K - 1 degrees of freedom.
// Distributions come from Boost.Math; tests/stats checks both against SciPy.
#include <cstddef>
#include <vector>

namespace ldm {

struct Interval {
  double low = 0, high = 0;
  // What the interval covers: the nominal confidence it was asked for, or less when the
  // sample is too small to reach it (an order-statistic interval of 5 frames covers at most
  // 93.75 %).
  double coverage = 0;
  bool reached = false;  // coverage >= the confidence asked for
};

// The interval [x_(l), x_(n+1-l)] (1-based order statistics) with the largest l whose
// coverage 1 - 2 P(B <= l - 1), B ~ Binomial(n, 1/2), is at least `confidence`; with too few
// values for that, [min, max] and its coverage (reached false). Throws on an empty sample.
Interval median_interval(std::vector<double> values, double confidence = 0.95);

// The largest 1-based l of median_interval for n values (0 when even [min, max] falls short).
size_t median_interval_rank(size_t n, double confidence = 0.95);

// exp(mean(log v) -/+ t_{(1+confidence)/2, K-1} s / sqrt(K)) of K >= 2 positive values.
// Throws with fewer than 2 values or a value <= 0.
Interval log_t_interval(const std::vector<double>& values, double confidence = 0.95);

// The largest relative distance of the interval's ends from `centre`:
// max(centre - low, high - centre) / centre (inf for a centre <= 0).
double relative_half_width(const Interval& interval, double centre);

// The standard normal distribution's quantile: normal_quantile(0.975) = 1.95996...
double normal_quantile(double p);

// Mean and sample standard deviation of the logarithms (the relative spread of positive
// values: a standard deviation of 0.03 is about 3 %). Needs >= 2 positive values.
struct LogMoments {
  double mean = 0, stddev = 0;
  size_t count = 0;
};
LogMoments log_moments(const std::vector<double>& values);

}  // namespace ldm
