#pragma once
// One record per measured configuration: an ordered list of named values, written as a row
// of a tidy CSV file and as an object of a JSON file. Columns are the union of the records'
// keys in first-seen order, so sweeps over different structures (with different sub-passes)
// still share one table.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "harness/records/columns.h"

namespace ldm {

using RecordValue = std::variant<std::monostate, bool, int64_t, double, std::string>;

// The columns a record of measurement may hold: a record made with a check refuses any other
// (Record::set and put throw std::logic_error naming the column, at its first use). The
// schema (harness/settings/record_schema.h) gives the check; records read back, merged or of run
// metadata are made without one.
using ColumnCheck = bool (*)(const std::string& column);

class Record {
 public:
  Record() = default;
  explicit Record(ColumnCheck declared) : declared_(declared) {}

  void put(const std::string& key, RecordValue value);  // replaces an existing key in place
  void set(const std::string& key, bool v) { put(key, v); }
  void set(const std::string& key, int v) { put(key, int64_t(v)); }
  void set(const std::string& key, long v) { put(key, int64_t(v)); }
  void set(const std::string& key, long long v) { put(key, int64_t(v)); }
  void set(const std::string& key, unsigned v) { put(key, int64_t(v)); }
  void set(const std::string& key, unsigned long v) { put(key, int64_t(v)); }
  void set(const std::string& key, unsigned long long v) { put(key, int64_t(v)); }
  void set(const std::string& key, float v) { put(key, double(v)); }
  void set(const std::string& key, double v) { put(key, v); }
  void set(const std::string& key, const std::string& v) { put(key, v); }
  void set(const std::string& key, const char* v) { put(key, std::string(v)); }
  // A declared column (harness/records/harness_columns.h, a pass's columns()): the typed way.
  template <typename T>
  void set(const Column& column, T&& v) {
    set(column.name, std::forward<T>(v));
  }
  const RecordValue* get(const std::string& key) const;
  const RecordValue* get(const Column& column) const { return get(column.name); }
  // Typed reads of one column: a number (an integer or a double), an integer, text or a flag;
  // nullopt, "" or false where the record has no such value of that type.
  std::optional<double> number(const std::string& key) const;
  std::optional<int64_t> integer(const std::string& key) const;
  std::string text(const std::string& key) const;
  bool flag(const std::string& key) const;
  std::optional<double> number(const Column& column) const { return number(column.name); }
  std::optional<int64_t> integer(const Column& column) const { return integer(column.name); }
  std::string text(const Column& column) const { return text(column.name); }
  bool flag(const Column& column) const { return flag(column.name); }
  // Every field of `other`, in its order, each replacing this record's value in place.
  void put_all(const Record& other);
  void erase(const std::string& key);  // no-op when absent
  const std::vector<std::pair<std::string, RecordValue>>& fields() const { return fields_; }
  // Whether the record checks its columns against a schema (made with a ColumnCheck).
  bool checked() const { return declared_ != nullptr; }

 private:
  std::vector<std::pair<std::string, RecordValue>> fields_;
  ColumnCheck declared_ = nullptr;
};

// Appends `note` to a text column's "; "-separated notes (the column made where absent;
// nothing when `note` is empty).
void append_note(Record& record, const Column& column, const std::string& note);

// Formatting shared by the writers: doubles round-trip (%.17g trimmed), NaN and infinities as
// nan / inf / -inf in CSV and as null in JSON (JSON has no such numbers).
std::string format_csv_value(const RecordValue& value);
std::string records_to_csv(const std::vector<Record>& records);
std::string records_to_json(const std::vector<Record>& records, const Record& run_metadata);

// Both files are replaced atomically: readers never see a half-written table.
void write_records(const std::string& csv_path, const std::string& json_path,
                   const std::vector<Record>& records, const Record& run_metadata);

}  // namespace ldm
