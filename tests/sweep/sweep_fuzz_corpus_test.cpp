// The sweep fuzzer's corpus and crash inputs (tests/fuzz/{corpus,crashes}/sweep/) replayed
// in the ordinary build: each parses or is refused with UserError, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/run/sweep_plan.h"
#include "harness/run/sweep_spec.h"
#include "harness/util/error.h"
#include "support/fuzz_inputs.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(SweepFuzzCorpus, InputsParseOrAreRefused) {
  const test::FuzzReplay replay = test::replay_fuzz_inputs("sweep", [](const fs::path&, const std::string& text) {
    SweepSpec spec = parse_sweep_spec(text, "fuzz.json", current_sweep_vocabulary());
    sweep_combinations(spec);
  });
  EXPECT_GE(replay.inputs, 3u);
}

// Every shipped sweep parses and expands (the default one is what a new user runs first).
TEST(SweepFuzzCorpus, ShippedSweepsAreValid) {
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(LDM_TEST_SOURCE_DIR) / ".." / "sweeps")) {
    if (entry.path().extension() != ".json") continue;
    ++checked;
    EXPECT_NO_THROW({
      const SweepPlan plan = plan_sweep(entry.path().string(), RunSettings());
      EXPECT_GT(plan.configurations.size(), 0u);
    }) << entry.path();
  }
  EXPECT_GE(checked, 2u);  // default.json and ci-small.json at least
}

}  // namespace
}  // namespace ldm
