#pragma once
// records.jsonl: the append-only journal of a run folder, from which records.csv and
// records.json are derived. One JSON object per line, each written with a single write()
// and fsync'd before the tables are touched:
//   {"run": {...}}      the metadata of an invocation that writes to this folder
//   {"record": {...}}   one finished configuration (its record, fields in order)
//   {"repetition": {...}}  one finished repetition of a configuration measured K >= 2
//                       times (harness/measuring/repetitions.h), before its record
// A kill can at worst leave a torn last line; reading drops it (it was never complete) and
// opening for append cuts it off, so every complete line survives any number of kills. An
// append that fails (a full disk: write or fsync) takes its partial line back and throws
// IoError, leaving the journal as it was.
#include <sys/types.h>

#include <cstddef>
#include <string>
#include <vector>

#include "harness/records/record.h"

namespace ldm {

struct JournalContents {
  std::vector<Record> runs;     // in order
  std::vector<Record> records;  // in order
  std::vector<Record> repetitions;  // in order
  // The journal line (1-based) of each record and repetition: what came after what (a
  // failed configuration measured again journals its new repetitions after its record).
  std::vector<size_t> record_lines, repetition_lines;
  size_t torn_bytes = 0;        // length of a torn (incomplete) last line, dropped
};

// Reads a journal; a missing file is empty. Throws UserError naming the file and line for a
// complete line that is not a journal entry (the file is not ours, or was edited).
JournalContents read_journal(const std::string& path);
// The same from the journal's text; `path` names it in messages (the fuzzer's entry point).
JournalContents parse_journal(const std::string& text, const std::string& path);

class RecordJournal {
 public:
  // Opens `path` for appending (creating it), after cutting off a torn last line.
  explicit RecordJournal(const std::string& path);
  ~RecordJournal();
  RecordJournal(const RecordJournal&) = delete;
  RecordJournal& operator=(const RecordJournal&) = delete;

  void append_run(const Record& metadata) { append("run", metadata); }
  void append_record(const Record& record) { append("record", record); }
  void append_repetition(const Record& repetition) { append("repetition", repetition); }

  // The journal's length in bytes, and cutting it back to such a length (fsync'd): what a
  // writer does when what it derives from an appended line (the tables) cannot be written,
  // so that the folder is left as it was before the line. Both throw IoError.
  off_t size() const;
  void truncate(off_t size);

 private:
  void append(const char* kind, const Record& fields);
  std::string path_;
  int fd_ = -1;
};

// One record per configuration (by config_id), in first-seen order: a configuration measured
// again (--redo-failed) appears twice in a journal, and its later record is the one that
// counts, in the earlier one's place.
std::vector<Record> latest_per_configuration(const std::vector<Record>& records);

// A record as one JSON line and back. Doubles keep their type (and NaN/inf, as
// {"nonfinite": "nan"}), so a table derived from the journal equals one written directly.
std::string journal_line(const char* kind, const Record& fields);

}  // namespace ldm
