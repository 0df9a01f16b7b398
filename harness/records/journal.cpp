#include "harness/records/journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/util/error.h"
#include "harness/util/json_input.h"

namespace ldm {
namespace {

using ordered_json = nlohmann::ordered_json;

ordered_json encode_value(const RecordValue& value) {
  struct Visitor {
    ordered_json operator()(std::monostate) const { return nullptr; }
    ordered_json operator()(bool b) const { return b; }
    ordered_json operator()(int64_t i) const { return i; }
    ordered_json operator()(double d) const {
      if (std::isnan(d)) return {{"nonfinite", "nan"}};
      if (std::isinf(d)) return {{"nonfinite", d > 0 ? "inf" : "-inf"}};
      return d;
    }
    ordered_json operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{}, value);
}

RecordValue decode_value(const ordered_json& v, const std::string& where) {
  if (v.is_null()) return std::monostate{};
  if (v.is_boolean()) return v.get<bool>();
  if (v.is_number_integer()) return v.get<int64_t>();
  if (v.is_number_float()) return v.get<double>();
  if (v.is_string()) return v.get<std::string>();
  if (v.is_object() && v.size() == 1 && v.contains("nonfinite") && v["nonfinite"].is_string()) {
    const std::string text = v["nonfinite"];
    if (text == "nan") return std::nan("");
    if (text == "inf") return INFINITY;
    if (text == "-inf") return -INFINITY;
  }
  throw UserError(where + ": not a record value");
}

}  // namespace

std::string journal_line(const char* kind, const Record& fields) {
  ordered_json object = ordered_json::object();
  for (const auto& [key, value] : fields.fields()) object[key] = encode_value(value);
  ordered_json line;
  line[kind] = object;
  // dump() escapes newlines inside strings: one entry is always one line.
  return line.dump() + "\n";
}

JournalContents read_journal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw_io_error("cannot read '" + path + "'", errno);
  return parse_journal(buffer.str(), path);
}

JournalContents parse_journal(const std::string& text, const std::string& path) {
  JournalContents contents;
  size_t begin = 0, line_number = 0;
  while (begin < text.size()) {
    const size_t end = text.find('\n', begin);
    if (end == std::string::npos) {  // no newline: the write was cut short
      contents.torn_bytes = text.size() - begin;
      break;
    }
    ++line_number;
    const std::string where = path + ":" + std::to_string(line_number);
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ordered_json entry;
    try {
      // Depth bounded and duplicate keys refused (util/json_input.h): a journal line is flat.
      entry = parse_ordered_json_strictly(line, where);
    } catch (const UserError& e) {
      throw UserError(std::string(e.what()) + " (not a journal line)");
    }
    const bool one = entry.is_object() && entry.size() == 1;
    const std::string kind = one ? entry.begin().key() : "";
    if (!(kind == "run" || kind == "record" || kind == "repetition") || !entry.begin().value().is_object())
      throw UserError(where + ": not a journal line (expected {\"run\": {...}}, {\"record\": {...}} "
                      "or {\"repetition\": {...}})");
    Record fields;
    for (const auto& [key, value] : entry.begin().value().items())
      fields.put(key, decode_value(value, where + ": " + key));
    // Every reader finds a record's configuration by its id (and its outcome by its status).
    if (kind != "run") {
      const RecordValue* id = fields.get("config_id");
      if (!id || !std::holds_alternative<std::string>(*id) || std::get<std::string>(*id).empty())
        throw UserError(where + ": a " + kind + " without a config_id (text)");
      const RecordValue* status = fields.get("status");
      if (status && !std::holds_alternative<std::string>(*status))
        throw UserError(where + ": " + std::get<std::string>(*id) + ": status is not text");
    }
    if (kind == "record") contents.record_lines.push_back(line_number);
    if (kind == "repetition") contents.repetition_lines.push_back(line_number);
    (kind == "run" ? contents.runs : kind == "record" ? contents.records : contents.repetitions)
        .push_back(std::move(fields));
  }
  return contents;
}

std::vector<Record> latest_per_configuration(const std::vector<Record>& records) {
  std::vector<Record> out;
  std::map<std::string, size_t> index;
  for (const Record& r : records) {
    const RecordValue* id = r.get("config_id");
    const std::string key = id && std::holds_alternative<std::string>(*id) ? std::get<std::string>(*id) : "";
    const auto [it, fresh] = index.emplace(key, out.size());
    if (fresh)
      out.push_back(r);
    else
      out[it->second] = r;
  }
  return out;
}

RecordJournal::RecordJournal(const std::string& path) : path_(path) {
  const JournalContents existing = read_journal(path);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw_io_error("cannot open '" + path + "' for appending", errno);
  if (existing.torn_bytes > 0) {
    const off_t size = ::lseek(fd_, 0, SEEK_END);
    if (size < 0 || ::ftruncate(fd_, size - off_t(existing.torn_bytes)) != 0) {
      const int error = errno;
      ::close(fd_);
      fd_ = -1;
      throw_io_error("cannot cut the torn last line off '" + path + "'", error);
    }
  }
}

RecordJournal::~RecordJournal() {
  if (fd_ >= 0) ::close(fd_);
}

off_t RecordJournal::size() const {
  struct stat info {};
  if (::fstat(fd_, &info) != 0) throw_io_error("cannot examine '" + path_ + "'", errno);
  return info.st_size;
}

void RecordJournal::truncate(off_t size) {
  if (::ftruncate(fd_, size) != 0) throw_io_error("cannot cut '" + path_ + "' back", errno);
  if (::fsync(fd_) != 0) throw_io_error("cannot flush '" + path_ + "' to disk (fsync)", errno);
}

void RecordJournal::append(const char* kind, const Record& fields) {
  const std::string line = journal_line(kind, fields);
  const off_t before = size();
  size_t written = 0;
  int error = 0;
  while (written < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + written, line.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : ENOSPC;
      break;
    }
    written += size_t(n);
  }
  // The line is on disk before any table derived from it is replaced.
  const bool fsync_failed = !error && ::fsync(fd_) != 0;
  if (fsync_failed) error = errno;
  if (!error) return;
  // Not appended, or not known to be on disk: the line is taken back whole, so that the
  // journal stays as it was (a torn line would be cut off by the next run anyway).
  try {
    truncate(before);
  } catch (const IoError&) {
  }
  throw_io_error(fsync_failed ? "cannot flush '" + path_ + "' to disk (fsync)" : "cannot append to '" + path_ + "'",
                 error);
}

}  // namespace ldm
