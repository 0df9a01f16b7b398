// `ldmbench model` (issue 33): the cost model fitted on work counters. The fit's maths on
// synthetic records with known coefficients (Python's unittest, tests/work/test_model.py),
// and the command end to end on a tiny llvmpipe sweep: a table of coefficients in ns per
// unit, a saved fit that --predict applies, and a run without work columns refused naming
// its file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(ModelFit, SyntheticRecords) {
  const test::Outcome o =
      test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/work/test_model.py 2>&1");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("OK"), std::string::npos) << o.output;
}

TEST(ModelCli, FitsPredictsAndRefusesARunWithoutCounters) {
  const fs::path dir = test::make_temp_dir("ldm-model");
  const std::string tiny =
      " --scene cornell --structure ppfla,psppsll --pass ao -N 2,4 --width 48 --height 40 --frames 3 "
      "--time-target 0 --no-images --no-reference";
  const test::Outcome run = test::ldmbench("run" + tiny + " --out " + (dir / "run").string() + " 2>&1");
  ASSERT_EQ(run.status, 0) << run.output;

  const std::string fit = (dir / "fit.json").string();
  const test::Outcome model = test::ldmbench("model " + (dir / "run").string() + " --folds 2 --out " + fit + " 2>&1");
  ASSERT_EQ(model.status, 0) << model.output;
  for (const char* expected : {"· construct", "· ao", "· frame", "ns per fragment", "held-out median error",
                               "(fixed cost)", "summary:"})
    EXPECT_NE(model.output.find(expected), std::string::npos) << expected << "\n" << model.output;
  EXPECT_TRUE(fs::is_regular_file(fit));

  const test::Outcome predict =
      test::ldmbench("model --predict " + (dir / "run").string() + " --fit " + fit + " 2>&1");
  EXPECT_EQ(predict.status, 0) << predict.output;
  EXPECT_NE(predict.output.find("cornell-ppfla-ao-n4"), std::string::npos) << predict.output;
  EXPECT_NE(predict.output.find("predicted ms"), std::string::npos) << predict.output;
  EXPECT_NE(predict.output.find("measured on this device"), std::string::npos) << predict.output;

  // The fit of another device: refused, naming the fit.
  const test::Outcome other =
      test::ldmbench("model --predict " + (dir / "run").string() + " --fit " + fit + " --device nvidia 2>&1");
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_NE(other.output.find(fit + ": a fit for another device"), std::string::npos) << other.output;

  // A run without the counting replay has no work columns: refused, naming its records.
  const std::string plain = (dir / "plain").string();
  const test::Outcome no_work =
      test::ldmbench("run --scene cornell --structure ppfla --pass ao -N 2,4 --width 48 --height 40 --frames 3 "
                     "--time-target 0 --no-images --no-reference --no-work --out " + plain + " 2>&1");
  ASSERT_EQ(no_work.status, 0) << no_work.output;
  const test::Outcome refused = test::ldmbench("model " + plain + " 2>&1");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find(plain), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("no work columns"), std::string::npos) << refused.output;
  const test::Outcome predict_plain = test::ldmbench("model --predict " + plain + " --fit " + fit + " 2>&1");
  EXPECT_EQ(predict_plain.status, 2) << predict_plain.output;
  EXPECT_NE(predict_plain.output.find(plain), std::string::npos) << predict_plain.output;

  // Bad arguments: exit 2 before Python starts.
  EXPECT_EQ(test::ldmbench("model 2>&1").status, 2);
  EXPECT_EQ(test::ldmbench("model " + (dir / "missing").string() + " 2>&1").status, 2);
  EXPECT_EQ(test::ldmbench("model --predict " + (dir / "run").string() + " 2>&1").status, 2);
}

}  // namespace
}  // namespace ldm
