#include "harness/stats/intervals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace ldm {
namespace {

// Coverage of [x_(l), x_(n+1-l)] for the median: P(l <= B <= n - l), B ~ Bin(n, 1/2).
double order_statistic_coverage(size_t n, size_t l) {
  if (l == 0 || 2 * l > n + 1) return 0;
  const boost::math::binomial_distribution<double> b(double(n), 0.5);
  return 1.0 - 2.0 * boost::math::cdf(b, double(l - 1));
}

}  // namespace

size_t median_interval_rank(size_t n, double confidence) {
  size_t best = 0;
  // Coverage falls as l grows, so the first l that falls short ends the search.
  for (size_t l = 1; 2 * l <= n + 1; ++l) {
    if (order_statistic_coverage(n, l) < confidence) break;
    best = l;
  }
  return best;
}

Interval median_interval(std::vector<double> values, double confidence) {
  if (values.empty()) throw std::invalid_argument("median_interval: no values");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  const size_t rank = median_interval_rank(n, confidence);
  const size_t l = std::max<size_t>(rank, 1);
  Interval out;
  out.low = values[l - 1];
  out.high = values[n - l];
  // One value covers nothing: its "interval" is a point.
  out.coverage = n == 1 ? 0.0 : order_statistic_coverage(n, l);
  out.reached = rank > 0;
  return out;
}

LogMoments log_moments(const std::vector<double>& values) {
  if (values.size() < 2) throw std::invalid_argument("log_moments: fewer than 2 values");
  LogMoments m;
  m.count = values.size();
  for (double v : values) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("log_moments: a value <= 0");
    m.mean += std::log(v);
  }
  m.mean /= double(m.count);
  double square = 0;
  for (double v : values) square += (std::log(v) - m.mean) * (std::log(v) - m.mean);
  m.stddev = std::sqrt(square / double(m.count - 1));
  return m;
}

Interval log_t_interval(const std::vector<double>& values, double confidence) {
  const LogMoments m = log_moments(values);
  const boost::math::students_t_distribution<double> t(double(m.count - 1));
  const double q = boost::math::quantile(t, 0.5 + confidence / 2);
  const double half = q * m.stddev / std::sqrt(double(m.count));
  Interval out;
  out.low = std::exp(m.mean - half);
  out.high = std::exp(m.mean + half);
  out.coverage = confidence;
  out.reached = true;
  return out;
}

double normal_quantile(double p) { return boost::math::quantile(boost::math::normal_distribution<double>(), p); }

double relative_half_width(const Interval& interval, double centre) {
  if (!(centre > 0)) return std::numeric_limits<double>::infinity();
  return std::max(centre - interval.low, interval.high - centre) / centre;
}

}  // namespace ldm
