// `ldmbench compare`: the per-frame samples files, each verdict on synthetic records (the
// level the test works on, Holm's correction, the minimum detectable change, the
// thresholds at their boundaries), and the command's exit codes. The statistics themselves
// are checked against SciPy in tests/stats.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <nlohmann/json.hpp>

#include "harness/compare/run_comparison.h"
#include "harness/measure/frame_samples.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(Samples, ParseRepetitionsAndOlderRunsFramesAndRejectGarbage) {
  const auto reps = parse_frame_samples(
      "repetition,frame,subpass,ms\n0,0,clear,0.5\n0,0,build,1.25\n0,1,build,2\n1,0,build,3\n", "f.csv");
  ASSERT_EQ(reps.size(), 2u);
  EXPECT_EQ(*reps[0].find("build"), (std::vector<double>{1.25, 2.0}));
  EXPECT_EQ(*reps[0].find("clear"), (std::vector<double>{0.5, 0.0}));  // absent in frame 1: 0 ms
  EXPECT_EQ(*reps[1].find("build"), (std::vector<double>{3.0}));
  // A file of one repetition alone (repetition 2 of a configuration, before combining).
  EXPECT_EQ(parse_frame_samples("repetition,frame,subpass,ms\n2,0,build,4\n", "f.csv").size(), 1u);
  // Older runs: one repetition.
  const auto old = parse_frame_samples("frame,subpass,ms\n0,build,1.25\n1,build,2\n", "f.csv");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].frames(), 2u);
  EXPECT_TRUE(parse_frame_samples("repetition,frame,subpass,ms\n", "f.csv").empty());
  for (const char* bad : {"frame,ms\n", "repetition,frame,subpass,ms\n0,0,build\n",
                          "repetition,frame,subpass,ms\n0,0,build,x\n", "repetition,frame,subpass,ms\n0,0,build,nan\n",
                          "repetition,frame,subpass,ms\n0,0,build,1,2\n", "repetition,frame,subpass,ms\n0,1,build,1\n",
                          "repetition,frame,subpass,ms\n0,0,build,1\n2,0,build,1\n",
                          "repetition,frame,subpass,ms\n1,0,build,1\n0,0,build,1\n"}) {
    try {
      parse_frame_samples(bad, "cfg-frames.csv");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("cfg-frames.csv:"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(load_frame_samples("/nonexistent/x-frames.csv"), UserError);
}

// A samples file as `ldmbench run` writes it: `frame` times per repetition, in a fresh folder.
std::string frames_file(const std::vector<std::vector<double>>& repetitions) {
  static const fs::path dir = test::make_temp_dir("ldm-compare-samples");
  static int count = 0;
  const fs::path file = dir / ("c" + std::to_string(count++) + "-frames.csv");
  std::ofstream out(file);
  out.precision(17);
  out << "repetition,frame,subpass,ms\n";
  for (size_t r = 0; r < repetitions.size(); ++r)
    for (size_t i = 0; i < repetitions[r].size(); ++i) out << r << "," << i << ",frame," << repetitions[r][i] << "\n";
  return file.string();  // absolute: joined to the run folder, stays itself
}

// K repetitions of F frames: each repetition's own offset (the process's) times frame noise.
std::vector<std::vector<double>> timed(std::mt19937& rng, double median, size_t repetitions,
                                       double process_spread, size_t frames = 12, double frame_spread = 0.01) {
  std::normal_distribution<double> z(0, 1);
  std::vector<std::vector<double>> out(repetitions);
  for (auto& rep : out) {
    const double offset = median * std::exp(process_spread * z(rng));
    for (size_t f = 0; f < frames; ++f) rep.push_back(offset * std::exp(frame_spread * z(rng)));
  }
  return out;
}

json record(const std::string& id, const std::vector<std::vector<double>>& repetitions) {
  return {{"config_id", id}, {"status", "ok"}, {"device", "gpu A"}, {"timer", "gl_timestamp"},
          {"structure_params", ""}, {"frame_samples_csv", repetitions.empty() ? "" : frames_file(repetitions)},
          {"bytes_allocated", 1000}, {"bytes_used", 800},
          {"mse", 0.010}, {"mssim", 0.9}, {"ref_noise_mse", 0.001}};
}

RunRecords run_of(std::vector<json> records, const std::string& commit = "aaa", const std::string& session = "") {
  RunRecords r;
  r.path = "test";
  r.run = {{"device", "gpu A"}, {"git_commit", commit}};
  if (!session.empty()) r.run["interleaved_session"] = session;
  r.records = std::move(records);
  return r;
}

ConfigChange compare_one(const json& a, const json& b, CompareThresholds t = {}) {
  t.time_subpasses = {"frame"};
  const RunComparison c = compare_runs(run_of({a}), run_of({b}, "bbb"), t);
  EXPECT_EQ(c.matched.size(), 1u);
  return c.matched.front();
}

TEST(CompareRuns, RepetitionsDecideTimeVerdictsWithTheirMinimumDetectableChange) {
  std::mt19937 rng(1);
  // 20 % slower, 2 % between repetitions, 6 a side: found, and well above the MDE.
  auto slow = compare_one(record("c", timed(rng, 10, 6, 0.02)), record("c", timed(rng, 12, 6, 0.02)));
  ASSERT_EQ(slow.times.size(), 1u);
  EXPECT_EQ(slow.times[0].verdict, "SLOW");
  EXPECT_EQ(slow.times[0].method, "welch_log_t");
  EXPECT_EQ(slow.times[0].base_repetitions, 6u);
  EXPECT_LT(slow.times[0].minimum_detectable, 0.1);
  EXPECT_LT(slow.times[0].change_low, 0.2);
  EXPECT_GT(slow.times[0].change_high, 0.2);
  EXPECT_TRUE(slow.time_regression());
  EXPECT_EQ(compare_one(record("c", timed(rng, 10, 6, 0.02)), record("c", timed(rng, 8, 6, 0.02))).times[0].verdict,
            "FAST");
  // The frames of one repetition say nothing of the process spread: 20 % between
  // repetitions hides a 20 % change from 3 repetitions a side, whatever the frames say.
  auto hidden = compare_one(record("c", timed(rng, 10, 3, 0.2, 200)), record("c", timed(rng, 12, 3, 0.2, 200)));
  EXPECT_EQ(hidden.times[0].verdict, "SAME");
  EXPECT_GT(hidden.times[0].minimum_detectable, 0.2);
  EXPECT_NE(describe_time_change(hidden.times[0]).find("could not detect <"), std::string::npos)
      << describe_time_change(hidden.times[0]);
}

TEST(CompareRuns, ThresholdsHoldAtTheirBoundaries) {
  // Nearly noiseless repetitions: the MDE is tiny, so --min-time-change decides.
  std::mt19937 rng(2);
  const json base = record("c", timed(rng, 10, 6, 0.001, 6, 0.0001));
  const json plus6 = record("c", timed(rng, 10.6, 6, 0.001, 6, 0.0001));
  const json plus4 = record("c", timed(rng, 10.4, 6, 0.001, 6, 0.0001));
  CompareThresholds t;  // 5 %
  EXPECT_EQ(compare_one(base, plus6, t).times[0].verdict, "SLOW");
  EXPECT_EQ(compare_one(base, plus4, t).times[0].verdict, "SAME");
  EXPECT_NE(describe_time_change(compare_one(base, plus4, t).times[0]).find("below the change of interest"),
            std::string::npos);
  t.min_time_change = 0.07;  // just above the 6 % change
  EXPECT_EQ(compare_one(base, plus6, t).times[0].verdict, "SAME");
  t.min_time_change = 0.055;  // just below it
  EXPECT_EQ(compare_one(base, plus6, t).times[0].verdict, "SLOW");
  t.min_time_change = 0.10;  // twice the default
  EXPECT_EQ(compare_one(base, plus6, t).times[0].verdict, "SAME");
  // alpha at its boundary: a change that is significant at 0.05 but not at 1e-9.
  std::mt19937 rng2(3);
  const json noisy_base = record("c", timed(rng2, 10, 4, 0.03)), noisy_slow = record("c", timed(rng2, 13, 4, 0.03));
  CompareThresholds loose, strict;
  strict.alpha = 1e-9;
  const TimeChange at_loose = compare_one(noisy_base, noisy_slow, loose).times[0];
  EXPECT_EQ(at_loose.verdict, "SLOW");
  const TimeChange at_strict = compare_one(noisy_base, noisy_slow, strict).times[0];
  EXPECT_NE(at_strict.verdict, "SLOW");
  EXPECT_GT(at_strict.minimum_detectable, at_loose.minimum_detectable);  // a stricter test sees less
}

// A change the test cannot test (a repetition's median is 0 ms) is judged by the change of
// interest alone: UNSURE from --min-time-change on, SAME below it, at the boundary.
TEST(CompareRuns, AnUntestedChangeIsJudgedByTheChangeOfInterestAtItsBoundary) {
  const json base = record("c", {{0, 0, 0}, {10, 10, 10}, {10, 10, 10}});
  const json up55 = record("c", {{0, 0, 0}, {10.55, 10.55, 10.55}, {10.55, 10.55, 10.55}});
  const json up45 = record("c", {{0, 0, 0}, {10.45, 10.45, 10.45}, {10.45, 10.45, 10.45}});
  const TimeChange above = compare_one(base, up55).times[0];
  EXPECT_LT(above.p_value, 0.0);  // not tested
  EXPECT_NE(above.warning.find("not tested"), std::string::npos) << above.warning;
  EXPECT_EQ(above.verdict, "UNSURE");  // +5.5 % against the default 5 %
  EXPECT_EQ(compare_one(base, up45).times[0].verdict, "SAME");
  CompareThresholds t;
  t.min_time_change = 0.056;
  EXPECT_EQ(compare_one(base, up55, t).times[0].verdict, "SAME");
  t.min_time_change = 0.044;
  EXPECT_EQ(compare_one(base, up45, t).times[0].verdict, "UNSURE");
}

TEST(CompareRuns, OneRepetitionAssumesIndependentFramesAndTheProcessSpread) {
  std::mt19937 rng(4);
  // 200 frames with 1 % noise: the frames alone would call +15 % certain.
  const json base = record("c", timed(rng, 10, 1, 0.0, 200)), slower = record("c", timed(rng, 11.5, 1, 0.0, 200));
  const TimeChange assumed = compare_one(base, slower).times[0];  // default spread 10 %
  EXPECT_EQ(assumed.method, "assumed_spread_z");
  EXPECT_EQ(assumed.verdict, "SAME");
  EXPECT_NE(assumed.warning.find("assumes independent frames"), std::string::npos) << assumed.warning;
  EXPECT_GT(assumed.minimum_detectable, 0.15);
  CompareThresholds trusting;
  trusting.process_spread = 0.0;  // what the old frame-level test believed
  EXPECT_EQ(compare_one(base, slower, trusting).times[0].verdict, "SLOW");
  // A side with repetitions lends its measured spread when it is larger than the assumed one.
  const json spread = record("c", timed(rng, 10, 5, 0.3));
  const TimeChange lent = compare_one(base, spread, trusting).times[0];
  EXPECT_EQ(lent.method, "assumed_spread_z");
  EXPECT_GT(lent.se, 0.2);
  // One frame: nothing is detectable.
  const TimeChange single = compare_one(record("c", {{10}}), record("c", {{20}})).times[0];
  EXPECT_EQ(single.verdict, "SAME");
  EXPECT_TRUE(std::isinf(single.minimum_detectable));
}

TEST(CompareRuns, HolmCorrectsOverEveryConfigurationAndSubpass) {
  // Eight configurations, each a marginal +8 % slowdown: significant alone at 0.05, not
  // all after Holm over the eight.
  std::mt19937 rng(5);
  std::vector<json> base, next;
  for (int i = 0; i < 8; ++i) {
    base.push_back(record("c" + std::to_string(i), timed(rng, 10, 4, 0.04)));
    next.push_back(record("c" + std::to_string(i), timed(rng, 10.8, 4, 0.04)));
  }
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  t.min_time_change = 0;
  const RunComparison c = compare_runs(run_of(base), run_of(next, "bbb"), t);
  EXPECT_EQ(c.time_tests, 8u);
  size_t raw = 0, corrected = 0;
  for (const ConfigChange& change : c.matched) {
    const TimeChange& x = change.times[0];
    EXPECT_GE(x.p_adjusted, x.p_value);
    raw += x.p_value < t.alpha;
    corrected += x.p_adjusted < t.alpha;
  }
  EXPECT_LT(corrected, raw);
  EXPECT_NE(comparison_table(c).find("8 tests, Holm-corrected"), std::string::npos) << comparison_table(c);
}

TEST(CompareRuns, AnInterleavedSessionIsTestedInPairs) {
  // Load that each pair shares (repetition j of A and of B side by side) swamps a 10 %
  // change for Welch's test; the paired test removes it.
  std::mt19937 rng(6);
  std::normal_distribution<double> z(0, 1);
  std::vector<std::vector<double>> a, b;
  for (int j = 0; j < 6; ++j) {
    const double load = 10 * std::exp(0.3 * z(rng));
    a.push_back({load * std::exp(0.005 * z(rng))});
    b.push_back({1.1 * load * std::exp(0.005 * z(rng))});
  }
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  const RunComparison unpaired = compare_runs(run_of({record("c", a)}), run_of({record("c", b)}, "bbb"), t);
  EXPECT_EQ(unpaired.matched[0].times[0].method, "welch_log_t");
  EXPECT_NE(unpaired.matched[0].times[0].verdict, "SLOW");
  const RunComparison paired =
      compare_runs(run_of({record("c", a)}, "aaa", "s1"), run_of({record("c", b)}, "bbb", "s1"), t);
  EXPECT_TRUE(paired.paired);
  EXPECT_EQ(paired.matched[0].times[0].method, "paired_log_t");
  EXPECT_EQ(paired.matched[0].times[0].verdict, "SLOW");
  // Two different sessions are not paired.
  EXPECT_FALSE(compare_runs(run_of({record("c", a)}, "aaa", "s1"), run_of({record("c", b)}, "bbb", "s2"), t).paired);
}

TEST(CompareRuns, RefusesTimeAcrossDevicesAndTimers) {
  std::mt19937 rng(7);
  const json base = record("c", timed(rng, 10, 3, 0.01));
  json other_device = record("c", timed(rng, 20, 3, 0.01));
  other_device["device"] = "gpu B";
  auto c = compare_one(base, other_device);
  EXPECT_TRUE(c.times.empty());
  EXPECT_NE(c.time_note.find("devices differ"), std::string::npos);
  EXPECT_EQ(c.memory_verdict, "SAME");  // the rest is still compared
  json other_timer = record("c", timed(rng, 20, 3, 0.01));
  other_timer["timer"] = "fenced_wall_clock";
  c = compare_one(base, other_timer);
  EXPECT_TRUE(c.times.empty());
  EXPECT_NE(c.time_note.find("timers differ"), std::string::npos);
}

// Two drivers (or two GPU models) measure differently without either regressing: the
// comparison says so, keeps its verdicts, and counts no regression (issue 31).
TEST(CompareRuns, ACrossDriverComparisonSaysSoAndCountsNoRegression) {
  std::mt19937 rng(11);
  json base = record("c", timed(rng, 10, 3, 0.01));
  base["gl_driver"] = "llvmpipe";
  base["device"] = "llvmpipe (LLVM 15.0.6, 256 bits)";
  json zink = record("c", timed(rng, 20, 3, 0.01));
  zink["gl_driver"] = "zink";
  zink["device"] = "zink (llvmpipe (LLVM 15.0.6, 256 bits))";
  zink["bytes_used"] = 900;  // MORE
  zink["mse"] = 0.02;        // WORSE
  zink["status"] = "lossy";  // worse
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  const RunComparison c = compare_runs(run_of({base}), run_of({zink}, "bbb"), t);
  ASSERT_EQ(c.matched.size(), 1u);
  const ConfigChange& m = c.matched.front();
  EXPECT_EQ(m.cross, "cross-driver");
  EXPECT_EQ(m.base_driver, "llvmpipe");
  EXPECT_EQ(m.new_driver, "zink");
  EXPECT_TRUE(m.times.empty());
  EXPECT_EQ(m.time_note, "drivers differ (llvmpipe vs zink)");
  EXPECT_EQ(m.memory_verdict, "MORE");  // what differs is still shown
  EXPECT_EQ(m.accuracy_verdict, "WORSE");
  EXPECT_TRUE(m.status_worse);
  for (const std::string& kind : regression_kinds()) EXPECT_EQ(count_regressions(c, kind), 0u) << kind;
  const std::string table = comparison_table(c);
  EXPECT_NE(table.find("baseline on llvmpipe, candidate on zink: a cross-driver comparison"), std::string::npos) << table;
  EXPECT_NE(table.find("differences are not regressions"), std::string::npos) << table;
  EXPECT_NE(table.find("[cross-driver: llvmpipe -> zink]"), std::string::npos) << table;
  EXPECT_NE(table.find("regressions: time 0 memory 0 accuracy 0 status 0"), std::string::npos) << table;
  EXPECT_EQ(comparison_json(c, t)["configurations"][0]["cross"], "cross-driver");

  // The same records on one driver are regressions.
  json same = zink;
  same["gl_driver"] = "llvmpipe";
  same["device"] = base["device"];
  const RunComparison r = compare_runs(run_of({base}), run_of({same}, "bbb"), t);
  EXPECT_EQ(r.matched.front().cross, "");
  EXPECT_EQ(count_regressions(r, "memory"), 1u);
  EXPECT_EQ(count_regressions(r, "accuracy"), 1u);
  EXPECT_EQ(count_regressions(r, "status"), 1u);
}

// Records from before gl_driver: the driver is derived from device, gl_vendor, gl_version,
// so an old llvmpipe baseline still matches a new llvmpipe run, and not a zink one.
TEST(CompareRuns, OldRecordsWithoutTheDriverColumnsAreMatchedByTheirGlStrings) {
  json old = record("c", {});
  old["device"] = "llvmpipe (LLVM 15.0.6, 256 bits)";
  old["gl_vendor"] = "Mesa/X.org";
  old["gl_version"] = "4.5 (Core Profile) Mesa 22.3.6";
  EXPECT_EQ(record_driver(old), "llvmpipe");
  json now = old;
  now["gl_driver"] = "llvmpipe";
  now["device_id"] = "software:llvmpipe (LLVM 15.0.6, 256 bits)";
  now["bytes_used"] = 900;
  EXPECT_EQ(compare_one(old, now).cross, "");
  EXPECT_TRUE(compare_one(old, now).memory_regression());
  json zink = now;
  zink["gl_driver"] = "zink";
  zink["device"] = "zink (llvmpipe (LLVM 15.0.6, 256 bits))";
  EXPECT_EQ(compare_one(old, zink).cross, "cross-driver");
  EXPECT_FALSE(compare_one(old, zink).memory_regression());
}

// One driver, two GPU models: cross-device; two GPUs of one model: compared, with a warning.
TEST(CompareRuns, AnotherDeviceModelIsCrossDeviceAnotherGpuOfTheModelIsCompared) {
  std::mt19937 rng(5);
  json a = record("c", timed(rng, 10, 3, 0.01));
  a["gl_driver"] = "nvidia";
  a["device"] = "NVIDIA A100";
  a["device_id"] = "00000000-0000-0000-0000-000000000001";
  json other_model = record("c", timed(rng, 10, 3, 0.01));
  other_model["gl_driver"] = "nvidia";
  other_model["device"] = "NVIDIA H100";
  other_model["bytes_used"] = 900;
  auto c = compare_one(a, other_model);
  EXPECT_EQ(c.cross, "cross-device");
  EXPECT_FALSE(c.memory_regression());
  EXPECT_TRUE(c.times.empty());
  json other_gpu = record("c", timed(rng, 10, 3, 0.01));
  other_gpu["gl_driver"] = "nvidia";
  other_gpu["device"] = "NVIDIA A100";
  other_gpu["device_id"] = "00000000-0000-0000-0000-000000000002";
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  const RunComparison r = compare_runs(run_of({a}), run_of({other_gpu}, "bbb"), t);
  EXPECT_EQ(r.matched.front().cross, "");
  EXPECT_EQ(r.matched.front().times.size(), 1u);
  const std::string table = comparison_table(r);
  EXPECT_NE(table.find("1 configuration(s) ran on another GPU of the same model"), std::string::npos) << table;
}

// Two runs at different loads of their machine: compared, with a warning (the intervals are
// calibrated at one load); at loads within the calibration's tolerance, none.
TEST(CompareRuns, RunsAtDifferentLoadsAreComparedWithAWarning) {
  std::mt19937 rng(6);
  const auto at_load = [&](double load) {
    json r = record("c", timed(rng, 10, 3, 0.01));
    r["load_average_start"] = load;
    return r;
  };
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  const auto warned = [](const RunComparison& c) {
    return std::any_of(c.warnings.begin(), c.warnings.end(),
                       [](const std::string& w) { return w.find("different loads") != std::string::npos; });
  };
  const RunComparison quiet_against_loaded = compare_runs(run_of({at_load(0.4)}), run_of({at_load(2.1)}, "bbb"), t);
  EXPECT_TRUE(warned(quiet_against_loaded));
  EXPECT_NE(comparison_table(quiet_against_loaded).find("median load average 0.40 and 2.10"), std::string::npos)
      << comparison_table(quiet_against_loaded);
  EXPECT_EQ(quiet_against_loaded.matched.front().times.size(), 1u);  // still compared
  EXPECT_FALSE(warned(compare_runs(run_of({at_load(0.4)}), run_of({at_load(0.8)}, "bbb"), t)));
  EXPECT_FALSE(warned(compare_runs(run_of({record("c", timed(rng, 10, 3, 0.01))}), run_of({at_load(3.0)}, "bbb"), t)));
  t.compare_time = false;  // the CI guard: no time is compared, so the load does not matter
  EXPECT_FALSE(warned(compare_runs(run_of({at_load(0.4)}), run_of({at_load(2.1)}, "bbb"), t)));
}

TEST(CompareRuns, MemoryIsExactUnlessToleranceAllows) {
  const json base = record("c", {});
  json more = base;
  more["bytes_used"] = 801;
  EXPECT_EQ(compare_one(base, more).memory_verdict, "MORE");
  CompareThresholds tolerant;
  tolerant.memory_tolerance = 0.01;
  EXPECT_EQ(compare_one(base, more, tolerant).memory_verdict, "SAME");
  json less = base;
  less["bytes_allocated"] = 999;
  EXPECT_EQ(compare_one(base, less).memory_verdict, "LESS");
  EXPECT_EQ(compare_one(base, base).memory_verdict, "SAME");
}

TEST(CompareRuns, AccuracyIsJudgedAgainstTheReferenceNoise) {
  const json base = record("c", {});
  json within = base, worse = base, better = base, no_reference = base;
  within["mse"] = 0.0109;  // +0.9 x ref_noise_mse
  worse["mse"] = 0.0111;   // +1.1 x
  better["mse"] = 0.0085;
  no_reference.erase("mse");
  EXPECT_EQ(compare_one(base, within).accuracy_verdict, "SAME");
  EXPECT_EQ(compare_one(base, worse).accuracy_verdict, "WORSE");
  EXPECT_TRUE(compare_one(base, worse).accuracy_regression());
  EXPECT_EQ(compare_one(base, better).accuracy_verdict, "BETTER");
  EXPECT_EQ(compare_one(base, no_reference).accuracy_verdict, "");
  CompareThresholds strict;
  strict.noise_factor = 0.5;
  EXPECT_EQ(compare_one(base, within, strict).accuracy_verdict, "WORSE");
}

TEST(CompareRuns, StatusWorseningsAndMissingConfigurations) {
  json ok = record("c", {}), lossy = ok, invalid = ok;
  lossy["status"] = "lossy";
  invalid["status"] = "invalid";
  EXPECT_TRUE(compare_one(ok, lossy).status_worse);
  EXPECT_TRUE(compare_one(lossy, invalid).status_worse);
  EXPECT_FALSE(compare_one(lossy, ok).status_worse);
  EXPECT_FALSE(compare_one(ok, ok).status_worse);

  const RunComparison c = compare_runs(run_of({record("a", {}), record("b", {})}),
                                       run_of({record("b", {}), record("new", {})}), {});
  ASSERT_EQ(c.matched.size(), 2u);
  EXPECT_EQ(c.matched[0].new_status, "missing");
  EXPECT_EQ(count_regressions(c, "status"), 1u);
  EXPECT_EQ(c.added, std::vector<std::string>{"new"});
}

TEST(CompareRuns, IgnoredParameterLeavesTheIdentity) {
  json a = record("cornell-ppfla-ao-n4-r32-plane-k=8", {}), b = a;
  a["structure_params"] = "k=8";
  b["config_id"] = "cornell-ppfla-ao-n4-r32-plane-k=1";
  b["structure_params"] = "k=1";
  b["status"] = "lossy";
  EXPECT_EQ(compare_runs(run_of({a}), run_of({b}), {}).matched[0].new_status, "missing");
  CompareThresholds t;
  t.ignored_params = {"k"};
  const RunComparison c = compare_runs(run_of({a}), run_of({b}), t);
  EXPECT_EQ(c.matched[0].identity, "cornell-ppfla-ao-n4-r32-plane");
  EXPECT_EQ(c.matched[0].new_status, "lossy");
  EXPECT_TRUE(c.added.empty());
}

TEST(CompareRuns, IgnoredViewCountPairsTwoValuesOfN) {
  json a = record("cornell-psppsll-ao-n16-r64-plane-prevframe", {}), b = a, c = a;
  a["n_views"] = 16;
  b["config_id"] = "cornell-psppsll-ao-n20-r64-plane-prevframe";
  b["n_views"] = 20;
  CompareThresholds t;
  t.ignored_params = {"n_views"};
  const RunComparison pairs = compare_runs(run_of({a}), run_of({b}), t);
  EXPECT_EQ(pairs.matched[0].identity, "cornell-psppsll-ao-r64-plane-prevframe");
  EXPECT_EQ(pairs.matched[0].new_status, "ok");
  // Only the whole fragment: -n16 is not cut out of -n160.
  c["config_id"] = "cornell-psppsll-ao-n160-r64-plane-prevframe";
  c["n_views"] = 16;  // a record whose id says otherwise keeps its id
  EXPECT_EQ(compare_runs(run_of({c}), run_of({c}), t).matched[0].identity,
            "cornell-psppsll-ao-n160-r64-plane-prevframe");
}

// Two runs of one sweep at two values of a parameter share no configuration: the comparison
// names the --ignore-param that pairs them, and that option does pair them.
json ppfla_at(int k, const std::string& scene) {
  json r = record(scene + "-ppfla-ao-n4-r32-plane-k=" + std::to_string(k), {});
  r["structure_params"] = "k=" + std::to_string(k);
  r["n_views"] = 4;
  r["r_ldm"] = 32;
  return r;
}

TEST(CompareRuns, SuggestsTheIgnoredParameterThatPairsMissingConfigurations) {
  const RunRecords base = run_of({ppfla_at(8, "cornell"), ppfla_at(8, "atrium")});
  const RunRecords next = run_of({ppfla_at(2, "cornell"), ppfla_at(2, "atrium")});
  const RunComparison c = compare_runs(base, next, {});
  EXPECT_EQ(count_regressions(c, "status"), 2u);
  ASSERT_EQ(c.pairing_hints.size(), 1u);  // n_views and r_ldm pair nothing
  EXPECT_EQ(c.pairing_hints[0].param, "k");
  EXPECT_EQ(c.pairing_hints[0].paired, 2u);
  EXPECT_EQ(c.pairing_hints[0].missing, 2u);
  EXPECT_NE(comparison_table(c).find("hint: --ignore-param k pairs 2 of the 2 configurations missing from NEW"),
            std::string::npos)
      << comparison_table(c);
  EXPECT_EQ(comparison_json(c, {})["pairing_hints"][0]["ignore_param"], "k");
  // The suggestion works: nothing missing, nothing suggested.
  CompareThresholds t;
  t.ignored_params = {"k"};
  const RunComparison paired = compare_runs(base, next, t);
  EXPECT_EQ(count_regressions(paired, "status"), 0u);
  EXPECT_TRUE(paired.added.empty());
  EXPECT_TRUE(paired.pairing_hints.empty());
  // A genuinely different configuration is not paired by any parameter.
  const RunComparison unrelated = compare_runs(run_of({record("a", {})}), run_of({record("b", {})}), {});
  EXPECT_TRUE(unrelated.pairing_hints.empty());
}

TEST(CompareRuns, NoSuggestionThatWouldMergeTwoRecords) {
  // NEW has k=2 and k=4 of one configuration: leaving k out would make them one identity.
  const RunComparison c = compare_runs(run_of({ppfla_at(8, "cornell")}),
                                       run_of({ppfla_at(2, "cornell"), ppfla_at(4, "cornell")}), {});
  EXPECT_TRUE(c.pairing_hints.empty());
}

// The command: exit 0 without selected regressions, 1 with, 2 for bad input.
using test::Outcome;
using test::ldmbench;

fs::path write_run(const fs::path& dir, const std::vector<json>& records) {
  fs::create_directories(dir);
  std::ofstream(dir / "records.json") << json{{"run", {{"device", "gpu A"}}}, {"records", records}}.dump();
  return dir;
}

TEST(CompareCommand, SuggestsIgnoreParamAndItPairs) {
  const fs::path tmp = test::make_temp_dir("ldm-compare");
  const fs::path a = write_run(tmp / "a", {ppfla_at(8, "cornell"), ppfla_at(8, "atrium")});
  const fs::path b = write_run(tmp / "b", {ppfla_at(2, "cornell"), ppfla_at(2, "atrium")});
  Outcome o = ldmbench("compare " + a.string() + " " + b.string());
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("hint: --ignore-param k pairs 2 of the 2 configurations missing from NEW"),
            std::string::npos)
      << o.output;
  o = ldmbench("compare --ignore-param k " + a.string() + " " + b.string());
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(o.output.find("missing"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("hint:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("regressions: time 0 memory 0 accuracy 0 status 0"), std::string::npos) << o.output;
}

TEST(CompareCommand, ExitCodeFollowsFailOn) {
  const fs::path tmp = test::make_temp_dir("ldm-compare");
  std::mt19937 rng(8);
  json worse = record("c", timed(rng, 10, 3, 0.01));
  worse["bytes_used"] = 900;
  const fs::path a = write_run(tmp / "a", {record("c", timed(rng, 10, 3, 0.01))});
  const fs::path b = write_run(tmp / "b", {worse});
  const std::string ab = a.string() + " " + b.string();
  Outcome o = ldmbench("compare " + ab);
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("regressions: time 0 memory 1 accuracy 0 status 0"), std::string::npos) << o.output;
  EXPECT_EQ(ldmbench("compare " + ab + " --fail-on time,status").status, 0);
  EXPECT_EQ(ldmbench("compare " + ab + " --fail-on memory").status, 1);
  EXPECT_EQ(ldmbench("compare " + ab + " --fail-on memory --memory-tolerance 0.2").status, 0);
  o = ldmbench("compare " + ab + " --json");
  ASSERT_EQ(o.status, 0);
  const json j = json::parse(o.output);
  EXPECT_EQ(j["regressions"]["memory"], 1);
  EXPECT_EQ(j["configurations"][0]["memory"]["verdict"], "MORE");

  o = ldmbench("compare " + ab + " --fail-on speed");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("speed"), std::string::npos);
  o = ldmbench("compare " + a.string() + " " + (tmp / "nowhere").string());
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("nowhere"), std::string::npos);
  std::ofstream(tmp / "bad.json") << "{\"records\": [{\"status\": \"ok\"}]}";
  o = ldmbench("compare " + a.string() + " " + (tmp / "bad.json").string());
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("config_id"), std::string::npos);
}

