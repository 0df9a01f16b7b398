// Records read back are validated (issue 19, item 9): `ldmbench merge` accepted a journal
// record with a renamed key (records.csv grew a st###ture_params column); `ldmbench report`
// used a tampered records.csv (n_views 999) and ignored a truncated records.json. Now the
// records must follow the column schema and the tables must be what the journal gives.
#include <gtest/gtest.h>

#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

fs::path small_run(const fs::path& dir, const std::string& name) {
  const fs::path out = dir / name;
  const Outcome o = test::ldmbench("run -N 2,3" + kTiny + "--out " + out.string());
  EXPECT_EQ(o.status, 0) << o.output;
  return out;
}

TEST(ReliabilityRecords, MergeRefusesAColumnOutsideTheSchema) {
  const fs::path dir = test::make_temp_dir("ldm-records");
  const fs::path run = small_run(dir, "run");
  write_file(run / "records.jsonl",
             replaced(test::read_text((run / "records.jsonl").string()), "\"structure_params\":", "\"st###ture_params\":"));
  const Outcome o = test::ldmbench("merge " + (dir / "merged").string() + " " + run.string());
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("column 'st###ture_params' is not in the record schema"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("records.jsonl"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "merged" / "records.csv"));
}

TEST(ReliabilityRecords, ReportAndCompareRefuseTablesThatDisagreeWithTheJournal) {
  const fs::path dir = test::make_temp_dir("ldm-records");
  const fs::path run = small_run(dir, "run");
  // The untouched run compares with itself.
  Outcome o = test::ldmbench("compare " + run.string() + " " + run.string() + " --no-time");
  EXPECT_EQ(o.status, 0) << o.output;
  // A tampered records.csv: n_views 999.
  const std::string csv = test::read_text((run / "records.csv").string());
  const auto rows = parse_csv(csv);
  ASSERT_GE(rows.size(), 2u);
  const size_t column = size_t(std::find(rows[0].begin(), rows[0].end(), "n_views") - rows[0].begin());
  ASSERT_LT(column, rows[0].size());
  std::string tampered;
  for (size_t r = 0; r < rows.size(); ++r) {
    for (size_t c = 0; c < rows[r].size(); ++c) {
      const std::string cell = r == 1 && c == column ? "999" : rows[r][c];
      tampered += (c ? "," : "") + (cell.find_first_of(",\"\n") == std::string::npos ? cell : "\"" + cell + "\"");
    }
    tampered += "\n";
  }
  write_file(run / "records.csv", tampered);
  o = test::ldmbench("report " + run.string() + " --out " + (dir / "report").string());
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("records.csv disagrees with"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("column n_views: '999' in the table, '2' in the journal"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "report"));
  write_file(run / "records.csv", csv);
  // A truncated records.json.
  const std::string json = test::read_text((run / "records.json").string());
  write_file(run / "records.json", json.substr(0, json.size() / 2));
  for (const std::string& command : {"report " + run.string() + " --out " + (dir / "report").string(),
                                     "compare " + run.string() + " " + run.string() + " --no-time"}) {
    o = test::ldmbench(command);
    EXPECT_EQ(o.status, 2) << command << "\n" << o.output;
    EXPECT_NE(o.output.find("records.json: malformed JSON at line"), std::string::npos) << command << "\n" << o.output;
  }
  // A records.json whose value was edited (the tables agree with each other, not the journal).
  nlohmann::json edited = nlohmann::json::parse(json);
  edited["records"][1]["bytes_allocated"] = 1;
  write_file(run / "records.json", edited.dump(2));
  o = test::ldmbench("compare " + run.string() + " " + run.string() + " --no-time");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("column bytes_allocated"), std::string::npos) << o.output;
  // Without a journal (a copied records.json), the schema still holds.
  fs::remove(run / "records.jsonl");
  edited = nlohmann::json::parse(json);
  edited["records"][0]["n_views"] = "two";
  write_file(run / "records.json", edited.dump(2));
  o = test::ldmbench("compare " + run.string() + " " + run.string() + " --no-time");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("column 'n_views' (views) holds two, not a number"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace ldm::reliability
