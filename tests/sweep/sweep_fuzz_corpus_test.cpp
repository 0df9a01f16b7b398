// The sweep fuzzer's corpus and crash inputs (tests/fuzz/{corpus,crashes}/sweep/) replayed
// in the ordinary build: each parses or is refused with UserError, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/run/sweep_plan.h"
#include "harness/run/sweep_spec.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(SweepFuzzCorpus, InputsParseOrAreRefused) {
  size_t count = 0;
  for (const char* kind : {"corpus", "crashes"}) {
    const fs::path dir = fs::path(LDM_TEST_SOURCE_DIR) / "fuzz" / kind / "sweep";
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      ++count;
      try {
        SweepSpec spec = parse_sweep_spec(text.str(), "fuzz.json", current_sweep_vocabulary());
        sweep_combinations(spec);
      } catch (const UserError&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << entry.path() << ": " << e.what();
      }
    }
  }
  EXPECT_GE(count, 3u);
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
