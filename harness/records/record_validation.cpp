#include "harness/records/record_validation.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/records/columns.h"
#include "harness/records/journal.h"
#include "harness/records/run_folder.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"
#include "harness/util/version.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

const char* const kStatuses[] = {"ok", "lossy", "invalid", "failed"};

std::string read_whole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path.string() + ": cannot read (" + errno_text(errno) + ")");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string clipped(std::string text) {
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return "'" + text + "'";
}

// How to read a difference between a table and its journal.
constexpr const char* kTableHint =
    " (the tables are derived from the journal: a run killed between the two leaves them "
    "behind, and rerunning the same command resumes and rewrites them; otherwise the table "
    "was edited or truncated)";

// Whether a CSV cell reads as the journal's value (formatting aside).
bool cell_reads_as(const std::string& cell, const RecordValue* value) {
  if (!value || std::holds_alternative<std::monostate>(*value)) return cell.empty();
  if (const bool* b = std::get_if<bool>(value)) return cell == (*b ? "true" : "false");
  if (const std::string* s = std::get_if<std::string>(value)) return cell == *s;
  char* end = nullptr;
  if (const int64_t* i = std::get_if<int64_t>(value)) {
    const long long parsed = std::strtoll(cell.c_str(), &end, 10);
    return !cell.empty() && *end == '\0' && parsed == *i;
  }
  const double d = std::get<double>(*value);
  if (std::isnan(d)) return cell == "nan";
  const double parsed = std::strtod(cell.c_str(), &end);
  return !cell.empty() && *end == '\0' && parsed == d;
}

}  // namespace

bool from_other_build(const Record& record) {
  return record.text("git_commit") != git_commit() ||
         record.text("ldmbench_version") != ldmbench_version();
}

std::string schema_problem(const Record& record, const std::vector<ColumnSpec>& columns, bool other_build) {
  for (const auto& [key, value] : record.fields()) {
    const ColumnSpec* spec = find_column_in(columns, key);
    if (!spec && other_build) continue;
    if (!spec)
      return "column '" + key + "' is not in the record schema (`ldmbench columns` lists them)";
    if ((key == "config_id" || key == "status") && !std::holds_alternative<std::string>(value))
      return "column '" + key + "' is not text";
    if (!spec->unit.empty() && !std::holds_alternative<std::monostate>(value) &&
        !std::holds_alternative<int64_t>(value) && !std::holds_alternative<double>(value))
      return "column '" + key + "' (" + spec->unit + ") holds " + format_csv_value(value) +
             ", not a number";
  }
  if (record.text("config_id").empty()) return "no config_id";
  const std::string status = record.text("status");
  if (std::find(std::begin(kStatuses), std::end(kStatuses), status) == std::end(kStatuses))
    return "status " + clipped(status) + " is none of ok, lossy, invalid, failed";
  return "";
}

void check_records_schema(const std::vector<Record>& records, const std::vector<ColumnSpec>& columns,
                          const std::string& where) {
  for (size_t i = 0; i < records.size(); ++i)
    if (const std::string problem = schema_problem(records[i], columns, from_other_build(records[i])); !problem.empty())
      throw UserError(where + ": record " + std::to_string(i + 1) +
                      (records[i].text("config_id").empty() ? "" : " (" + records[i].text("config_id") + ")") +
                      ": " + problem);
}

namespace {
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}
}  // namespace

void check_journal_records(const JournalContents& contents, const std::vector<ColumnSpec>& columns,
                           const std::vector<std::string>& always_written, const std::string& journal) {
  for (size_t i = 0; i < contents.records.size(); ++i) {
    const Record& r = contents.records[i];
    const std::string id = r.text("config_id");
    const std::string where = journal + ":" +
                              (i < contents.record_lines.size() ? std::to_string(contents.record_lines[i]) : "?") +
                              (id.empty() ? "" : " (" + id + ")");
    const std::vector<ColumnSpec>* schema = &columns;
    const std::vector<std::string>* always = &always_written;
    std::vector<ColumnSpec> declared;
    std::vector<std::string> declared_always;
    if (from_other_build(r)) {
      const Record* run = nullptr;
      for (auto it = contents.runs.rbegin(); it != contents.runs.rend() && !run; ++it)
        if (it->text("git_commit") == r.text("git_commit") &&
            it->text("ldmbench_version") == r.text("ldmbench_version") &&
            !it->text("schema_columns").empty())
          run = &*it;
      if (!run)
        throw UserError(where + ": written by ldmbench " + clipped(r.text("ldmbench_version")) + " (commit " +
                        clipped(r.text("git_commit")) +
                        "), whose run entry declares no schema (schema_columns) to check its columns "
                        "against: merge it with the build that wrote it");
      for (const auto& name : words(run->text("schema_columns"))) declared.push_back({"", name, "", ""});
      declared_always = words(run->text("schema_always_written"));
      schema = &declared;
      always = &declared_always;
    }
    if (const std::string problem = schema_problem(r, *schema, false); !problem.empty())
      throw UserError(where + ": " + problem +
                      (schema == &declared ? " (the schema its build's run entry declares)" : ""));
    for (const auto& name : *always)
      if (!r.get(name))
        throw UserError(where + ": column '" + name + "' is missing, which every record of its build carries");
  }
}

