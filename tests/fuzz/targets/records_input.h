#pragma once
// What the records fuzzer (fuzz_records.cpp) does with one input, shared with its corpus
// replay in the ordinary build (tests/reliability/records_fuzz_corpus_test.cpp). The input is
// up to three parts separated by the byte 0x1e: a journal (records.jsonl), a records.csv and
// a records.json. The journal must parse or throw UserError; its records are checked
// against the column schema (UserError allowed); the tables this build derives from them
// must agree with them (else std::logic_error: the derivation and the check disagree); the
// given tables, whatever they hold, are judged without a crash; the last part is read as
// `ldmbench compare` reads a records.json. Anything but UserError escaping is a finding.
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/records/journal.h"
#include "harness/records/record_validation.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"

namespace ldm::fuzz {

inline void judge_records_input(const std::string& input) {
  std::vector<std::string> parts;
  for (size_t begin = 0;;) {
    const size_t end = input.find('\x1e', begin);
    parts.push_back(input.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos || parts.size() == 3) break;
    begin = end + 1;
  }
  try {
    const JournalContents journal = parse_journal(parts[0], "fuzz.jsonl");
    const std::vector<Record> records = latest_per_configuration(journal.records);
    try {
      check_records_schema(records, harness_record_columns(), "fuzz.jsonl");
    } catch (const UserError&) {
    }
    const std::string csv = records_to_csv(records);
    const std::string json = records_to_json(records, Record());
    try {
      check_tables_against_records(records, "fuzz.jsonl", &csv, "fuzz.csv", &json, "fuzz.json");
    } catch (const UserError& e) {
      throw std::logic_error(std::string("the tables derived from a journal disagree with it: ") + e.what());
    }
    const std::string* given_csv = parts.size() > 1 ? &parts[1] : nullptr;
    const std::string* given_json = parts.size() > 2 ? &parts[2] : nullptr;
    try {
      check_tables_against_records(records, "fuzz.jsonl", given_csv, "fuzz.csv", given_json, "fuzz.json");
    } catch (const UserError&) {
    }
  } catch (const UserError&) {
  }
  try {
    const nlohmann::json root = parse_json_strictly(parts.back(), "fuzz.json");
    if (root.is_object() && root.contains("records") && root["records"].is_array())
      for (const auto& r : root["records"]) (void)schema_problem(record_from_json(r, "fuzz.json"), harness_record_columns());
  } catch (const UserError&) {
  }
}

}  // namespace ldm::fuzz
