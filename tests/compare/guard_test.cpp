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
#include "harness/compare/samples.h"
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
  EXPECT_NE(o.output.find("regressions: time"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("missing"), std::string::npos) << o.output;
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
      "--width 32 --height 32 --frames 4 --warmup 1 --no-images --out " + out.string(), &output);
  ASSERT_EQ(status, 0) << output;
  const RunRecords run = load_run_records(out.string());
  ASSERT_EQ(run.records.size(), 1u);
  const auto& r = run.records[0];
  const FrameSamples samples = load_frame_samples((out / r["frame_samples_csv"].get<std::string>()).string());
  for (const char* subpass : {"build", "frame"}) {
    ASSERT_TRUE(samples.count(subpass)) << subpass;
    std::vector<double> times = samples.at(subpass);
    ASSERT_EQ(times.size(), 4u) << subpass;
    std::sort(times.begin(), times.end());
    EXPECT_DOUBLE_EQ((times[1] + times[2]) / 2, r[std::string(subpass) + "_ms_median"].get<double>()) << subpass;
  }
}

}  // namespace
}  // namespace ldm
