// The run-to-run spread (harness/measure/run_to_run_spread.h), its cache rules and the
// widening of a record's intervals (harness/measuring/timing_columns.h); the machine state beside
// the times (harness/measuring/machine_state.h).
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "harness/measuring/machine_state.h"
#include "harness/measuring/timing_columns.h"
#include "harness/measure/run_to_run_spread.h"
#include "harness/stats/intervals.h"
#include "harness/util/error.h"
#include "support/probe_spread.h"
#include "support/subpass_time.h"

namespace ldm {
namespace {

TEST(RunToRunSpread, IsTheRmsLogRatioOverEveryPairOfProcesses) {
  // Three processes; "a/frame" in all (ratios 2 and 4 to the first, 2 between the others),
  // "b/frame" in two only (ratio 1), "c/frame" in one only (no pair), a 0 ms one ignored.
  const std::vector<ProbeMedians> processes = {
      {{"a/frame", 1.0}, {"b/frame", 3.0}, {"c/frame", 5.0}, {"d/frame", 0.0}},
      {{"a/frame", 2.0}, {"b/frame", 3.0}, {"d/frame", 1.0}},
      {{"a/frame", 4.0}},
  };
  const RunToRunSpread s = spread_from_processes(processes);
  EXPECT_EQ(s.processes, 3u);
  EXPECT_EQ(s.pairs, 4u);  // a: (0,1) (0,2) (1,2); b: (0,1)
  const double l2 = std::log(2.0);
  EXPECT_NEAR(s.spread, std::sqrt((l2 * l2 + 4 * l2 * l2 + l2 * l2 + 0) / 4), 1e-12);
}

TEST(RunToRunSpread, NeedsTwoProcessesWithSomethingInCommon) {
  EXPECT_TRUE(std::isnan(spread_from_processes({{{"a/frame", 1.0}}}).spread));
  EXPECT_TRUE(std::isnan(spread_from_processes({{{"a/frame", 1.0}}, {{"b/frame", 1.0}}}).spread));
}

TEST(RunToRunSpread, IsMeasuredAgainWhenOldOrAtAnotherLoad) {
  RunToRunSpread cached;
  cached.spread = 0.1;
  cached.measured_at = 1'000'000;
  cached.load_average = 1.0;
  EXPECT_EQ(calibration_staleness(cached, 1'000'000 + 3600, 1.4), "");
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + kCalibrationMaxAgeSeconds + 1, 1.0).find("h ago"),
            std::string::npos);
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + 60, 1.6).find("load average 1.60 now, 1.00"),
            std::string::npos);
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + 60, 0.4).find("load average"), std::string::npos);
  EXPECT_NE(calibration_staleness(cached, 1'000'000 - 60, 1.0), "");  // from the future: a clock moved
  EXPECT_EQ(calibration_staleness(cached, 1'000'000 + 60, std::nan("")), "");  // no load known now
}

TEST(RunToRunSpread, WidensOneRepetitionByTheWholeSpreadAndKRepetitionsByTheOtherRunsShare) {
  const double z = normal_quantile(0.975);
  EXPECT_NEAR(z, 1.959964, 1e-6);
  // One repetition: sqrt(within^2 + (z s)^2).
  EXPECT_NEAR(widened_log_half_width(0.03, 0.2, 1, z, RepetitionProcesses::Separate), std::hypot(0.03, z * 0.2), 1e-12);
  // K repetitions, each in its own process: the t interval holds this run's offsets; the other
  // run's median of K adds s^2/(2K).
  EXPECT_NEAR(widened_log_half_width(0.1, 0.2, 4, z, RepetitionProcesses::Separate),
              std::hypot(0.1, z * 0.2 / std::sqrt(8.0)), 1e-12);
  // K repetitions in one process share its offset: K does not shrink the spread's part, and
  // the t interval, which holds only the noise between them, counts where it is wider.
  EXPECT_NEAR(widened_log_half_width(0.1, 0.2, 4, z, RepetitionProcesses::Shared), z * 0.2, 1e-12);
  EXPECT_NEAR(widened_log_half_width(0.5, 0.2, 4, z, RepetitionProcesses::Shared), 0.5, 1e-12);
  // One repetition: where it ran does not matter.
  EXPECT_EQ(widened_log_half_width(0.03, 0.2, 1, z, RepetitionProcesses::Shared),
            widened_log_half_width(0.03, 0.2, 1, z, RepetitionProcesses::Separate));
  // No spread: unchanged.
  EXPECT_EQ(widened_log_half_width(0.03, std::nan(""), 1, z, RepetitionProcesses::Separate), 0.03);
  // Never narrower than either part.
  EXPECT_GE(widened_log_half_width(0.5, 0.01, 1, z, RepetitionProcesses::Separate), 0.5);
}

