// ldmbench calibrate and --calibration / LDM_CALIBRATION end to end: the probe writes a
// spread, a run widens its records by it and says so, skip says so too, bad values are
// refused naming where they came from, and --isolation process hands the parent's spread to
// every child.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "harness/measuring/calibration.h"
#include "harness/measure/run_to_run_spread.h"
#include "support/probe_spread.h"
#include "support/test_support.h"

namespace ldm {
namespace {

using test::ldmbench;
using test::make_temp_dir;
using test::read_text;

const char* kTinyRun = "run --scene cornell --structure ppsll -N 4 -R 32 --image-size 32x32 --no-reference --no-images";

// This device's calibration cache entry in a cache of its own, `cache` (XDG_CACHE_HOME, for
// this process and the ldmbench it starts with the same variable).
std::string own_cache_entry(const std::string& cache) {
  setenv("XDG_CACHE_HOME", cache.c_str(), 1);
  return calibration_cache_file(test::gl_context().device()).string();
}

nlohmann::json only_record(const std::string& out) {
  const auto records = nlohmann::json::parse(read_text(out + "/records.json")).at("records");
  EXPECT_EQ(records.size(), 1u);
  return records.at(0);
}

TEST(Calibration, ProbeWritesASpreadThatARunWidensItsIntervalsBy) {
  const std::string dir = make_temp_dir("calibrate");
  // A cache of its own: an earlier probe of the day there would be pooled with this one.
  const auto probe = ldmbench("calibrate --processes 2 --out " + dir + "/spread.json",
                              "XDG_CACHE_HOME=" + make_temp_dir("calibrate-empty-cache"));
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_NE(probe.output.find("run-to-run spread:"), std::string::npos) << probe.output;
  const RunToRunSpread spread = read_calibration_file(dir + "/spread.json");
  EXPECT_GT(spread.pairs, 0u);
  EXPECT_EQ(spread.processes, 2u);
  EXPECT_GE(spread.spread, 0.0);
  EXPECT_EQ(spread.pooled_probes, 1u);
  ASSERT_EQ(spread.probes.size(), 1u);
  EXPECT_EQ(spread.probes[0].spread, spread.spread);

  const auto run = ldmbench(std::string(kTinyRun) + " --calibration " + dir + "/spread.json --out " + dir + "/run");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto r = only_record(dir + "/run");
  EXPECT_EQ(r.at("time_interval"), "order_statistics_of_frames+run_to_run_spread");
  EXPECT_EQ(r.at("time_run_to_run_spread").get<double>(), spread.spread);
  EXPECT_NE(r.at("time_calibration").get<std::string>().find("file " + dir + "/spread.json"), std::string::npos);
  EXPECT_GE(r.at("time_half_width").get<double>(), r.at("time_half_width_within_run").get<double>());
  EXPECT_TRUE(r.contains("load_average_start"));
}

TEST(Calibration, SkipLeavesIntervalsWithinRunAndEveryRecordSaysSo) {
  const std::string dir = make_temp_dir("calibrate-skip");
  const auto run = ldmbench(std::string(kTinyRun) + " --out " + dir, "LDM_CALIBRATION=skip");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto r = only_record(dir);
  EXPECT_EQ(r.at("time_interval"), "order_statistics_of_frames");
  EXPECT_NE(r.at("time_calibration").get<std::string>().find("skipped (LDM_CALIBRATION skip)"), std::string::npos);
  EXPECT_FALSE(r.contains("time_run_to_run_spread"));
}

TEST(Calibration, BadValuesAreRefusedNamingTheirOrigin) {
  const std::string dir = make_temp_dir("calibrate-bad");
  const auto option = ldmbench(std::string(kTinyRun) + " --calibration " + dir + "/none.json --out " + dir + "/a");
  EXPECT_EQ(option.status, 2) << option.output;
  EXPECT_NE(option.output.find("--calibration " + dir + "/none.json: neither auto, skip nor"), std::string::npos)
      << option.output;
  const auto variable = ldmbench(std::string(kTinyRun) + " --out " + dir + "/b", "LDM_CALIBRATION=sometimes");
  EXPECT_EQ(variable.status, 2) << variable.output;
  EXPECT_NE(variable.output.find("LDM_CALIBRATION sometimes"), std::string::npos) << variable.output;
  test::run_shell("printf '{\"spread\": 9}' > " + dir + "/wide.json");
  const auto file = ldmbench(std::string(kTinyRun) + " --calibration " + dir + "/wide.json --out " + dir + "/c");
  EXPECT_EQ(file.status, 2) << file.output;
  EXPECT_NE(file.output.find("wide.json: \"spread\" must be between 0 and 5"), std::string::npos) << file.output;
  // Nothing was measured into the refused folders.
  EXPECT_FALSE(std::filesystem::exists(dir + "/a/records.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/b/records.csv"));
}

TEST(Calibration, ProcessIsolationHandsTheParentsSpreadToEveryChild) {
  const std::string dir = make_temp_dir("calibrate-process");
  test::run_shell("printf '{\"spread\": 0.1, \"measured_at\": 1}' > " + dir + "/spread.json");
  const auto run = ldmbench(std::string(kTinyRun) + " --repetitions 2 --isolation process --calibration " + dir +
                            "/spread.json --out " + dir + "/run");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto r = only_record(dir + "/run");
  EXPECT_EQ(r.at("repetitions"), 2);
  EXPECT_EQ(r.at("time_interval"), "t_on_log_repetition_medians+run_to_run_spread");
  EXPECT_EQ(r.at("time_run_to_run_spread").get<double>(), 0.1);
}

// The probe reads the cache's earlier probes: one older than a day is dropped from the list;
// a written-before-pooling entry (no list) counts as one probe.
TEST(Calibration, ProbeDropsTheCachesProbesOlderThanADay) {
  const std::string cache = make_temp_dir("calibrate-old-cache");
  const std::string entry = own_cache_entry(cache);
  const RunToRunSpread old =
      test::probe_spread({0.9, 6, 4, int64_t(std::time(nullptr)) - kCalibrationMaxAgeSeconds - 60, 0.0});
  write_calibration_file(entry, old);
  const auto probe = ldmbench("calibrate --processes 2", "XDG_CACHE_HOME=" + cache);
  ASSERT_EQ(probe.status, 0) << probe.output;
  const RunToRunSpread cached = read_calibration_file(entry);
  EXPECT_EQ(cached.pooled_probes, 1u);
  EXPECT_EQ(cached.processes, 2u);
  ASSERT_EQ(cached.probes.size(), 1u);
  EXPECT_GT(cached.probes[0].measured_at, old.measured_at);  // the fresh one, alone
  // Pooled alone: sqrt(s^2 pairs / pairs), which is s but for rounding.
  EXPECT_DOUBLE_EQ(cached.spread, cached.probes[0].spread);
}

TEST(Calibration, AutoReadsAFreshCacheEntryWithoutProbing) {
  const std::string cache = make_temp_dir("calibrate-cache");
  // The entry this device would be cached under, fresh and at today's load.
  const std::string entry = own_cache_entry(cache);
  RunToRunSpread spread;
  spread.spread = 0.123;
  spread.measured_at = int64_t(std::time(nullptr));
  write_calibration_file(entry, spread);  // no load: any load holds
  const std::string out = make_temp_dir("calibrate-auto");
  const auto run = ldmbench(std::string(kTinyRun) + " --calibration auto --out " + out, "XDG_CACHE_HOME=" + cache);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("calibrating"), std::string::npos) << run.output;
  const auto r = only_record(out);
  EXPECT_EQ(r.at("time_run_to_run_spread").get<double>(), 0.123);
  EXPECT_NE(r.at("time_calibration").get<std::string>().find("cache " + entry), std::string::npos);
}

// What a tool reads before handing the cache entry to --calibration: where it is and whether
// auto would read it as it is; a missing entry is not current.
TEST(Calibration, ShowJsonSaysWhereTheEntryIsAndWhetherItIsCurrent) {
  const std::string cache = make_temp_dir("calibrate-show-cache");
  const std::string entry = own_cache_entry(cache);
  const auto missing = ldmbench("calibrate --show --json", "XDG_CACHE_HOME=" + cache);
  ASSERT_EQ(missing.status, 0) << missing.output;
  const auto none = nlohmann::json::parse(missing.output.substr(missing.output.find('{')));
  EXPECT_EQ(none.at("file"), entry);
  EXPECT_FALSE(none.at("cached").get<bool>());
  EXPECT_FALSE(none.at("current").get<bool>());
  RunToRunSpread spread;
  spread.spread = 0.123;
  spread.measured_at = int64_t(std::time(nullptr));
  write_calibration_file(entry, spread);  // no load: any load holds
  const auto fresh = ldmbench("calibrate --show --json", "XDG_CACHE_HOME=" + cache);
  ASSERT_EQ(fresh.status, 0) << fresh.output;
  const auto state = nlohmann::json::parse(fresh.output.substr(fresh.output.find('{')));
  EXPECT_TRUE(state.at("current").get<bool>()) << fresh.output;
  EXPECT_EQ(state.at("spread").get<double>(), 0.123);
  spread.measured_at -= kCalibrationMaxAgeSeconds + 60;
  write_calibration_file(entry, spread);
  const auto old = ldmbench("calibrate --show --json", "XDG_CACHE_HOME=" + cache);
  const auto aged = nlohmann::json::parse(old.output.substr(old.output.find('{')));
  EXPECT_FALSE(aged.at("current").get<bool>());
  EXPECT_FALSE(aged.at("stale").get<std::string>().empty());
}

}  // namespace
}  // namespace ldm
