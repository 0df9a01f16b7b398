#include "harness/stats/time_tests.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <boost/math/distributions/non_central_t.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/tools/roots.hpp>

#include "harness/stats/intervals.h"

namespace ldm {
namespace {

double two_sided_p(double statistic, double df) {
  const double x = -std::fabs(statistic);
  if (!std::isfinite(df)) return std::min(1.0, 2 * boost::math::cdf(boost::math::normal(), x));
  return std::min(1.0, 2 * boost::math::cdf(boost::math::students_t(df), x));
}

TimeTest finish(TimeTestMethod method, double log_ratio, double se, double df) {
  TimeTest t;
  t.method = method;
  t.log_ratio = log_ratio;
  t.se = se;
  t.df = df;
  if (se > 0 && std::isfinite(se))
    t.p_value = two_sided_p(log_ratio / se, df);
  else
    // No spread at all: any difference is certain (identical sides give none); no
    // knowledge (inf) is never significant.
    t.p_value = se == 0 && log_ratio != 0 ? 0.0 : 1.0;
  return t;
}

double critical_value(double alpha, double df) {
  if (!std::isfinite(df)) return boost::math::quantile(boost::math::normal(), 1 - alpha / 2);
  return boost::math::quantile(boost::math::students_t(df), 1 - alpha / 2);
}

// P(|T| > c) for T with non-centrality `ncp` (normal when df is infinite).
double rejection_probability(double ncp, double c, double df) {
  if (!std::isfinite(df)) {
    const boost::math::normal z(ncp, 1);
    return boost::math::cdf(boost::math::complement(z, c)) + boost::math::cdf(z, -c);
  }
  const boost::math::non_central_t t(df, ncp);
  return boost::math::cdf(boost::math::complement(t, c)) + boost::math::cdf(t, -c);
}

}  // namespace

const char* time_test_method_name(TimeTestMethod method) {
  switch (method) {
    case TimeTestMethod::WelchLogT: return "welch_log_t";
    case TimeTestMethod::PairedLogT: return "paired_log_t";
    case TimeTestMethod::AssumedSpreadZ: return "assumed_spread_z";
  }
  return "?";
}

TimeTest welch_log_t(const std::vector<double>& base, const std::vector<double>& next) {
  const LogMoments a = log_moments(base), b = log_moments(next);
  const double va = a.stddev * a.stddev / double(a.count), vb = b.stddev * b.stddev / double(b.count);
  const double se = std::sqrt(va + vb);
  // Welch-Satterthwaite; with no spread on either side the df do not matter.
  const double df = va + vb > 0 ? (va + vb) * (va + vb) /
                                      (va * va / double(a.count - 1) + vb * vb / double(b.count - 1))
                                : double(a.count + b.count - 2);
  return finish(TimeTestMethod::WelchLogT, b.mean - a.mean, se, df);
}

TimeTest paired_log_t(const std::vector<double>& base, const std::vector<double>& next) {
  if (base.size() != next.size() || base.size() < 2)
    throw std::invalid_argument("paired_log_t: needs the same K >= 2 values on each side");
  std::vector<double> ratios;
  for (size_t j = 0; j < base.size(); ++j) {
    if (!(base[j] > 0) || !(next[j] > 0)) throw std::invalid_argument("paired_log_t: a value <= 0");
    ratios.push_back(next[j] / base[j]);
  }
  const LogMoments d = log_moments(ratios);
  return finish(TimeTestMethod::PairedLogT, d.mean, d.stddev / std::sqrt(double(d.count)),
                double(d.count - 1));
}

TimeTest assumed_spread_z(double base_median, double base_se_rel, double next_median,
                          double next_se_rel, double process_spread) {
  if (!(base_median > 0) || !(next_median > 0))
    throw std::invalid_argument("assumed_spread_z: a median <= 0");
  const double variance = base_se_rel * base_se_rel + next_se_rel * next_se_rel +
                          2 * process_spread * process_spread;
  return finish(TimeTestMethod::AssumedSpreadZ, std::log(next_median / base_median),
                std::sqrt(variance), std::numeric_limits<double>::infinity());
}

TimeTest log_z_test(double log_ratio, double se) {
  return finish(TimeTestMethod::AssumedSpreadZ, log_ratio, se, std::numeric_limits<double>::infinity());
}

double median_relative_se(double median, double low, double high, double coverage) {
  if (!(median > 0) || !(coverage > 0) || coverage >= 1) return std::numeric_limits<double>::infinity();
  const double z = boost::math::quantile(boost::math::normal(), 0.5 + coverage / 2);
  return (high - low) / (2 * z) / median;
}

double minimum_detectable_log_change(double se, double df, double alpha, double power) {
  if (!std::isfinite(se)) return std::numeric_limits<double>::infinity();
  if (se <= 0) return 0;
  const double c = critical_value(alpha, df);
  // The rejection probability grows with the non-centrality; find where it reaches power.
  double high = c + 10;
  while (rejection_probability(high, c, df) < power) high *= 2;
  boost::uintmax_t iterations = 200;
  const auto [lo, hi] = boost::math::tools::toms748_solve(
      [&](double ncp) { return rejection_probability(ncp, c, df) - power; }, 0.0, high,
      boost::math::tools::eps_tolerance<double>(40), iterations);
  return se * (lo + hi) / 2;
}

std::vector<double> holm_adjusted(const std::vector<double>& p) {
  const size_t m = p.size();
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<double> adjusted(m);
  double running = 0;
  for (size_t i = 0; i < m; ++i) {
    running = std::max(running, std::min(1.0, double(m - i) * p[order[i]]));
    adjusted[order[i]] = running;
  }
  return adjusted;
}

}  // namespace ldm
