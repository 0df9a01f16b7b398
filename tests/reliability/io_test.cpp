// A full disk and a failing configuration (issue 19, items 7 and 11): the configuration that
// hit ENOSPC became a `failed` record with exit 2 (the bad-input status), its images stayed as
// orphans (a 0-byte PNG under its final name), the messages omitted the errno, and a resume
// kept the failed record. Now an I/O failure stops the run with its own exit status (4) and
// the errno, the configuration in flight leaves nothing, and a resume measures it. A
// configuration that fails for another reason keeps no file either. One exit-status table.
#include <gtest/gtest.h>

#include <regex>

#include "harness/run/exit_codes.h"
#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

TEST(ReliabilityIo, AFullDiskStopsTheRunAndTheResumeMeasuresWhatItLost) {
  const fs::path dir = test::make_temp_dir("ldm-io");
  const std::string sweep = "run -N 2,3,4" + kTiny;
  // Which call writes the second configuration's PNG (a fault-free run, counted).
  const fs::path log = dir / "calls.log";
  const std::string count_env = std::string("LD_PRELOAD=") + LDM_FAULT_SHIM + " LDM_FAULT_DIR=" + (dir / "count").string() +
                                " LDM_FAULT_LOG=" + log.string();
  ASSERT_EQ(test::ldmbench(sweep + "--out " + (dir / "count" / "out").string(), count_env).status, 0);
  std::istringstream calls(test::read_text(log.string()));
  long at = 0;
  for (std::string line; std::getline(calls, line);)
    if (line.find("n3-") != std::string::npos && line.find(".png") != std::string::npos && line.find(" open ") != std::string::npos) {
      at = std::stol(line);
      break;
    }
  ASSERT_GT(at, 0) << test::read_text(log.string());
  // From that call on the disk is full.
  const fs::path out = dir / "run";
  const Outcome full = test::ldmbench(sweep + "--out " + out.string(),
                                      std::string("LD_PRELOAD=") + LDM_FAULT_SHIM + " LDM_FAULT_DIR=" + out.string() +
                                          " LDM_FAULT_AT=" + std::to_string(at) + " LDM_FAULT_STICKY=1");
  EXPECT_EQ(full.status, 4) << full.output;
  EXPECT_NE(full.output.find("I/O error"), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("No space left on device (ENOSPC)"), std::string::npos) << full.output;
  EXPECT_NE(full.output.find(".png"), std::string::npos) << full.output;  // the file it could not write
  EXPECT_NE(full.output.find("1 of 3 configurations are recorded"), std::string::npos) << full.output;
  FolderState state = inspect_folder(out);
  EXPECT_TRUE(state.problems.empty()) << joined(state.problems);  // no 0-byte PNG, no orphan
  ASSERT_EQ(state.ids.size(), 1u);
  for (const auto& entry : fs::directory_iterator(out / "images"))
    EXPECT_EQ(entry.path().filename().string().find("n3-"), std::string::npos) << entry.path();
  // Space freed: the same command measures the two that are missing.
  const Outcome resumed = test::ldmbench(sweep + "--out " + out.string());
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming: 1"), std::string::npos) << resumed.output;
  state = inspect_folder(out);
  EXPECT_TRUE(state.problems.empty()) << joined(state.problems);
  EXPECT_EQ(state.ids.size(), 3u);
  for (const auto& r : journal_entries(out, "record")) EXPECT_EQ(r["status"], "ok") << r["config_id"];
}

TEST(ReliabilityIo, AFailedConfigurationKeepsNoFile) {
  const fs::path dir = test::make_temp_dir("ldm-io");
  const fs::path out = dir / "run";
  const std::string command = "run -N 2,3" + kTiny + "--out " + out.string();
  ASSERT_EQ(test::ldmbench(command).status, 0);
  // The run's records taken out of its journal (its run entry kept: the same sweep), and a
  // file where the samples folder should be: both configurations are measured again and
  // fail after their images are written.
  const std::string journal = test::read_text((out / "records.jsonl").string());
  write_file(out / "records.jsonl", journal.substr(0, journal.find('\n') + 1));
  fs::remove_all(out / "images");
  fs::remove_all(out / "samples");
  write_file(out / "samples", "not a folder\n");
  const Outcome o = test::ldmbench(command);
  EXPECT_EQ(o.status, 3) << o.output;
  const auto records = journal_entries(out, "record");
  ASSERT_EQ(records.size(), 2u) << o.output;
  for (const auto& r : records) {
    EXPECT_EQ(r["status"], "failed") << r;
    EXPECT_NE(r["status_detail"].get<std::string>().find("samples"), std::string::npos) << r;
  }
  // Their images were written, then removed with the failure: none is an orphan.
  ASSERT_TRUE(fs::is_directory(out / "images"));
  for (const auto& entry : fs::directory_iterator(out / "images")) ADD_FAILURE() << "orphan " << entry.path();
}

TEST(ReliabilityIo, OneExitStatusTableIsDocumentedAndKept) {
  const std::string doc = test::read_text(std::string(LDM_TEST_SOURCE_DIR) + "/../docs/guide/reliability.md");
  ASSERT_FALSE(doc.empty());
  const std::vector<std::pair<int, std::string>> codes = {
      {kExitOk, "kExitOk"},           {kExitFailure, "kExitFailure"}, {kExitUsage, "kExitUsage"},
      {kExitSomeFailed, "kExitSomeFailed"}, {kExitIoError, "kExitIoError"}, {kExitBusy, "kExitBusy"},
      {kExitInterruptedBase + 2, "SIGINT"}, {kExitInterruptedBase + 15, "SIGTERM"}};
  for (const auto& [code, name] : codes) {
    const std::regex row("\\n\\| " + std::to_string(code) + " \\|[^\\n]*" + name);
    EXPECT_TRUE(std::regex_search(doc, row)) << "docs/guide/reliability.md has no row for " << code << " (" << name << ")";
  }
  // Distinct, and none is a signal's.
  std::set<int> distinct;
  for (const auto& [code, name] : codes) EXPECT_TRUE(distinct.insert(code).second) << code;
  EXPECT_LT(kExitBusy, kExitInterruptedBase);
  // lossy is a measurement, not a failure: its exit status is said.
  EXPECT_NE(doc.find("lossy"), std::string::npos);
}

}  // namespace
}  // namespace ldm::reliability