TEST(RunToRunSpread, RoundTripsThroughJsonAndRefusesBadFiles) {
  RunToRunSpread s = test::probe_spread({0.25, 180, 5, 1796265508, 0.75});
  s.device = "llvmpipe";
  s.host = "vm";
  const RunToRunSpread back = spread_from_json(spread_to_json(s), "x.json");
  EXPECT_EQ(back.spread, 0.25);
  EXPECT_EQ(back.pairs, 180u);
  EXPECT_EQ(back.measured_at, 1796265508);
  EXPECT_EQ(back.load_average, 0.75);
  EXPECT_EQ(back.device, "llvmpipe");
  try {
    spread_from_json("{\"spread\": -1}", "bad.json");
    ADD_FAILURE() << "a negative spread was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
  }
  EXPECT_THROW(spread_from_json("{\"pairs\": 3}", "missing.json"), UserError);
  EXPECT_THROW(spread_from_json("[1]", "array.json"), UserError);
  EXPECT_THROW(spread_from_json("{\"spread\": \"wide\"}", "text.json"), UserError);
}

// A probe of the day at about the fresh one's load pools with it (every log ratio weighing
// the same); one at another load, one older than a day and one of unknown load do not.
// The load is other processes' busy CPUs where the entry has them: the load average, which
// lags a minute, reads 1-2 right after ldmbench's own run on an idle machine.
TEST(RunToRunSpread, JudgesTheLoadByOtherProcessesBusyCpusWhereTheEntryHasThem) {
  RunToRunSpread cached;
  cached.spread = 0.1;
  cached.measured_at = 1'000'000;
  cached.load_average = 0.2;
  cached.busy_cpus = 0.05;
  // The average moved (a run just ended), the CPUs other work keeps busy did not: current.
  EXPECT_EQ(calibration_staleness(cached, 1'000'000 + 60, 1.9, 0.1), "");
  // Another job took a CPU: stale, and the why names the busy CPUs.
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + 60, 0.2, 1.2).find("keep 1.20 CPUs busy now, 0.05 before"),
            std::string::npos);
  // Busy CPUs unknown now, or an entry written before they were read: the load average decides.
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + 60, 1.9).find("load average 1.90"), std::string::npos);
  cached.busy_cpus = std::nan("");
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + 60, 1.9, 0.1).find("load average"), std::string::npos);
  // Age is judged first either way.
  cached.busy_cpus = 0.05;
  EXPECT_NE(calibration_staleness(cached, 1'000'000 + kCalibrationMaxAgeSeconds + 1, 0.2, 0.05).find("h ago"),
            std::string::npos);
  EXPECT_TRUE(same_load(2.0, 0.1, 0.2, 0.3));
  EXPECT_FALSE(same_load(0.2, 0.1, 0.2, 0.7));
  EXPECT_TRUE(same_load(0.2, std::nan(""), 0.6, 0.9));  // one lacks busy CPUs: the averages
  EXPECT_FALSE(same_load(std::nan(""), std::nan(""), 0.6, 0.9));
}

