#pragma once
// Records read back by `ldmbench merge`, `compare` and `report` are checked before they are
// trusted (issue 19: a journal record with a renamed key grew a column in the merged
// tables; a tampered records.csv and a truncated records.json were used as they were):
//   - against the column schema (columns.h): every column described, config_id and status
//     text (status one of ok, lossy, invalid, failed), a column with a unit a number;
//   - a run folder's tables (records.csv, records.json) against its journal
//     (records.jsonl), from which they are derived: they must be exactly what the journal
//     gives, or the table was edited, truncated, or lags a killed run.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/records/columns.h"
#include "harness/records/journal.h"
#include "harness/records/record.h"

namespace ldm {

// What a record's columns do wrong against the schema ("" when nothing): "column
// 'st###ture_params' is not in the record schema (`ldmbench columns`)".
// `other_build`: the record was written by another build of ldmbench (its git_commit or
// ldmbench_version differs from this one's), whose schema may have had other columns: an
// unknown column is then no problem (the types of known ones still are).
// `columns`: the schema (harness/settings/record_schema.h record_columns(): the harness's and
// every pass's columns).
std::string schema_problem(const Record& record, const std::vector<ColumnSpec>& columns,
                           bool other_build = false);
// Whether `record` names a build other than this one (git_commit, ldmbench_version).
bool from_other_build(const Record& record);
// Throws UserError "<where>: record <i> (<config_id>): <problem>" for the first problem
// (unknown columns allowed in records of another build).
void check_records_schema(const std::vector<Record>& records, const std::vector<ColumnSpec>& columns,
                          const std::string& where);
// `ldmbench merge`'s check of a journal (issue 35): every record against the schema of the
// build that wrote it, this build's (`columns`, `always_written`) or, for a record of another
// build, the one that build's run entry declares (schema_columns, schema_always_written):
// no column it does not declare, none it always writes missing. Throws UserError
// "<journal>:<line> (<config_id>): column '<name>' ..."; a record of another build whose run
// entry declares no schema is refused too (nothing to check it against).
void check_journal_records(const JournalContents& contents, const std::vector<ColumnSpec>& columns,
                           const std::vector<std::string>& always_written, const std::string& journal);
// A records.json record (an object of values) as a Record; throws UserError naming `where`
// for a value that is an array or an object.
Record record_from_json(const nlohmann::json& object, const std::string& where);

// Throws UserError naming the table, the configuration and the column of the first
// difference between `run_dir`'s records.csv / records.json and what its journal gives
// (the latest record per configuration); nothing when `run_dir` holds no journal.
// Returns whether a journal was found (and the tables checked).
bool check_tables_match_journal(const std::string& run_dir);
// The same on texts: `records` (the journal's latest per configuration, from `journal_name`)
// against a records.csv and a records.json text (either may be null: not there). The
// fuzzer's entry point (tests/fuzz/targets/fuzz_records.cpp).
void check_tables_against_records(const std::vector<Record>& records, const std::string& journal_name,
                                  const std::string* csv_text, const std::string& csv_name,
                                  const std::string* json_text, const std::string& json_name);

// RFC 4180 rows of a CSV text (quoted fields may hold commas, quotes and newlines).
std::vector<std::vector<std::string>> parse_csv(const std::string& text);

}  // namespace ldm
