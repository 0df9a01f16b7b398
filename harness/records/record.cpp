#include "harness/records/record.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/util/files.h"

namespace ldm {

void Record::put(const std::string& key, RecordValue value) {
  if (declared_ && !declared_(key))
    throw std::logic_error("record column '" + key +
                           "' is not declared: declare it with its unit and description "
                           "(harness/records/harness_columns.h, or the pass's columns())");
  for (auto& [k, v] : fields_) {
    if (k == key) {
      v = std::move(value);
      return;
    }
  }
  fields_.emplace_back(key, std::move(value));
}

void Record::erase(const std::string& key) {
  fields_.erase(std::remove_if(fields_.begin(), fields_.end(),
                               [&](const auto& field) { return field.first == key; }),
                fields_.end());
}

const RecordValue* Record::get(const std::string& key) const {
  for (const auto& [k, v] : fields_)
    if (k == key) return &v;
  return nullptr;
}

std::optional<double> Record::number(const std::string& key) const {
  const RecordValue* value = get(key);
  if (!value) return std::nullopt;
  if (const auto* i = std::get_if<int64_t>(value)) return double(*i);
  if (const auto* d = std::get_if<double>(value)) return *d;
  return std::nullopt;
}

std::optional<int64_t> Record::integer(const std::string& key) const {
  const RecordValue* value = get(key);
  if (const auto* i = value ? std::get_if<int64_t>(value) : nullptr) return *i;
  return std::nullopt;
}

std::string Record::text(const std::string& key) const {
  const RecordValue* value = get(key);
  const auto* s = value ? std::get_if<std::string>(value) : nullptr;
  return s ? *s : std::string();
}

bool Record::flag(const std::string& key) const {
  const RecordValue* value = get(key);
  const auto* b = value ? std::get_if<bool>(value) : nullptr;
  return b && *b;
}

void Record::put_all(const Record& other) {
  for (const auto& [key, value] : other.fields()) put(key, value);
}

void append_note(Record& record, const Column& column, const std::string& note) {
  if (note.empty()) return;
  const std::string before = record.text(column);
  record.set(column, before.empty() ? note : before + "; " + note);
}

namespace {

std::string format_double(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[40];
  // The shortest of %.Ng that reads back to the same double.
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  return buffer;
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

nlohmann::json to_json(const RecordValue& value) {
  struct Visitor {
    nlohmann::json operator()(std::monostate) const { return nullptr; }
    nlohmann::json operator()(bool b) const { return b; }
    nlohmann::json operator()(int64_t i) const { return i; }
    nlohmann::json operator()(double d) const {
      if (!std::isfinite(d)) return nullptr;
      return d;
    }
    nlohmann::json operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace

std::string format_csv_value(const RecordValue& value) {
  struct Visitor {
    std::string operator()(std::monostate) const { return ""; }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return format_double(d); }
    std::string operator()(const std::string& s) const { return csv_quote(s); }
  };
  return std::visit(Visitor{}, value);
}

std::string records_to_csv(const std::vector<Record>& records) {
  std::vector<std::string> columns;
  for (const auto& r : records)
    for (const auto& [key, value] : r.fields())
      if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
  std::string out;
  for (size_t i = 0; i < columns.size(); ++i) {
    if (i) out += ',';
    out += csv_quote(columns[i]);
  }
  out += "\n";
  for (const auto& r : records) {
    for (size_t i = 0; i < columns.size(); ++i) {
      if (i) out += ",";
      if (const RecordValue* v = r.get(columns[i])) out += format_csv_value(*v);
    }
    out += "\n";
  }
  return out;
}

std::string records_to_json(const std::vector<Record>& records, const Record& run_metadata) {
  nlohmann::ordered_json root;
  nlohmann::ordered_json metadata = nlohmann::ordered_json::object();
  for (const auto& [key, value] : run_metadata.fields()) metadata[key] = to_json(value);
  root["run"] = metadata;
  root["records"] = nlohmann::ordered_json::array();
  for (const auto& r : records) {
    nlohmann::ordered_json row = nlohmann::ordered_json::object();
    for (const auto& [key, value] : r.fields()) row[key] = to_json(value);
    root["records"].push_back(row);
  }
  return root.dump(2) + "\n";
}

void write_records(const std::string& csv_path, const std::string& json_path,
                   const std::vector<Record>& records, const Record& run_metadata) {
  write_text_atomically(csv_path, records_to_csv(records));
  write_text_atomically(json_path, records_to_json(records, run_metadata));
}

}  // namespace ldm