Record record_from_json(const nlohmann::json& object, const std::string& where) {
  if (!object.is_object()) throw UserError(where + ": a record is not a JSON object");
  Record r;
  for (const auto& [key, v] : object.items()) {
    if (v.is_null()) r.put(key, std::monostate{});
    else if (v.is_boolean()) r.put(key, v.get<bool>());
    else if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)) r.put(key, v.get<double>());
    else if (v.is_number_integer()) r.put(key, v.get<int64_t>());
    else if (v.is_number_float()) r.put(key, v.get<double>());
    else if (v.is_string()) r.put(key, v.get<std::string>());
    else throw UserError(where + ": column '" + key + "' holds " + std::string(v.type_name()) + ", not a value");
  }
  return r;
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, any = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (c == '"') quoted = false;
      else field += c;
      continue;
    }
    any = true;
    if (c == '"') quoted = true;
    else if (c == ',') row.push_back(std::move(field)), field.clear();
    else if (c == '\n') {
      row.push_back(std::move(field));
      field.clear();
      rows.push_back(std::move(row));
      row.clear();
      any = false;
    } else if (c != '\r') field += c;
  }
  if (any || !field.empty()) {
    row.push_back(std::move(field));
    rows.push_back(std::move(row));
  }
  return rows;
}

bool check_tables_match_journal(const std::string& run_dir) {
  const fs::path dir(run_dir.empty() ? "." : run_dir);
  const fs::path journal_path = dir / kJournalFile;
  std::error_code error;
  if (!fs::is_regular_file(journal_path, error)) return false;
  const JournalContents journal = read_journal(journal_path.string());
  const fs::path csv_path = dir / "records.csv", json_path = dir / "records.json";
  const bool has_csv = fs::exists(csv_path, error), has_json = fs::exists(json_path, error);
  const std::string csv = has_csv ? read_whole(csv_path) : "", json = has_json ? read_whole(json_path) : "";
  check_tables_against_records(latest_per_configuration(journal.records), journal_path.string(),
                               has_csv ? &csv : nullptr, csv_path.string(), has_json ? &json : nullptr,
                               json_path.string());
  return true;
}

void check_tables_against_records(const std::vector<Record>& records, const std::string& journal_name,
                                  const std::string* csv_text, const std::string& csv_name,
                                  const std::string* json_text, const std::string& json_name) {
  // records.csv: the text the journal gives; else every cell must still read as the
  // journal's value (another build may format numbers differently), or the first
  // differing cell is named.
  if (csv_text) {
    const std::string& actual = *csv_text;
    const std::string expected = records_to_csv(records);
    if (actual != expected) {
      const auto have = parse_csv(actual), want = parse_csv(expected);
      std::string what;
      if (have.empty() || want.empty() || have[0] != want[0]) {
        what = "its columns differ from the journal's";
        const size_t columns = std::max(have.empty() ? 0 : have[0].size(), want.empty() ? 0 : want[0].size());
        for (size_t c = 0; c < columns; ++c) {
          const std::string a = !have.empty() && c < have[0].size() ? have[0][c] : "(none)";
          const std::string b = !want.empty() && c < want[0].size() ? want[0][c] : "(none)";
          if (a != b) {
            what += ": column " + std::to_string(c + 1) + " is " + clipped(a) + " in the table, " +
                    clipped(b) + " in the journal";
            break;
          }
        }
      } else if (have.size() != want.size()) {
        what = "it holds " + std::to_string(have.size() - 1) + " records, the journal " +
               std::to_string(want.size() - 1);
      } else {
        const std::vector<std::string>& header = want[0];
        for (size_t r = 1; r < have.size() && what.empty(); ++r)
          for (size_t c = 0; c < header.size() && what.empty(); ++c) {
            const std::string cell = c < have[r].size() ? have[r][c] : "";
            const RecordValue* value = records[r - 1].get(header[c]);
            if (have[r].size() != header.size() || !cell_reads_as(cell, value))
              what = "configuration " + records[r - 1].text("config_id") + ", column " + header[c] +
                     ": " + clipped(cell) + " in the table, " +
                     clipped(value ? format_csv_value(*value) : "") + " in the journal";
          }
      }
      if (!what.empty())
        throw UserError(csv_name + " disagrees with " + journal_name + ": " + what + kTableHint);
    }
  }

  // records.json: its "records" exactly the journal's (its "run" object is the latest run's).
  if (json_text) {
    const nlohmann::json actual = parse_json_strictly(*json_text, json_name);
    const nlohmann::json expected = nlohmann::json::parse(records_to_json(records, Record()));
    if (!actual.is_object() || !actual.contains("records") || !actual["records"].is_array())
      throw UserError(json_name + ": not an ldmbench records.json (no \"records\" array)");
    const nlohmann::json& have = actual["records"];
    const nlohmann::json& want = expected["records"];
    std::string what;
    if (have.size() != want.size()) {
      what = "it holds " + std::to_string(have.size()) + " records, the journal " + std::to_string(want.size());
    } else {
      for (size_t i = 0; i < have.size() && what.empty(); ++i) {
        if (have[i] == want[i]) continue;
        const std::string id = want[i].value("config_id", "?");
        for (const auto& [key, value] : want[i].items())
          if (!have[i].is_object() || !have[i].contains(key) || have[i][key] != value) {
            what = "configuration " + id + ", column " + key + ": " +
                   (have[i].is_object() && have[i].contains(key) ? clipped(have[i][key].dump()) : "(none)") +
                   " in the table, " + clipped(value.dump()) + " in the journal";
            break;
          }
        if (what.empty() && have[i].is_object())
          for (const auto& [key, value] : have[i].items())
            if (!want[i].contains(key)) {
              what = "configuration " + id + ": column " + key + " is not in the journal";
              break;
            }
        if (what.empty()) what = "record " + std::to_string(i + 1) + " differs";
      }
    }
    if (!what.empty())
      throw UserError(json_name + " disagrees with " + journal_name + ": " + what + kTableHint);
  }
}

}  // namespace ldm
