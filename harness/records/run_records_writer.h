#pragma once
// The records of a run folder kept consistent with its journal (records.jsonl): every
// record and repetition is journaled first (durable), then the tables (records.csv,
// records.json) are rewritten from the records. When a write fails (a full disk), the folder
// is brought back to a consistent state: the journal cut back and the tables rewritten as
// they were, or, when the journal cannot be cut back, the tables removed (a folder with its
// journal and no tables is consistent; the next run into it, or `ldmbench merge`, writes
// them from the journal). The one writer of a run's records: `ldmbench run` journals and
// tabulates through it alone.
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "harness/records/journal.h"
#include "harness/records/record.h"

namespace ldm {

class RunRecordsWriter {
 public:
  // Opens OUT_DIR's journal for appending. `records` are the records already there (one per
  // configuration), `finished` the configurations that count as done; `now` stamps the run
  // entry's "finished" field at each record.
  RunRecordsWriter(const std::string& out_dir, std::vector<Record> records, std::set<std::string> finished,
                   std::function<std::string()> now);

  // Journals the run entry; the tables carry it from then on.
  void start_run(const Record& run);
  // Rewrites the tables from the records (consistent with the journal after any kill).
  void write_tables();
  // At the end of a run that recorded nothing: empty tables (removed when the disk refuses
  // even those; the IoError goes on).
  void write_tables_if_empty();

  // The record of a finished configuration: journaled (durable before the tables change),
  // in the tables (a redone configuration takes its failed record's place). When the tables
  // cannot be written, the journal is cut back and the tables rewritten as they were, so
  // that the folder stays in its state before this record; the IoError goes on.
  void finish(const Record& record);
  // A repetition of an unfinished configuration, journaled only.
  void append_repetition(const Record& repetition);

  // Whether the entry whose append (or the tables after it) failed stayed whole in the
  // journal: the failure could not be taken back (a disk that stays full refuses even the
  // cut). It then counts, like any journaled entry, and its files stay; the tables follow
  // at the next run, which derives them from the journal.
  bool kept_in_journal() const { return kept_in_journal_; }

  const std::vector<Record>& records() const { return records_; }
  bool finished(const std::string& config_id) const { return finished_.count(config_id) != 0; }

 private:
  // Tables that cannot be brought in line with the journal are removed (unlinking frees
  // space, so a full disk allows it).
  void drop_tables();
  bool journal_holds(off_t before, off_t length);

  std::string csv_path_, json_path_;
  RecordJournal journal_;
  std::vector<Record> records_;
  std::set<std::string> finished_;
  std::function<std::string()> now_;
  Record run_;
  bool kept_in_journal_ = false;
};

}  // namespace ldm
