#pragma once
// Tests of a time change between two runs, on the level that carries the variance: the
// repetitions (each an independent GL context with its own offset: caches, clocks, load),
// not the frames of one process, which share that offset and are not independent.
//
// Every test works on log times, so that its effect is a ratio (new / base) and its
// standard error a relative spread:
//   welch_log_t           K_base, K_new >= 2 repetitions: Welch's t test on the logs of the
//                         repetitions' medians (unequal variances, Welch-Satterthwaite df).
//   paired_log_t          an interleaved A/B session (repetition j of A and of B measured
//                         side by side): a paired t test on the K log ratios, which cancels
//                         the drift and load the pair shares.
//   assumed_spread_z      a side with a single repetition, whose process-to-process spread
//                         cannot be seen: its frames are taken as independent (their median's
//                         standard error) *and* an assumed process spread is added, so the
//                         verdict is conservative rather than blind to it.
// minimum_detectable_change() turns a test's standard error into the smallest change it
// could have detected at a significance level and power (non-central t, Boost.Math), and
// holm_adjusted() corrects p values for testing many configurations and sub-passes at once.
#include <limits>
#include <string>
#include <vector>

namespace ldm {

enum class TimeTestMethod { WelchLogT, PairedLogT, AssumedSpreadZ };
const char* time_test_method_name(TimeTestMethod method);  // welch_log_t, ...

struct TimeTest {
  TimeTestMethod method = TimeTestMethod::WelchLogT;
  double log_ratio = 0;  // estimated log(new / base)
  double se = 0;         // its standard error
  double df = std::numeric_limits<double>::infinity();  // inf: a normal (z) test
  double p_value = 1;    // two-sided
};

// K >= 2 positive values on each side; throws std::invalid_argument otherwise.
TimeTest welch_log_t(const std::vector<double>& base, const std::vector<double>& next);
// The same number K >= 2 of positive values on each side, base[j] paired with next[j].
TimeTest paired_log_t(const std::vector<double>& base, const std::vector<double>& next);
// Medians with their relative standard errors (from the frames); `process_spread` is the
// assumed relative standard deviation between two processes' medians of the same work,
// added on each side.
TimeTest assumed_spread_z(double base_median, double base_se_rel, double next_median,
                          double next_se_rel, double process_spread);

// A normal test of an estimated log ratio with standard error `se` (a side of one
// repetition, whose spread is partly assumed: method AssumedSpreadZ).
TimeTest log_z_test(double log_ratio, double se);

// The relative standard error of a median from its order-statistic interval (interval
// width over twice the normal quantile of its coverage); inf when it covers nothing.
double median_relative_se(double median, double low, double high, double coverage);

// The smallest |log change| a two-sided test with standard error `se` and `df` degrees of
// freedom detects with probability `power` at significance `alpha`: inf when se is inf.
double minimum_detectable_log_change(double se, double df, double alpha, double power);

// Holm's step-down adjusted p values, in the input's order (each in [0, 1]): rejecting
// those below alpha keeps the chance of any false verdict at most alpha, whatever the
// dependence between the tests (configurations share a machine; build and frame overlap).
std::vector<double> holm_adjusted(const std::vector<double>& p_values);

}  // namespace ldm