// Two real runs of one configuration, the second under zink (Mesa's second driver): the
// records name their driver and device, and compare calls it a cross-driver comparison with
// no regression, whatever --fail-on asks (issue 31).
TEST(CompareCommand, ARunUnderZinkAgainstLlvmpipeIsACrossDriverComparison) {
  const fs::path tmp = test::make_temp_dir("ldm-compare-drivers");
  const std::string args = "run --scene cornell --structure ppfla -N 4 -R 32 --image-size 32x32 --frames 2 --time-target 0 "
                           "--warmup 1 --no-reference --no-images --out ";
  Outcome o = ldmbench(args + (tmp / "llvmpipe").string(), "env -u MESA_LOADER_DRIVER_OVERRIDE");
  ASSERT_EQ(o.status, 0) << o.output;
  const fs::path runtime = tmp / "xdg";
  fs::create_directories(runtime);
  fs::permissions(runtime, fs::perms::owner_all, fs::perm_options::replace);
  o = ldmbench(args + (tmp / "zink").string(), "XDG_RUNTIME_DIR=" + runtime.string() +
                                                   " MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1 ");
  if (o.status != 0 && o.output.find("zink") == std::string::npos)
    GTEST_SKIP() << "no zink here: " << o.output;
  ASSERT_EQ(o.status, 0) << o.output;
  const RunRecords a = load_run_records((tmp / "llvmpipe").string()), z = load_run_records((tmp / "zink").string());
  ASSERT_EQ(a.records.size(), 1u);
  ASSERT_EQ(z.records.size(), 1u);
  const std::string driver_a = a.records[0].value("gl_driver", ""), driver_z = z.records[0].value("gl_driver", "");
  if (driver_z != "zink") GTEST_SKIP() << "the zink override gave " << driver_z;
  EXPECT_EQ(a.records[0].value("device_id", ""), "software:" + a.records[0].value("device", ""));
  EXPECT_EQ(a.run.value("gl_driver", ""), driver_a);
  o = ldmbench("compare " + (tmp / "llvmpipe").string() + " " + (tmp / "zink").string() +
               " --fail-on time,memory,accuracy,status");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("baseline on " + driver_a + ", candidate on zink: a cross-driver comparison"),
            std::string::npos) << o.output;
  EXPECT_NE(o.output.find("drivers differ (" + driver_a + " vs zink)"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("regressions: time 0 memory 0 accuracy 0 status 0"), std::string::npos) << o.output;
}

