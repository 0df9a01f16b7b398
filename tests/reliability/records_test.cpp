// Records read back are validated (issue 19, item 9): `ldmbench merge` accepted a journal
// record with a renamed key (records.csv grew a st###ture_params column); `ldmbench report`
// used a tampered records.csv (n_views 999) and ignored a truncated records.json. Now the
// records must follow the column schema and the tables must be what the journal gives.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <sstream>

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

// The journal's lines, one string each.
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}
std::string joined_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

// Every file under `dir` with its bytes: a refused merge must leave its OUT as it was.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    files[entry.path().string()] = entry.is_regular_file() ? test::read_text(entry.path().string()) : "<dir>";
  return files;
}

// Issue 35: records of another build were exempt from the schema check (its schema could
// differ), so a corrupted column name in them went through. Now every run entry declares its
// build's schema and each record is checked against its own build's: a column it does not
// declare, or one it always writes missing, is refused naming the file, line and column,
// and an existing OUT is left exactly as it was.
TEST(ReliabilityRecords, MergeChecksEveryRecordAgainstItsOwnBuildsSchema) {
  const fs::path dir = test::make_temp_dir("ldm-records");
  const fs::path run = small_run(dir, "run");
  // As written by another build: its git_commit everywhere (run entry and records).
  const std::string other = std::regex_replace(test::read_text((run / "records.jsonl").string()),
                                               std::regex("\"git_commit\":\"[^\"]*\""),
                                               "\"git_commit\":\"another-build\"");
  const std::vector<std::string> lines = split_lines(other);
  std::vector<size_t> record_lines;
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind("{\"record\":", 0) == 0) record_lines.push_back(i);
  ASSERT_EQ(record_lines.size(), 2u);
  const fs::path out = dir / "merged";
  fs::create_directories(out);
  write_file(out / "notes.txt", "kept\n");
  const auto before = snapshot(out);
  auto merge_with = [&](const std::vector<std::string>& journal) {
    write_file(run / "records.jsonl", joined_lines(journal));
    return test::ldmbench("merge " + out.string() + " " + run.string());
  };

  // Intact, another build's records merge (into a fresh folder).
  {
    write_file(run / "records.jsonl", other);
    const Outcome o = test::ldmbench("merge " + (dir / "fresh").string() + " " + run.string());
    EXPECT_EQ(o.status, 0) << o.output;
  }
  // A corrupted column name in the last record.
  std::vector<std::string> journal = lines;
  journal[record_lines[1]] = replaced(journal[record_lines[1]], "\"structure_params\":", "\"st###ture_params\":");
  Outcome o = merge_with(journal);
  EXPECT_EQ(o.status, 2) << o.output;
  const std::string at = "records.jsonl:" + std::to_string(record_lines[1] + 1);
  EXPECT_NE(o.output.find(at), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("column 'st###ture_params' is not in the record schema"), std::string::npos) << o.output;
  EXPECT_EQ(snapshot(out), before);
  // An always-written column missing from the first record.
  journal = lines;
  journal[record_lines[0]] = std::regex_replace(journal[record_lines[0]], std::regex(",\"wall_seconds\":[^,}]*"), "");
  o = merge_with(journal);
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("records.jsonl:" + std::to_string(record_lines[0] + 1)), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("column 'wall_seconds' is missing"), std::string::npos) << o.output;
  EXPECT_EQ(snapshot(out), before);
  // A run entry of another build that declares no schema: nothing to check against.
  journal = lines;
  for (auto& line : journal)
    if (line.rfind("{\"run\":", 0) == 0)
      line = std::regex_replace(line, std::regex(",\"schema_columns\":\"[^\"]*\""), "");
  o = merge_with(journal);
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("declares no schema"), std::string::npos) << o.output;
  EXPECT_EQ(snapshot(out), before);
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