TEST(RunToRunSpread, PoolsProbesByOtherProcessesBusyCpusNotTheirLaggingLoadAverage) {
  const int64_t now = 2'000'000;
  ProbeEntry fresh_probe{0.08, 18, 4, now, 1.9};
  fresh_probe.busy_cpus = 0.0;
  const RunToRunSpread fresh = test::probe_spread(fresh_probe);
  ProbeEntry after_a_run{0.20, 18, 4, now - 600, 0.1};  // average 1.8 apart, both idle
  after_a_run.busy_cpus = 0.1;
  ProbeEntry beside_a_build{0.40, 18, 4, now - 300, 1.8};  // same average, a CPU taken
  beside_a_build.busy_cpus = 1.1;
  const ProbeEntry older{0.30, 18, 4, now - 900, 1.7};  // no busy CPUs: by its average, pooled
  const RunToRunSpread pooled = pool_with_earlier_probes(fresh, {after_a_run, beside_a_build, older}, now);
  EXPECT_EQ(pooled.pooled_probes, 3u);
  EXPECT_NEAR(pooled.spread, std::sqrt((0.08 * 0.08 + 0.2 * 0.2 + 0.3 * 0.3) * 18 / 54), 1e-12);
  EXPECT_EQ(pooled.busy_cpus, 0.0);
  // Kept through the cache file.
  const RunToRunSpread back = spread_from_json(spread_to_json(pooled), "test");
  EXPECT_EQ(back.busy_cpus, 0.0);
  ASSERT_EQ(back.probes.size(), 4u);
  EXPECT_EQ(back.probes[1].busy_cpus, 1.1);
  EXPECT_TRUE(std::isnan(back.probes[2].busy_cpus));
}

TEST(MachineState, CountsTheCpusOtherProcessesKeepBusyFromProcStat) {
  const std::string before =
      "cpu  100 0 50 800 50 0 0 0 0 0\ncpu0 50 0 25 400 25 0 0 0 0 0\ncpu1 50 0 25 400 25 0 0 0 0 0\nintr 1\n";
  const std::string after =
      "cpu  200 0 100 900 50 0 0 0 0 0\ncpu0 150 0 75 400 25 0 0 0 0 0\ncpu1 50 0 25 500 25 0 0 0 0 0\n";
  const auto a = parse_cpu_ticks(before), b = parse_cpu_ticks(after);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->busy, 150u);    // user + system
  EXPECT_EQ(a->total, 1000u);  // idle and iowait count in the total only
  // 150 busy ticks of 250 on 2 CPUs: one CPU and a fifth kept busy.
  EXPECT_NEAR(*busy_cpus_between(*a, *b, 2), 1.2, 1e-12);
  EXPECT_FALSE(busy_cpus_between(*a, *a, 2));  // no tick passed
  EXPECT_FALSE(parse_cpu_ticks("intr 1\n"));
  // This machine's own reading, where it has /proc/stat: between none and every CPU busy.
  if (const auto now = busy_cpus_now(0.05)) {
    EXPECT_GE(*now, 0.0);
    EXPECT_LE(*now, double(std::thread::hardware_concurrency()) + 1e-9);
  }
}

TEST(RunToRunSpread, PoolsAFreshProbeWithTheDaysProbesAtItsLoad) {
  const int64_t now = 2'000'000;
  const RunToRunSpread fresh = test::probe_spread({0.08, 18, 4, now, 1.0});
  const std::vector<ProbeEntry> earlier = {
      {0.20, 18, 4, now - 3600, 1.3},                         // same load (within 0.5): pooled
      {0.30, 36, 6, now - 600, 0.4},                          // 0.6 below: kept, not pooled
      {0.90, 18, 4, now - kCalibrationMaxAgeSeconds - 1, 1.0},  // older than a day: dropped
      {0.50, 18, 4, now - 60, std::nan("")},                  // load unknown: kept, not pooled
  };
  const RunToRunSpread pooled = pool_with_earlier_probes(fresh, earlier, now);
  EXPECT_NEAR(pooled.spread, std::sqrt((0.08 * 0.08 * 18 + 0.20 * 0.20 * 18) / 36), 1e-12);
  EXPECT_EQ(pooled.pairs, 36u);
  EXPECT_EQ(pooled.processes, 8u);
  EXPECT_EQ(pooled.pooled_probes, 2u);
  ASSERT_EQ(pooled.probes.size(), 4u);  // the day's three earlier ones and the fresh one, last
  EXPECT_EQ(pooled.probes.back().spread, 0.08);
  EXPECT_EQ(pooled.measured_at, now);
  EXPECT_EQ(pooled.load_average, 1.0);
  // Alone, it is itself.
  const RunToRunSpread alone = pool_with_earlier_probes(fresh, {}, now);
  EXPECT_EQ(alone.spread, 0.08);
  EXPECT_EQ(alone.pooled_probes, 1u);
  EXPECT_EQ(alone.probes.size(), 1u);
}