// --min-time-change through the command, at its boundary: the default is 5 % (a 5.5 %
// slowdown is SLOW, 4.5 % SAME), and the value given is the one judged by (0.06 turns the
// 5.5 % SAME, 0.04 the 4.5 % SLOW), in the verdicts, the JSON thresholds and the exit code of
// --fail-on time. Nearly noiseless repetitions, so that the MDE (~0.1 %) never decides.
TEST(CompareCommand, MinTimeChangeHoldsAtItsBoundary) {
  const fs::path tmp = test::make_temp_dir("ldm-compare");
  std::mt19937 rng(9);
  const fs::path a = write_run(tmp / "a", {record("c", timed(rng, 10, 6, 0.0005, 6, 0.0001))});
  const fs::path up55 = write_run(tmp / "up55", {record("c", timed(rng, 10.55, 6, 0.0005, 6, 0.0001))});
  const fs::path up45 = write_run(tmp / "up45", {record("c", timed(rng, 10.45, 6, 0.0005, 6, 0.0001))});
  const fs::path down55 = write_run(tmp / "down55", {record("c", timed(rng, 10.0 / 1.055, 6, 0.0005, 6, 0.0001))});
  auto judged = [&](const fs::path& next, const std::string& extra) {
    const Outcome o = ldmbench("compare " + a.string() + " " + next.string() + " --time-subpasses frame --json " + extra);
    EXPECT_EQ(o.status, 0) << o.output;
    const json j = json::parse(o.output);
    const json& time = j["configurations"][0]["time"][0];
    EXPECT_LT(time["minimum_detectable_change"].get<double>(), 0.005) << time;
    return std::make_pair(time["verdict"].get<std::string>(), j["thresholds"]["min_time_change"].get<double>());
  };
  EXPECT_EQ(judged(up55, ""), std::make_pair(std::string("SLOW"), 0.05));
  EXPECT_EQ(judged(up45, "").first, "SAME");
  EXPECT_EQ(judged(down55, "").first, "FAST");
  EXPECT_EQ(judged(up55, "--min-time-change 0.06"), std::make_pair(std::string("SAME"), 0.06));
  EXPECT_EQ(judged(up45, "--min-time-change 0.04"), std::make_pair(std::string("SLOW"), 0.04));
  EXPECT_EQ(judged(down55, "--min-time-change 0.06").first, "SAME");
  const std::string up = "compare " + a.string() + " " + up55.string() + " --time-subpasses frame --fail-on time";
  EXPECT_EQ(ldmbench(up).status, 1);
  EXPECT_EQ(ldmbench(up + " --min-time-change 0.06").status, 0);
  // The help states the default it applies.
  EXPECT_NE(ldmbench("compare --help").output.find("--min-time-change"), std::string::npos);
}

}  // namespace
}  // namespace ldm

