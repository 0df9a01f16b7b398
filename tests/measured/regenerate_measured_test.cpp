// scripts/regenerate_measured.py (issue 32, item 8): docs/ keeps a committed run's records and
// not its images; the script measures the run's recorded command again and puts the images
// back. Proven here on a small run laid out as docs/ lays one out: its images removed, then
// regenerated, must be the same files byte for byte (the same build renders the same pixels
// and writes the same PNG and EXR bytes), and the committed records must be left as they were.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/test_support.h"

namespace fs = std::filesystem;
namespace test = ldm::test;

namespace {

std::string script() { return std::string(LDM_TEST_SOURCE_DIR) + "/../scripts/regenerate_measured.py"; }

}  // namespace

TEST(RegenerateMeasured, RemovedImagesComeBackByteForByteAndRecordsStayUntouched) {
  const fs::path root = test::make_temp_dir("regenerate");
  const fs::path run = root / "docs" / "measured" / "small";
  fs::create_directories(run.parent_path());
  // Run from ROOT with a relative --out, as the committed runs were; a fixed frame count (no
  // time target) so that the two runs' records agree in every column but time.
  const auto made = test::run_shell("cd " + root.string() + " && " + LDM_BINARY_PATH +
                                    " run --scene cornell --structure psppsll --pass ao -N 2 -R 16"
                                    " --width 32 --height 32 --frames 2 --warmup 0 --time-target 0 --reference-spp 4"
                                    " --calibration skip --out docs/measured/small");
  ASSERT_EQ(made.status, 0) << made.output;
  const fs::path kept = root / "images-as-measured";
  fs::rename(run / "images", kept);
  const std::string records = test::read_text((run / "records.jsonl").string());

  const auto listed = test::run_shell(std::string(LDM_PYTHON) + " " + script() + " " + root.string());
  ASSERT_EQ(listed.status, 0) << listed.output;
  EXPECT_NE(listed.output.find("docs/measured/small: images absent"), std::string::npos) << listed.output;

  const auto regenerated = test::run_shell(std::string(LDM_PYTHON) + " " + script() + " --images --ldmbench " +
                                           LDM_BINARY_PATH + " " + root.string());
  ASSERT_EQ(regenerated.status, 0) << regenerated.output;
  EXPECT_EQ(regenerated.output.find("note:"), std::string::npos)
      << "the same build must give the same records: " << regenerated.output;
  int compared = 0;
  for (const auto& image : fs::directory_iterator(kept)) {
    const fs::path again = run / "images" / image.path().filename();
    ASSERT_TRUE(fs::exists(again)) << again;
    EXPECT_EQ(test::read_text(again.string()), test::read_text(image.path().string())) << again;
    ++compared;
  }
  EXPECT_GE(compared, 4) << "the AO image, its reference and maps in PNG and EXR";
  EXPECT_EQ(test::read_text((run / "records.jsonl").string()), records) << "the committed records were rewritten";
}

// scripts/ldmrecords (issue 32, item 5): its readers, and no script in scripts/ reading records
// its own way (tests/measured/test_ldmrecords.py, Python's unittest).
TEST(Ldmrecords, OneReaderForEveryScript) {
  const auto o = test::run_shell(std::string("LDMBENCH=") + LDM_BINARY_PATH + " " + LDM_PYTHON + " " +
                                 LDM_TEST_SOURCE_DIR + "/measured/test_ldmrecords.py -v");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("test_time_machine_state_and_job_vary_results_do_not"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("skipped"), std::string::npos) << "the schema's flag must be checked here: " << o.output;
}
