// The records fuzzer's corpus and crash inputs (tests/fuzz/{corpus,crashes}/records/)
// replayed in the ordinary build through the same judge (records_input.h): UserError or
// nothing, and tables derived from a journal always agree with it.
#include <gtest/gtest.h>

#include "reliability_support.h"
#include "support/fuzz_inputs.h"
#include "tests/fuzz/targets/records_input.h"

namespace ldm::reliability {
namespace {

TEST(ReliabilityFuzzCorpus, RecordsInputsAreJudgedWithoutCrashing) {
  // The judge refuses nothing itself: a UserError that escapes it is a failure too.
  const test::FuzzReplay replay = test::replay_fuzz_inputs(
      "records", [](const fs::path&, const std::string& bytes) { fuzz::judge_records_input(bytes); });
  EXPECT_GE(replay.inputs, 4u);
  EXPECT_EQ(replay.accepted, replay.inputs);
}

}  // namespace
}  // namespace ldm::reliability
