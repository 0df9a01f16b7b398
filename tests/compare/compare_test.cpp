// `ldmbench compare`: the U test against SciPy, the per-frame samples files, each verdict
// on synthetic records, and the command's exit codes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/compare/mann_whitney.h"
#include "harness/compare/run_comparison.h"
#include "harness/compare/samples.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Oracle: scipy.stats.mannwhitneyu(a, b, alternative="two-sided", method="asymptotic")
// (SciPy 1.10.1), printed once and copied here.
TEST(MannWhitney, MatchesScipyAsymptotic) {
  const auto separated = mann_whitney_u({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  EXPECT_DOUBLE_EQ(separated.u, 0);
  EXPECT_NEAR(separated.p_value, 0.012185780355344813, 1e-12);
  const auto tied = mann_whitney_u({1.0, 2, 2, 3, 5, 7, 7, 8, 9, 9.5}, {2, 4, 4, 6, 8, 10, 11, 12, 12, 13, 14});
  EXPECT_DOUBLE_EQ(tied.u, 27.5);
  EXPECT_NEAR(tied.p_value, 0.05661901581720463, 1e-12);
  EXPECT_DOUBLE_EQ(mann_whitney_u({3, 3, 3}, {3, 3, 3}).p_value, 1.0);
  EXPECT_THROW(mann_whitney_u({}, {1}), std::invalid_argument);
}

TEST(Samples, ParseTheRunsFramesCsvAndRejectGarbage) {
  const FrameSamples s = parse_frame_samples("frame,subpass,ms\n0,clear,0.5\n0,build,1.25\n1,build,2\n", "f.csv");
  EXPECT_EQ(s.at("build"), (std::vector<double>{1.25, 2.0}));
  EXPECT_EQ(s.at("clear"), (std::vector<double>{0.5}));
  EXPECT_TRUE(parse_frame_samples("frame,subpass,ms\n", "f.csv").empty());
  for (const char* bad : {"frame,ms\n", "frame,subpass,ms\n0,build\n", "frame,subpass,ms\n0,build,x\n",
                          "frame,subpass,ms\n0,build,nan\n", "frame,subpass,ms\n0,build,1,2\n"}) {
    try {
      parse_frame_samples(bad, "cfg-frames.csv");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("cfg-frames.csv:"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(load_frame_samples("/nonexistent/x-frames.csv"), UserError);
}

// A samples file as `ldmbench run` writes it, holding `frame` times, in a fresh folder.
std::string frames_file(const std::vector<double>& times) {
  static const fs::path dir = test::make_temp_dir("ldm-compare-samples");
  static int count = 0;
  const fs::path file = dir / ("c" + std::to_string(count++) + "-frames.csv");
  std::ofstream out(file);
  out << "frame,subpass,ms\n";
  for (size_t i = 0; i < times.size(); ++i) out << i << ",frame," << times[i] << "\n";
  return file.string();  // absolute: joined to the run folder, stays itself
}

std::vector<double> samples(double base, double step, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(base + step * ((i * 7) % n));  // spread, unsorted
  return v;
}

json record(const std::string& id, const std::vector<double>& frame_times) {
  return {{"config_id", id}, {"status", "ok"}, {"device", "gpu A"}, {"timer", "gl_timestamp"},
          {"structure_params", ""}, {"frame_samples_csv", frame_times.empty() ? "" : frames_file(frame_times)},
          {"bytes_allocated", 1000}, {"bytes_used", 800},
          {"mse", 0.010}, {"mssim", 0.9}, {"ref_noise_mse", 0.001}};
}

RunRecords run_of(std::vector<json> records, const std::string& commit = "aaa") {
  RunRecords r;
  r.path = "test";
  r.run = {{"device", "gpu A"}, {"git_commit", commit}};
  r.records = std::move(records);
  return r;
}

ConfigChange compare_one(const json& a, const json& b, CompareThresholds t = {}) {
  t.time_subpasses = {"frame"};
  const RunComparison c = compare_runs(run_of({a}), run_of({b}, "bbb"), t);
  EXPECT_EQ(c.matched.size(), 1u);
  return c.matched.front();
}

TEST(CompareRuns, TimeVerdictsNeedSignificanceAndSize) {
  const json base = record("c", samples(10, 0.1, 12));
  // 20% slower, well separated: significant and large.
  auto slow = compare_one(base, record("c", samples(12, 0.1, 12)));
  ASSERT_EQ(slow.times.size(), 1u);
  EXPECT_EQ(slow.times[0].verdict, "SLOW");
  EXPECT_LT(slow.times[0].p_value, 0.05);
  EXPECT_TRUE(slow.time_regression());
  EXPECT_TRUE(slow.times[0].warning.empty());
  EXPECT_EQ(compare_one(base, record("c", samples(8, 0.1, 12))).times[0].verdict, "FAST");
  // 2% slower and well separated: significant but below --min-time-change (5%).
  auto small = compare_one(record("c", samples(10, 0.001, 12)), record("c", samples(10.2, 0.001, 12)));
  EXPECT_LT(small.times[0].p_value, 0.05);
  EXPECT_EQ(small.times[0].verdict, "SAME");
  EXPECT_FALSE(small.time_regression());
  CompareThresholds sensitive;
  sensitive.min_time_change = 0.01;
  EXPECT_EQ(compare_one(record("c", samples(10, 0.001, 12)), record("c", samples(10.2, 0.001, 12)),
                        sensitive).times[0].verdict, "SLOW");
  // A large median change the samples cannot confirm: three frames with a wide spread.
  auto unsure = compare_one(record("c", {10, 20, 30}), record("c", {15, 25, 12}));
  EXPECT_EQ(unsure.times[0].verdict, "UNSURE");
  EXPECT_NE(unsure.times[0].warning.find("fewer than 9"), std::string::npos);
  // One frame each: not tested.
  auto one = compare_one(record("c", {10}), record("c", {20}));
  EXPECT_EQ(one.times[0].verdict, "UNSURE");
  EXPECT_LT(one.times[0].p_value, 0);
}

TEST(CompareRuns, RefusesTimeAcrossDevicesAndTimers) {
  const json base = record("c", samples(10, 0.1, 12));
  json other_device = record("c", samples(20, 0.1, 12));
  other_device["device"] = "gpu B";
  auto c = compare_one(base, other_device);
  EXPECT_TRUE(c.times.empty());
  EXPECT_NE(c.time_note.find("devices differ"), std::string::npos);
  EXPECT_EQ(c.memory_verdict, "SAME");  // the rest is still compared
  json other_timer = record("c", samples(20, 0.1, 12));
  other_timer["timer"] = "fenced_wall_clock";
  c = compare_one(base, other_timer);
  EXPECT_TRUE(c.times.empty());
  EXPECT_NE(c.time_note.find("timers differ"), std::string::npos);
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

// The command: exit 0 without selected regressions, 1 with, 2 for bad input.
using test::Outcome;
using test::ldmbench;

fs::path write_run(const fs::path& dir, const std::vector<json>& records) {
  fs::create_directories(dir);
  std::ofstream(dir / "records.json") << json{{"run", {{"device", "gpu A"}}}, {"records", records}}.dump();
  return dir;
}

TEST(CompareCommand, ExitCodeFollowsFailOn) {
  const fs::path tmp = test::make_temp_dir("ldm-compare");
  json worse = record("c", samples(10, 0.1, 12));
  worse["bytes_used"] = 900;
  const fs::path a = write_run(tmp / "a", {record("c", samples(10, 0.1, 12))});
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

}  // namespace
}  // namespace ldm