// Probes keep their processes' medians, and pooling pairs the processes of different probes:
// two probes each steady within (ratio 1 between its processes) but a factor 2 apart (a
// slower hour) give a spread that neither shows alone. A probe by another build is not pooled.
TEST(RunToRunSpread, PoolingPairsTheProcessesOfProbesMinutesApart) {
  const int64_t now = 2'000'000;
  const RunToRunSpread fresh =
      test::probe_spread({0, 1, 2, now, 1.0, "abc", {{{"a/frame", 2.0}}, {{"a/frame", 2.0}}}});
  ProbeEntry earlier{0, 1, 2, now - 1800, 1.2, "abc", {{{"a/frame", 1.0}}, {{"a/frame", 1.0}}}};
  ProbeEntry other_build{0, 1, 2, now - 900, 1.0, "def", {{{"a/frame", 8.0}}, {{"a/frame", 8.0}}}};
  const RunToRunSpread pooled = pool_with_earlier_probes(fresh, {earlier, other_build}, now);
  // 4 processes: 6 pairs, the 4 across the two probes at log 2, the 2 within at 0.
  EXPECT_EQ(pooled.pairs, 6u);
  EXPECT_NEAR(pooled.spread, std::sqrt(4 * std::log(2.0) * std::log(2.0) / 6), 1e-12);
  EXPECT_EQ(pooled.pooled_probes, 2u);
  EXPECT_EQ(pooled.processes, 4u);
  ASSERT_EQ(pooled.probes.size(), 3u);
  const RunToRunSpread back = spread_from_json(spread_to_json(pooled), "medians.json");
  ASSERT_EQ(back.probes.size(), 3u);
  EXPECT_EQ(back.probes[0].commit, "abc");
  ASSERT_EQ(back.probes[0].medians.size(), 2u);
  EXPECT_EQ(back.probes[0].medians[1].at("a/frame"), 1.0);
  EXPECT_EQ(back.probes[2].medians[0].at("a/frame"), 2.0);
  EXPECT_THROW(spread_from_json("{\"spread\": 0.1, \"probes\": [{\"spread\": 0.1, \"pairs\": 3, \"medians\": [{\"a\": \"x\"}]}]}",
                                "m.json"),
               UserError);
}

TEST(RunToRunSpread, KeepsAtMostTheNewestProbesAndRoundTripsThemThroughJson) {
  const int64_t now = 2'000'000;
  std::vector<ProbeEntry> earlier;
  for (int i = 0; i < 30; ++i) earlier.push_back({0.1 + 0.01 * i, 6, 4, now - 3000 + 100 * i, 1.0});
  const RunToRunSpread fresh = test::probe_spread({0.2, 6, 4, now, 1.0});
  const RunToRunSpread pooled = pool_with_earlier_probes(fresh, earlier, now);
  ASSERT_EQ(pooled.probes.size(), kCalibrationKeptProbes);
  EXPECT_DOUBLE_EQ(pooled.probes.front().spread, 0.1 + 0.01 * (30 - (kCalibrationKeptProbes - 1)));
  EXPECT_EQ(pooled.pooled_probes, kCalibrationKeptProbes);
  const RunToRunSpread back = spread_from_json(spread_to_json(pooled), "pooled.json");
  EXPECT_EQ(back.pooled_probes, kCalibrationKeptProbes);
  ASSERT_EQ(back.probes.size(), kCalibrationKeptProbes);
  EXPECT_EQ(back.probes.back().spread, 0.2);
  EXPECT_EQ(back.probes.back().measured_at, now);
  EXPECT_EQ(back.probes.front().load_average, 1.0);
  EXPECT_THROW(spread_from_json("{\"spread\": 0.1, \"probes\": [{\"spread\": -1, \"pairs\": 3}]}", "p.json"),
               UserError);
  EXPECT_THROW(spread_from_json("{\"spread\": 0.1, \"probes\": 3}", "p.json"), UserError);
}

TEST(RunToRunSpread, KeysTheCacheByDeviceDriverAndHost) {
  const std::string key = calibration_key("llvmpipe (LLVM 15)", "4.5 Mesa", "vm");
  EXPECT_EQ(key.rfind("spread-vm-4_5_Mesa-", 0), 0u) << key;
  EXPECT_NE(key, calibration_key("llvmpipe (LLVM 15)", "4.6 Mesa", "vm"));
  EXPECT_NE(key, calibration_key("llvmpipe (LLVM 15)", "4.5 Mesa", "vm2"));
  EXPECT_NE(key, calibration_key("zink", "4.5 Mesa", "vm"));
  EXPECT_EQ(key.find('/'), std::string::npos);
}

