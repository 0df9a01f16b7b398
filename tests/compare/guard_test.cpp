// The CI regression guard (scripts/regression-guard.sh) against the committed baseline
// results/baselines/ci-small: today's build passes it, and a configuration degraded on
// purpose fails it, by status (a fixed array too short: lossy) and by memory (one too long).
// And the per-frame samples the comparison tests are really where a run's records say.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "harness/compare/run_comparison.h"
#include "harness/measure/frame_samples.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

Outcome guard(const std::string& environment) {
  const fs::path script = fs::path(LDM_TEST_SOURCE_DIR) / ".." / "scripts" / "regression-guard.sh";
  return test::run_shell(environment + " LDMBENCH=" + std::string(LDM_BINARY_PATH) + " " +
                         script.string());
}

TEST(RegressionGuard, PassesOnTheCommittedBaseline) {
  const Outcome o = guard("");
  EXPECT_EQ(o.status, 0) << o.output;
  // Nothing time-based in the guard, not even a verdict it does not fail on.
  test::expect_contains(o.output, {"regressions: time", "not compared (--no-time)"});
  EXPECT_EQ(o.output.find("missing"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("SLOW"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("FAST"), std::string::npos) << o.output;
}

TEST(RegressionGuard, FailsOnAStatusRegression) {
  // k=2 is below the Cornell box's depth complexity (6): the fixed array drops fragments.
  const Outcome o = guard("LDM_GUARD_RUN_ARGS='--param ppfla:k=2' LDM_GUARD_COMPARE_ARGS='--ignore-param k'");
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("ok -> lossy WORSE"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("status 2"), std::string::npos) << o.output;  // both view counts
}

TEST(RegressionGuard, FailsOnAMemoryRegression) {
  // k=12 loses nothing (status stays ok) but allocates twice the entries.
  const Outcome o = guard("LDM_GUARD_RUN_ARGS='--param ppfla:k=12' LDM_GUARD_COMPARE_ARGS='--ignore-param k'");
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("memory 2 accuracy 0 status 0"), std::string::npos) << o.output;
}

TEST(RunRecords, NameEveryFramesSamples) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-samples")) / "run";
  std::string output;
  const int status = test::run_command(
      std::string(LDM_BINARY_PATH) + " run --scene cornell --structure psppsll -N 2 -R 32 "
      "--width 32 --height 32 --frames 4 --time-target 0 --warmup 1 --no-images --out " + out.string(), &output);
  ASSERT_EQ(status, 0) << output;
  const RunRecords run = load_run_records(out.string());
  ASSERT_EQ(run.records.size(), 1u);
  const auto& r = run.records[0];
  const auto samples = load_frame_samples((out / r["frame_samples_csv"].get<std::string>()).string());
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(r["repetitions"], 1);
  EXPECT_EQ(r["frames_measured"], 4);
  EXPECT_EQ(r["time_interval"], "order_statistics_of_frames");
  for (const char* subpass : {"build", "pass", "frame"}) {
    ASSERT_TRUE(samples[0].find(subpass)) << subpass;
    std::vector<double> times = *samples[0].find(subpass);
    ASSERT_EQ(times.size(), 4u) << subpass;
    std::sort(times.begin(), times.end());
    const std::string name = subpass;
    EXPECT_DOUBLE_EQ((times[1] + times[2]) / 2, r[name + "_ms_median"].get<double>()) << subpass;
    // Four frames cannot reach 95 %: the interval is [min, max] (coverage 87.5 %).
    EXPECT_DOUBLE_EQ(times.front(), r[name + "_ms_ci_low"].get<double>()) << subpass;
    EXPECT_DOUBLE_EQ(times.back(), r[name + "_ms_ci_high"].get<double>()) << subpass;
  }
  EXPECT_DOUBLE_EQ(r["time_interval_coverage"].get<double>(), 0.875);
}

// --repetitions: each repetition in its own context (or process), round robin, combined into
// one record whose median is the median of the repetitions' medians and whose interval is
// over them; the repetitions' own samples files are gone, their frames in one file.
TEST(RunRecords, RepetitionsAreCombinedIntoOneRecord) {
  for (const char* isolation : {"context", "process"}) {
    const fs::path out = fs::path(test::make_temp_dir("ldm-repetitions")) / "run";
    std::string output;
    const int status = test::run_command(
        std::string(LDM_BINARY_PATH) + " run --scene cornell --structure psppsll,dfbuffer -N 2 -R 32 "
        "--width 32 --height 32 --frames 3 --time-target 0 --warmup 1 --no-images --repetitions 3 "
        "--isolation " + isolation + " --out " + out.string(), &output);
    ASSERT_EQ(status, 0) << output;
    // Round robin: repetition 1 of both configurations before repetition 2 of either.
    const size_t second_psppsll = output.find("psppsll-ao-n2-r32-plane-prevframe (repetition 2/3)");
    const size_t first_dfbuffer = output.find("dfbuffer-ao-n2-r32-plane-prevframe (repetition 1/3)");
    ASSERT_NE(second_psppsll, std::string::npos) << output;
    EXPECT_LT(first_dfbuffer, second_psppsll) << output;
    const RunRecords run = load_run_records(out.string());
    ASSERT_EQ(run.records.size(), 2u);
    EXPECT_EQ(run.run["isolation"], isolation);
    for (const auto& r : run.records) {
      EXPECT_EQ(r["status"], "ok") << r.dump();
      EXPECT_EQ(r["repetitions"], 3);
      EXPECT_EQ(r["frames_per_repetition"], "3;3;3");
      EXPECT_EQ(r["time_interval"], "t_on_log_repetition_medians");
      EXPECT_FALSE(r.contains("repetition"));
      const auto samples = load_frame_samples((out / r["frame_samples_csv"].get<std::string>()).string());
      ASSERT_EQ(samples.size(), 3u);
      std::vector<double> medians;
      for (const auto& rep : samples) {
        std::vector<double> t = *rep.find("frame");
        std::sort(t.begin(), t.end());
        medians.push_back(t[1]);
      }
      std::sort(medians.begin(), medians.end());
      EXPECT_DOUBLE_EQ(r["frame_ms_median"].get<double>(), medians[1]);
      EXPECT_LE(r["frame_ms_ci_low"].get<double>(), medians[1]);
      EXPECT_GE(r["frame_ms_ci_high"].get<double>(), medians[1]);
      EXPECT_GT(r["frame_ms_rep_spread"].get<double>(), 0.0);
    }
    for (const auto& file : fs::directory_iterator(out / "samples"))
      EXPECT_EQ(file.path().filename().string().find("-rep"), std::string::npos) << file.path();
  }
}

