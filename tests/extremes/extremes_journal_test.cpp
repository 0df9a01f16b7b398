// records.jsonl (issue 12): every value type survives the journal, NaN and infinities too
// (the tables derived from it equal tables written directly), and a torn last line is
// dropped on reading and cut off before the next append.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/records/journal.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

Record sample(int64_t id) {
  Record r;
  r.set("config_id", "c" + std::to_string(id));
  r.set("count", id);
  r.set("ratio", 0.1 * double(id));
  r.set("whole", 3.0);  // a double that looks like an integer stays a double
  r.set("nan", std::nan(""));
  r.set("inf", INFINITY);
  r.set("flag", id % 2 == 0);
  r.set("text", "a, \"quoted\"\nline");
  r.put("empty", std::monostate{});
  return r;
}

TEST(ExtremesJournal, ValuesRoundTripAndTablesMatch) {
  const std::string path = test::make_temp_dir("ldm-journal") + "/records.jsonl";
  {
    RecordJournal journal(path);
    Record run;
    run.set("sweep_key", "k");
    journal.append_run(run);
    journal.append_record(sample(1));
    journal.append_record(sample(2));
  }
  const JournalContents contents = read_journal(path);
  ASSERT_EQ(contents.runs.size(), 1u);
  ASSERT_EQ(contents.records.size(), 2u);
  EXPECT_EQ(contents.torn_bytes, 0u);
  const std::vector<Record> direct = {sample(1), sample(2)};
  EXPECT_EQ(records_to_csv(contents.records), records_to_csv(direct));
  EXPECT_EQ(records_to_json(contents.records, contents.runs[0]),
            records_to_json(direct, contents.runs[0]));
  EXPECT_TRUE(std::holds_alternative<double>(*contents.records[0].get("whole")));
  EXPECT_TRUE(std::isnan(std::get<double>(*contents.records[0].get("nan"))));
}

TEST(ExtremesJournal, ATornLastLineIsDroppedAndCutOff) {
  const std::string path = test::make_temp_dir("ldm-journal") + "/records.jsonl";
  {
    RecordJournal journal(path);
    journal.append_record(sample(1));
  }
  std::ofstream(path, std::ios::app) << "{\"record\": {\"config_id\": \"c2\", \"co";  // killed
  const JournalContents torn = read_journal(path);
  EXPECT_EQ(torn.records.size(), 1u);
  EXPECT_GT(torn.torn_bytes, 0u);
  {
    RecordJournal journal(path);  // cuts the torn line off, then appends whole lines
    journal.append_record(sample(3));
  }
  const JournalContents repaired = read_journal(path);
  ASSERT_EQ(repaired.records.size(), 2u);
  EXPECT_EQ(repaired.torn_bytes, 0u);
  EXPECT_EQ(std::get<std::string>(*repaired.records[1].get("config_id")), "c3");
  // A complete line that is not a journal entry is an error naming the file and line.
  std::ofstream(path, std::ios::app) << "[1, 2]\n";
  try {
    read_journal(path);
    FAIL() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("records.jsonl:3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ldm