Record timed_record(size_t repetitions) {
  Record r;
  r.set("repetitions", repetitions);
  r.set("time_interval", kFrameInterval);
  r.set("time_half_width", 0.02);
  test::set_subpass_time(r, "frame", 10.0, 9.8, 10.2);
  test::set_subpass_time(r, "build", 4.0, 3.9, 4.2);
  test::set_subpass_time(r, "rebuild", 0.0, 0.0, 0.0);  // a sub-pass no frame ran
  return r;
}

double number(const Record& r, const std::string& key) { return std::get<double>(*r.get(key)); }

TEST(WidenTimeIntervals, WidensEverySubpassAndSaysSo) {
  Record r = timed_record(1);
  RunToRunSpread spread;
  spread.spread = 0.2;
  widen_time_intervals(r, &spread, "file f.json", RepetitionProcesses::Separate);
  const double z = normal_quantile(0.975);
  const double h = widened_log_half_width(std::log(10.0 / 9.8), 0.2, 1, z, RepetitionProcesses::Separate);  // the wider side
  EXPECT_NEAR(number(r, "frame_ms_ci_low"), 10.0 * std::exp(-h), 1e-9);
  EXPECT_NEAR(number(r, "frame_ms_ci_high"), 10.0 * std::exp(h), 1e-9);
  const double hb = widened_log_half_width(std::log(4.2 / 4.0), 0.2, 1, z, RepetitionProcesses::Separate);  // the wider side
  EXPECT_NEAR(number(r, "build_ms_ci_low"), 4.0 * std::exp(-hb), 1e-9);
  EXPECT_EQ(number(r, "rebuild_ms_ci_high"), 0.0);  // 0 ms stays 0 ms
  EXPECT_EQ(std::get<std::string>(*r.get("time_interval")), std::string(kFrameInterval) + kRunToRunSuffix);
  EXPECT_EQ(number(r, "time_half_width_within_run"), 0.02);
  EXPECT_NEAR(number(r, "time_half_width"), std::exp(h) - 1, 1e-9);
  EXPECT_EQ(number(r, "time_run_to_run_spread"), 0.2);
  EXPECT_EQ(std::get<std::string>(*r.get("time_calibration")), "file f.json");
  // Twice is once: a resumed or combined record is not widened again.
  const double high = number(r, "frame_ms_ci_high");
  widen_time_intervals(r, &spread, "file f.json", RepetitionProcesses::Separate);
  EXPECT_EQ(number(r, "frame_ms_ci_high"), high);
}

TEST(WidenTimeIntervals, RepetitionsInOneProcessKeepTheWholeSpread) {
  RunToRunSpread spread;
  spread.spread = 0.2;
  const double z = normal_quantile(0.975);
  Record shared = timed_record(3), separate = timed_record(3);
  widen_time_intervals(shared, &spread, "file f.json", RepetitionProcesses::Shared);
  widen_time_intervals(separate, &spread, "file f.json", RepetitionProcesses::Separate);
  // --isolation context: the three share this process's offset, so the interval is the
  // spread's whole z s; --isolation process: three processes' offsets average down.
  EXPECT_NEAR(number(shared, "frame_ms_ci_high"), 10.0 * std::exp(z * 0.2), 1e-9);
  EXPECT_LT(number(separate, "frame_ms_ci_high"), number(shared, "frame_ms_ci_high"));
  EXPECT_NEAR(number(separate, "frame_ms_ci_high"),
              10.0 * std::exp(std::hypot(std::log(10.0 / 9.8), z * 0.2 / std::sqrt(6.0))), 1e-9);  // the wider side
}

TEST(WidenTimeIntervals, WithoutASpreadOnlySaysWhy) {
  Record r = timed_record(1);
  widen_time_intervals(r, nullptr, "skipped (--calibration skip): intervals are within-run only",
                       RepetitionProcesses::Separate);
  EXPECT_EQ(number(r, "frame_ms_ci_high"), 10.2);
  EXPECT_EQ(std::get<std::string>(*r.get("time_interval")), kFrameInterval);
  EXPECT_EQ(r.get("time_run_to_run_spread"), nullptr);
  EXPECT_NE(std::get<std::string>(*r.get("time_calibration")).find("skipped"), std::string::npos);
  Record failed;  // nothing timed: nothing said
  widen_time_intervals(failed, nullptr, "skipped", RepetitionProcesses::Separate);
  EXPECT_EQ(failed.get("time_calibration"), nullptr);
}

