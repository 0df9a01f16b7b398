// harness/stats and the timing summaries built on them: every interval, test, MDE and
// correction checked against SciPy (tests/stats/scipy_oracle.py) or hand-computed cases,
// and the stop rule, the repetition summaries and the digits on synthetic samples with
// known answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>

#include "harness/measure/run_to_run_spread.h"
#include "harness/measuring/timing_columns.h"
#include "harness/measure/frame_stop_rule.h"
#include "harness/measure/timing_stats.h"
#include "harness/stats/intervals.h"
#include "harness/stats/time_tests.h"
#include "support/test_support.h"

namespace ldm {
namespace {

using nlohmann::json;

// SciPy's answers to `cases` (one JSON object each, see scipy_oracle.py).
json scipy(const json& cases) {
  const std::string dir = test::make_temp_dir("ldm-stats-oracle");
  const std::string input = dir + "/cases.json";
  std::ofstream(input) << cases.dump();
  std::string output;
  const int status = test::run_command(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR +
                                           "/stats/scipy_oracle.py < " + input, &output);
  // Not a skip: CI installs SciPy (scripts/setup.sh); a missing module must be visible.
  EXPECT_EQ(status, 0) << output;
  return status == 0 ? json::parse(output) : json::array();
}

std::vector<double> lognormal(std::mt19937& rng, size_t n, double median, double spread) {
  std::normal_distribution<double> z(0, 1);
  std::vector<double> v;
  for (size_t i = 0; i < n; ++i) v.push_back(median * std::exp(spread * z(rng)));
  return v;
}

TEST(MedianInterval, RanksAndCoverageMatchTheBinomialForEverySampleSize) {
  json cases = json::array();
  for (int n = 1; n <= 300; ++n)
    for (double confidence : {0.9, 0.95, 0.99}) cases.push_back({{"kind", "median_rank"}, {"n", n}, {"confidence", confidence}});
  const json answers = scipy(cases);
  ASSERT_EQ(answers.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    const size_t n = cases[i]["n"];
    const double confidence = cases[i]["confidence"];
    EXPECT_EQ(median_interval_rank(n, confidence), answers[i]["rank"].get<size_t>()) << "n " << n;
    std::vector<double> values(n);
    for (size_t k = 0; k < n; ++k) values[k] = double(k);
    std::shuffle(values.begin(), values.end(), std::mt19937(unsigned(n)));  // 0..n-1, unsorted
    const Interval interval = median_interval(values, confidence);
    const size_t l = std::max<size_t>(answers[i]["rank"].get<size_t>(), 1);
    EXPECT_EQ(interval.low, double(l - 1)) << "n " << n;
    EXPECT_EQ(interval.high, double(n - l)) << "n " << n;
    if (n > 1) EXPECT_NEAR(interval.coverage, answers[i]["coverage"].get<double>(), 1e-12) << "n " << n;
    EXPECT_EQ(interval.reached, answers[i]["rank"].get<size_t>() > 0) << "n " << n;
  }
  // The textbook case: 95 % needs 6 values ([min, max] covers 1 - 2/64 = 96.875 %).
  EXPECT_EQ(median_interval_rank(5, 0.95), 0u);
  EXPECT_EQ(median_interval_rank(6, 0.95), 1u);
  EXPECT_THROW(median_interval({}, 0.95), std::invalid_argument);
}

TEST(MedianInterval, CoversTheTrueMedianAsOftenAsItSays) {
  std::mt19937 rng(7);
  std::exponential_distribution<double> skewed(1.0);  // frame times are right-skewed
  const double true_median = std::log(2.0);
  int covered = 0;
  const int trials = 4000;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> v(25);
    for (double& x : v) x = skewed(rng);
    const Interval i = median_interval(v, 0.95);
    covered += i.low <= true_median && true_median <= i.high;
  }
  // Coverage for n = 25 is 1 - 2 P(B <= 7) = 0.9567; 4000 trials: sd 0.0032.
  EXPECT_NEAR(double(covered) / trials, 0.9567, 0.013);
}

TEST(LogTInterval, MatchesScipyAndRefusesWhatHasNoLog) {
  json cases = json::array();
  const std::vector<std::vector<double>> samples = {{10, 11}, {9.5, 10, 10.8, 12.1, 9.9}, {1, 2, 4, 8, 16, 32}};
  for (const auto& v : samples) cases.push_back({{"kind", "log_t_interval"}, {"values", v}, {"confidence", 0.95}});
  const json answers = scipy(cases);
  ASSERT_EQ(answers.size(), samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    const Interval interval = log_t_interval(samples[i], 0.95);
    EXPECT_NEAR(interval.low, answers[i]["low"].get<double>(), 1e-9 * interval.low);
    EXPECT_NEAR(interval.high, answers[i]["high"].get<double>(), 1e-9 * interval.high);
  }
  EXPECT_THROW(log_t_interval({3.0}), std::invalid_argument);
  EXPECT_THROW(log_t_interval({3.0, 0.0}), std::invalid_argument);
}

using SamplePairs = std::vector<std::pair<std::vector<double>, std::vector<double>>>;

// test(a, b) on each pair: its statistic and p value are scipy's test `kind` ("welch",
// "paired") on the logs.
template <typename Test>
void expect_as_scipy(const char* kind, const SamplePairs& pairs, Test test) {
  json cases = json::array();
  for (const auto& [a, b] : pairs) cases.push_back({{"kind", kind}, {"a", a}, {"b", b}});
  const json answers = scipy(cases);
  ASSERT_EQ(answers.size(), pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    const TimeTest t = test(pairs[i].first, pairs[i].second);
    EXPECT_NEAR(t.log_ratio / t.se, answers[i]["statistic"].get<double>(), 1e-9) << kind << " " << i;
    EXPECT_NEAR(t.p_value, answers[i]["p"].get<double>(), 1e-9) << kind << " " << i;
  }
}

TEST(TimeTests, WelchAndPairedMatchScipyOnLogs) {
  std::mt19937 rng(11);
  SamplePairs pairs;
  for (int i = 0; i < 40; ++i) {
    const size_t ka = 2 + size_t(i % 7), kb = 2 + size_t((i * 3) % 6);
    pairs.push_back({lognormal(rng, ka, 10, 0.02 + 0.01 * (i % 5)), lognormal(rng, kb, 10 * (1 + 0.01 * (i % 9)), 0.03)});
  }
  expect_as_scipy("welch", pairs, [](const auto& a, const auto& b) { return welch_log_t(a, b); });
  SamplePairs matched;
  for (int i = 0; i < 40; ++i) {
    const size_t k = 2 + size_t(i % 8);
    const std::vector<double> load = lognormal(rng, k, 10, 0.2);  // shared by each pair
    std::vector<double> a = load, b = load;
    for (size_t j = 0; j < k; ++j) {
      a[j] *= std::exp(0.01 * std::sin(double(i + j)));
      b[j] *= (1 + 0.01 * (i % 6)) * std::exp(0.01 * std::cos(double(i * j)));
    }
    matched.push_back({a, b});
  }
  expect_as_scipy("paired", matched, [](const auto& a, const auto& b) { return paired_log_t(a, b); });
  EXPECT_THROW(paired_log_t({1, 2}, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(welch_log_t({1}, {1, 2}), std::invalid_argument);
}

TEST(TimeTests, MinimumDetectableChangeHasTheStatedPower) {
  // At the MDE's non-centrality SciPy's non-central t gives the power asked for.
  json cases = json::array();
  std::vector<std::pair<double, double>> settings;  // df (inf: normal), alpha
  for (double df : {2.0, 4.0, 7.5, 20.0, std::numeric_limits<double>::infinity()})
    for (double alpha : {0.05, 0.005})
      for (double power : {0.8, 0.9}) {
        const double se = 0.03;
        const double mde = minimum_detectable_log_change(se, df, alpha, power);
        cases.push_back({{"kind", "power"}, {"df", std::isfinite(df) ? json(df) : json(nullptr)},
                         {"alpha", alpha}, {"ncp", mde / se}, {"expected", power}});
      }
  const json answers = scipy(cases);
  ASSERT_EQ(answers.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i)
    EXPECT_NEAR(answers[i]["power"].get<double>(), cases[i]["expected"].get<double>(), 1e-6) << cases[i].dump();
  // And by simulation: Welch's test on K = 5 lognormal repetitions a side, the true change
  // set to the MDE the observed spread implies, rejects about `power` of the time.
  std::mt19937 rng(3);
  const double spread = 0.04, alpha = 0.05;
  const TimeTest typical = welch_log_t(lognormal(rng, 5, 10, spread), lognormal(rng, 5, 10, spread));
  const double se = spread * std::sqrt(2.0 / 5.0);
  const double mde = minimum_detectable_log_change(se, 8.0, alpha, 0.8);
  (void)typical;
  int rejected = 0;
  const int trials = 3000;
  for (int t = 0; t < trials; ++t) {
    const TimeTest test = welch_log_t(lognormal(rng, 5, 10, spread), lognormal(rng, 5, 10 * std::exp(mde), spread));
    rejected += test.p_value < alpha;
  }
  // The nominal 0.8 uses the true se and df 8; Welch estimates both, a little lower power.
  EXPECT_NEAR(double(rejected) / trials, 0.8, 0.05);
  EXPECT_EQ(minimum_detectable_log_change(std::numeric_limits<double>::infinity(), 3, 0.05, 0.8),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(minimum_detectable_log_change(0, 3, 0.05, 0.8), 0);
}

TEST(TimeTests, HolmMatchesTheHandComputedStepDown) {
  // sorted 0.005, 0.01, 0.03, 0.04 -> 4*0.005 = 0.02, 3*0.01 = 0.03, 2*0.03 = 0.06,
  // max(0.06, 1*0.04) = 0.06; back in the input's order.
  const std::vector<double> adjusted = holm_adjusted({0.01, 0.04, 0.03, 0.005});
  const std::vector<double> expected = {0.03, 0.06, 0.06, 0.02};
  ASSERT_EQ(adjusted.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(adjusted[i], expected[i], 1e-15) << i;
  EXPECT_EQ(holm_adjusted({0.6, 0.9}), (std::vector<double>{1.0, 1.0}));
  EXPECT_TRUE(holm_adjusted({}).empty());
}

TEST(TimeTests, FamilyWiseFalseVerdictsStayBelowAlphaUnderTheNull) {
  // 16 tests (8 configurations x 2 sub-passes) of identical builds with process offsets:
  // Holm keeps the chance of any false rejection at most alpha.
  std::mt19937 rng(5);
  int any_false = 0;
  const int trials = 1000;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> p;
    for (int test = 0; test < 16; ++test)
      p.push_back(welch_log_t(lognormal(rng, 3, 10, 0.1), lognormal(rng, 3, 10, 0.1)).p_value);
    const auto adjusted = holm_adjusted(p);
    any_false += std::any_of(adjusted.begin(), adjusted.end(), [](double q) { return q < 0.05; });
  }
  EXPECT_LE(double(any_false) / trials, 0.05 + 0.02);  // sd of the rate ~0.007
}

TEST(TimeTests, SingleRepetitionTestCarriesTheAssumedSpread) {
  // Frames alone (a se of 0.5 %) would call a 10 % change certain; the assumed 10 %
  // process spread makes it undetectable.
  const TimeTest frames_only = assumed_spread_z(10, 0.005, 11, 0.005, 0.0);
  EXPECT_LT(frames_only.p_value, 1e-6);
  const TimeTest honest = assumed_spread_z(10, 0.005, 11, 0.005, 0.10);
  EXPECT_GT(honest.p_value, 0.3);
  EXPECT_NEAR(honest.se, std::sqrt(2 * 0.005 * 0.005 + 2 * 0.01), 1e-15);
  EXPECT_EQ(honest.method, TimeTestMethod::AssumedSpreadZ);
  EXPECT_EQ(median_relative_se(10, 9, 11, 0.0), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(median_relative_se(10, 9, 11, 0.95), 1.0 / 1.959963984540054 / 10, 1e-12);
}

TimingSeries series_of(const std::vector<double>& frame_ms) {
  TimingSeries s;
  for (double ms : frame_ms) s.add_frame({{"build", ms / 2}, {"frame", ms}});
  return s;
}

TEST(RepetitionSummaries, MedianOfMediansWithATIntervalOnTheirLogs) {
  const std::vector<TimingSeries> reps = {series_of({10, 11, 12}), series_of({20, 21, 19}), series_of({14, 15, 16})};
  const auto summaries = summarize_repetitions(reps);
  const TimingSummary* frame = find_summary(summaries, "frame");
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->repetitions, 3u);
  EXPECT_EQ(frame->samples, 9u);
  EXPECT_EQ(frame->repetition_medians, (std::vector<double>{11, 20, 15}));
  EXPECT_EQ(frame->median, 15);
  EXPECT_EQ(frame->min, 10);
  EXPECT_EQ(frame->max, 21);
  const Interval expected = log_t_interval({11, 20, 15});
  EXPECT_DOUBLE_EQ(frame->interval.low, expected.low);
  EXPECT_DOUBLE_EQ(frame->interval.high, expected.high);
  EXPECT_NEAR(frame->repetition_spread, log_moments({11, 20, 15}).stddev, 1e-15);
  // One repetition: the order-statistic interval of its frames.
  const auto one = summarize_repetitions({series_of({5, 6, 7, 8, 9, 10, 11})});
  EXPECT_EQ(find_summary(one, "frame")->interval.low, 5);
  EXPECT_EQ(find_summary(one, "frame")->interval.high, 11);
  EXPECT_TRUE(std::isnan(find_summary(one, "frame")->repetition_spread));
  // A sub-pass one repetition never ran (a rebuild) counts 0 ms there: no log scale.
  TimingSeries rebuilt = series_of({10, 10, 10});
  rebuilt.add_frame({{"build", 5}, {"frame", 10}, {"rebuild", 3}});
  const auto mixed = summarize_repetitions({rebuilt, series_of({10, 10, 10, 10})});
  const TimingSummary* rebuild = find_summary(mixed, "rebuild");
  ASSERT_NE(rebuild, nullptr);
  EXPECT_EQ(rebuild->repetition_medians, (std::vector<double>{0, 0}));
  EXPECT_TRUE(std::isnan(rebuild->repetition_spread));
}

// The frames `rule` asks for, each `frame()`.
template <typename Frame>
TimingSeries frames_until_stopped(FrameStopRule& rule, Frame frame) {
  TimingSeries s;
  while (rule.want_another(s)) s.add_frame(frame());
  return s;
}

// Frame times with 100 % noise (exponential, mean 10 ms) drawn from `seed`.
auto exponential_frames(unsigned seed) {
  return [rng = std::mt19937(seed), noise = std::exponential_distribution<double>(0.1)]() mutable {
    return FrameTimes{{"frame", noise(rng)}};
  };
}

// The run-to-run spread's floor raises the target: the same 10 % noise that needs about 150
// frames for +-2 % stops far sooner at a floor of +-9 % (a noisy machine's, s 0.2), with the
// target met at the floor and missed at the requested 2 %; a target of 0 stays exact.
TEST(FrameStopRule, TheSpreadsFloorRaisesTheTargetButNeverAnExactCount) {
  RunToRunSpread spread;
  spread.spread = 0.2;
  const double floor = frame_precision_floor(&spread, 1.96);
  EXPECT_NEAR(floor, 1.96 * 0.2 / (3 * std::sqrt(2.0)), 1e-12);
  EXPECT_EQ(frame_precision_floor(nullptr, 1.96), 0.0);
  TimePrecision precision{0.02, 60.0, 400};
  precision.spread_floor = floor;
  EXPECT_EQ(precision.effective_target(), floor);
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(10, 1);
  FrameStopRule rule(5, precision);
  const TimingSeries s = frames_until_stopped(rule, [&] { return FrameTimes{{"frame", noise(rng)}, {"build", 4.0}}; });
  EXPECT_LT(s.frames(), 40u);
  EXPECT_TRUE(rule.target_met(s));
  EXPECT_GT(FrameStopRule::worst_half_width(s), 0.02);
  TimePrecision exact{0.0, 60.0, 400};
  exact.spread_floor = floor;
  EXPECT_EQ(exact.effective_target(), 0.0);
  FrameStopRule fixed(5, exact);
  EXPECT_EQ(frames_until_stopped(fixed, [] { return FrameTimes{{"frame", 10.0}}; }).frames(), 5u);
}

TEST(FrameStopRule, StopsAtTheTargetTheCapOrTheMinimum) {
  const TimePrecision precision{0.02, 60.0, 400};
  // Constant frames: the interval is a point, so the first count whose interval reaches
  // 95 % ends it (6: five frames cannot claim it).
  {
    FrameStopRule rule(5, precision);
    const TimingSeries s = frames_until_stopped(rule, [] { return FrameTimes{{"frame", 10.0}}; });
    EXPECT_EQ(s.frames(), 6u);
    EXPECT_TRUE(rule.target_met(s));
  }
  // 10 % noise: about (1.96 * 1.25 * 0.1 / 0.02)^2 = 150 frames for +-2 %, then stop met.
  {
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(10, 1);
    FrameStopRule rule(5, precision);
    const TimingSeries s = frames_until_stopped(
        rule, [&] { return FrameTimes{{"frame", noise(rng)}, {"build", 4.0}}; });
    EXPECT_GT(s.frames(), 60u);
    EXPECT_LT(s.frames(), 400u);
    EXPECT_TRUE(rule.target_met(s));
    EXPECT_LE(FrameStopRule::worst_half_width(s), 0.02);
  }
  // 100 % noise never gets there: the frame cap ends it, target missed.
  {
    FrameStopRule rule(5, {0.001, 60.0, 50});
    const TimingSeries s = frames_until_stopped(rule, exponential_frames(2));
    EXPECT_EQ(s.frames(), 50u);
    EXPECT_FALSE(rule.target_met(s));
  }
  // Target 0: exactly the minimum.
  {
    FrameStopRule rule(7, {0.0, 60.0, 400});
    const TimingSeries s = frames_until_stopped(rule, exponential_frames(4));
    EXPECT_EQ(s.frames(), 7u);
    EXPECT_TRUE(rule.target_met(s));
  }
  // The time cap: 0 s stops at the minimum even when the target is not met.
  {
    FrameStopRule rule(6, {0.001, 0.0, 400});
    const TimingSeries s = frames_until_stopped(rule, exponential_frames(6));
    EXPECT_EQ(s.frames(), 6u);
    EXPECT_FALSE(rule.target_met(s));
  }
}

TEST(TimeDigits, PrintedToWhatTheIntervalSupports) {
  EXPECT_EQ(format_supported_digits(12.34, 11.94, 12.74), "12.3");
  EXPECT_EQ(format_supported_digits(12.34, 12.33, 12.35), "12.34");
  EXPECT_EQ(format_supported_digits(123.4, 80, 170), "120");
  EXPECT_EQ(format_supported_digits(0.01234, 0.002, 0.02), "0.012");
  EXPECT_EQ(format_supported_digits(9.4, 3.3, 15.5), "9.4");  // at least 2 significant digits
  EXPECT_EQ(format_time_with_interval(12.34, 11.94, 12.74), "12.3 ±3.2%");
  EXPECT_EQ(format_time_with_interval(10, 5, 21), "10 ±110%");
  EXPECT_EQ(format_time_with_interval(12.34, 12.34, 12.34), "12.34 ±0.0%");
}

}  // namespace
}  // namespace ldm
