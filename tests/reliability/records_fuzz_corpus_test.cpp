// The records fuzzer's corpus and crash inputs (tests/fuzz/{corpus,crashes}/records/)
// replayed in the ordinary build through the same judge (records_input.h): UserError or
// nothing, and tables derived from a journal always agree with it.
#include <gtest/gtest.h>

#include "reliability_support.h"
#include "tests/fuzz/targets/records_input.h"

namespace ldm::reliability {
namespace {

TEST(ReliabilityFuzzCorpus, RecordsInputsAreJudgedWithoutCrashing) {
  size_t count = 0;
  for (const char* kind : {"corpus", "crashes"}) {
    const fs::path dir = fs::path(LDM_TEST_SOURCE_DIR) / "fuzz" / kind / "records";
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().filename().string().front() == '.') continue;
      ++count;
      try {
        fuzz::judge_records_input(test::read_text(entry.path().string()));
      } catch (const std::exception& e) {
        ADD_FAILURE() << entry.path() << ": " << e.what();
      }
    }
  }
  EXPECT_GE(count, 4u);
}

}  // namespace
}  // namespace ldm::reliability