TEST(MachineState, ReadsNvidiaSmiClocksAndWarnsAboutThrottlingAndClockChanges) {
  const auto gpu = parse_nvidia_smi_clocks("1980, 312.45, 0x0000000000000000");
  ASSERT_TRUE(gpu);
  EXPECT_EQ(gpu->sm_clock_mhz, 1980);
  EXPECT_NEAR(gpu->power_w, 312.45, 1e-9);
  EXPECT_EQ(gpu->throttle_reasons, "0x0000000000000000");
  const auto no_power = parse_nvidia_smi_clocks("1410, [N/A], 0x0000000000000001");
  ASSERT_TRUE(no_power);
  EXPECT_TRUE(std::isnan(no_power->power_w));
  EXPECT_EQ(gpu->max_sm_clock_mhz, 0);  // not asked for
  const auto with_max = parse_nvidia_smi_clocks("345, 80.72, 0x0000000000000001, 1980");
  ASSERT_TRUE(with_max);
  EXPECT_EQ(with_max->max_sm_clock_mhz, 1980);
  EXPECT_EQ(with_max->throttle_reasons, "0x0000000000000001");
  EXPECT_FALSE(parse_nvidia_smi_clocks("garbage"));
  EXPECT_FALSE(parse_nvidia_smi_clocks("N/A, 1, 0x0"));

  MachineState start, end;
  start.gpu = *gpu;
  end.gpu = *gpu;
  EXPECT_EQ(clock_change_warning(start, end), "");
  end.gpu->sm_clock_mhz = 1500;
  EXPECT_NE(clock_change_warning(start, end).find("SM clock changed"), std::string::npos);
  end.gpu = *gpu;
  end.gpu->throttle_reasons = "0x0000000000000001";  // idle only: not throttling
  EXPECT_EQ(clock_change_warning(start, end), "");
  end.gpu->throttle_reasons = "0x0000000000000020";  // software slowdown
  EXPECT_NE(clock_change_warning(start, end).find("throttled"), std::string::npos);
  // Steady but far below the maximum (an H200 left at its idle clock): a warning too.
  start.gpu = *with_max;
  end.gpu = *with_max;
  EXPECT_NE(clock_change_warning(start, end).find("below 90 % of its 1980 MHz maximum"), std::string::npos)
      << clock_change_warning(start, end);
  start.gpu->sm_clock_mhz = end.gpu->sm_clock_mhz = 1900;
  EXPECT_EQ(clock_change_warning(start, end), "");
  Record with_max_column;
  set_machine_state_columns(with_max_column, start, end);
  EXPECT_EQ(std::get<double>(*with_max_column.get("gpu_sm_clock_max_mhz")), 1980);
  MachineState cpu_a, cpu_b;
  cpu_a.cpu_mhz = 3000;
  cpu_b.cpu_mhz = 2000;
  EXPECT_NE(clock_change_warning(cpu_a, cpu_b).find("CPU clock changed"), std::string::npos);
  cpu_b.cpu_mhz = 2900;
  EXPECT_EQ(clock_change_warning(cpu_a, cpu_b), "");
}

TEST(MachineState, RecordsBothEndsOfWhatWasRead) {
  MachineState start, end;
  start.load_average = 0.5;
  end.load_average = 1.5;
  start.cpu_mhz = 2600;  // the end's unknown: no cpu column
  start.cpu_governor = "performance";
  Record r;
  set_machine_state_columns(r, start, end);
  EXPECT_EQ(std::get<double>(*r.get("load_average_start")), 0.5);
  EXPECT_EQ(std::get<double>(*r.get("load_average_end")), 1.5);
  EXPECT_EQ(std::get<std::string>(*r.get("cpu_governor")), "performance");
  EXPECT_EQ(r.get("cpu_mhz_start"), nullptr);
  EXPECT_EQ(r.get("gpu_sm_clock_mhz_start"), nullptr);
  // This machine: a load average is always readable on Linux.
  EXPECT_TRUE(sample_machine_state({}).load_average.has_value());
}

}  // namespace
}  // namespace ldm