namespace ldm {
namespace {

TEST(CompareRuns, SingleRunsAssumeTheRecordsCalibratedSpreadAndSayHowManyRepetitionsReach10Percent) {
  std::mt19937 rng(7);
  json a = record("c", timed(rng, 10, 1, 0.0, 30)), b = record("c", timed(rng, 10.5, 1, 0.0, 30));
  // Without a calibration: the assumed default, and the warning says so.
  const ConfigChange assumed = compare_one(a, b);
  ASSERT_EQ(assumed.times.size(), 1u);
  EXPECT_EQ(assumed.times[0].spread_source, "default");
  EXPECT_NEAR(assumed.times[0].process_spread, CompareThresholds::kDefaultProcessSpread, 1e-12);
  EXPECT_NE(assumed.times[0].warning.find("`ldmbench calibrate` measures it"), std::string::npos)
      << assumed.times[0].warning;
  // With one (the spread of a difference of two runs): one run's share, sqrt 2 smaller.
  a["time_run_to_run_spread"] = 0.3;
  b["time_run_to_run_spread"] = 0.2;
  const ConfigChange calibrated = compare_one(a, b);
  EXPECT_EQ(calibrated.times[0].spread_source, "calibration");
  EXPECT_NEAR(calibrated.times[0].process_spread, 0.3 / std::sqrt(2.0), 1e-12);
  EXPECT_GT(calibrated.times[0].minimum_detectable, assumed.times[0].minimum_detectable);
  // --process-spread wins over the records.
  CompareThresholds given;
  given.process_spread = 0.05;
  given.process_spread_given = true;
  EXPECT_EQ(compare_one(a, b, given).times[0].spread_source, "--process-spread");
  // The table names the repetitions that reach 10 % at that spread.
  CompareThresholds t;
  t.time_subpasses = {"frame"};
  const std::string table = comparison_table(compare_runs(run_of({a}), run_of({b}, "bbb"), t));
  const size_t needed = repetitions_for_detectable_change(0.3 / std::sqrt(2.0), 0.10, 0.05, 0.8);
  EXPECT_NE(table.find("a 10% change needs about " + std::to_string(needed) + " repetitions per side"),
            std::string::npos)
      << table;
}

TEST(CompareRuns, RepetitionsForADetectableChangeFollowTheNormalApproximation) {
  // 2 ((1.96 + 0.8416) 0.2 / log 1.1)^2 = 69.1 -> 70.
  EXPECT_EQ(repetitions_for_detectable_change(0.2, 0.10, 0.05, 0.8), 70u);
  EXPECT_EQ(repetitions_for_detectable_change(0.01, 0.10, 0.05, 0.8), 2u);  // never fewer than 2
  EXPECT_LT(repetitions_for_detectable_change(0.2, 0.20, 0.05, 0.8), 70u);
  EXPECT_GT(repetitions_for_detectable_change(0.2, 0.10, 0.05, 0.9), 70u);
}

}  // namespace
}  // namespace ldm