// The command of a small run of `structures` (a comma list) on cornell, 2 repetitions of 3
// frames, no images, written to `out`; `options` added.
std::string two_repetitions_run(const std::string& structures, const fs::path& out,
                                const std::string& options = "") {
  return std::string(LDM_BINARY_PATH) + " run --scene cornell --structure " + structures +
         " -N 2 -R 32 --width 32 --height 32 --frames 3 --time-target 0 --warmup 1 --no-images "
         "--repetitions 2" + options + " --out " + out.string();
}

// A repetition measured alone (--step, as a child measures it) is journaled; the full
// command then resumes with it and measures only the rest.
TEST(RunRecords, RepetitionsResumeFromTheJournal) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-repetitions")) / "run";
  const std::string command = two_repetitions_run("psppsll", out);
  std::string output;
  ASSERT_EQ(test::run_command(command + " --step cornell-psppsll-ao-n2-r32-plane-prevframe", &output), 0) << output;
  EXPECT_NE(output.find("(repetition 1/2)"), std::string::npos) << output;
  EXPECT_EQ(output.find("configuration "), std::string::npos) << "a step prints no summary table:\n" << output;
  ASSERT_EQ(test::run_command(command, &output), 0) << output;
  EXPECT_NE(output.find("1 repetition(s) of unfinished ones"), std::string::npos) << output;
  EXPECT_EQ(output.find("(repetition 1/2)"), std::string::npos) << output;
  EXPECT_NE(output.find("(repetition 2/2)"), std::string::npos) << output;
  const RunRecords run = load_run_records(out.string());
  ASSERT_EQ(run.records.size(), 1u);
  EXPECT_EQ(run.records[0]["repetitions"], 2);
  ASSERT_NE(test::run_command(command + " --step nonexistent", &output), 0);
  EXPECT_NE(output.find("--step nonexistent: no such configuration"), std::string::npos) << output;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// A step of several configurations (what a child of --isolation process runs: one per
// round) measures the next repetition of each, once, and the second such step completes
// them: no repetition of a configuration shares a process with another of it.
TEST(RunRecords, AStepOfSeveralConfigurationsMeasuresTheNextRepetitionOfEach) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-step-several")) / "run";
  const std::string command = two_repetitions_run("psppsll,ppsll", out);
  const std::string step =
      " --step cornell-psppsll-ao-n2-r32-plane-prevframe,cornell-ppsll-ao-n2-r32-plane-prevframe";
  std::string output;
  ASSERT_EQ(test::run_command(command + step, &output), 0) << output;
  EXPECT_EQ(occurrences(output, "(repetition 1/2)"), 2u) << output;
  EXPECT_EQ(output.find("(repetition 2/2)"), std::string::npos) << "one repetition each per step:\n" << output;
  ASSERT_EQ(test::run_command(command + step, &output), 0) << output;
  EXPECT_EQ(occurrences(output, "(repetition 2/2)"), 2u) << output;
  const RunRecords run = load_run_records(out.string());
  ASSERT_EQ(run.records.size(), 2u);
  for (const auto& r : run.records) EXPECT_EQ(r["repetitions"], 2);
  ASSERT_NE(test::run_command(command + " --step cornell-psppsll-ao-n2-r32-plane-prevframe,nonexistent", &output), 0);
  EXPECT_NE(output.find("--step nonexistent: no such configuration"), std::string::npos) << output;
}

// --isolation process starts one child per round (each journals its invocation), not one
// per configuration and round: 2 configurations x 2 repetitions are 2 children.
TEST(RunRecords, ProcessIsolationStartsOneChildPerRepetitionRound) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-isolation-rounds")) / "run";
  std::string output;
  ASSERT_EQ(test::run_command(two_repetitions_run("psppsll,ppsll", out, " --calibration skip --isolation process"),
                              &output),
            0)
      << output;
  const std::string journal = test::read_text((out / "records.jsonl").string());
  EXPECT_EQ(occurrences(journal, "{\"run\""), 3u) << "the parent and two children:\n" << journal;
  const RunRecords run = load_run_records(out.string());
  ASSERT_EQ(run.records.size(), 2u);
  for (const auto& r : run.records) EXPECT_EQ(r["repetitions"], 2);
}

}  // namespace
}  // namespace ldm
