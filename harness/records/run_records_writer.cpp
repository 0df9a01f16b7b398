#include "harness/records/run_records_writer.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <utility>

#include "harness/records/run_folder.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

std::string config_id_of(const Record& r) {
  const RecordValue* id = r.get("config_id");
  return id ? std::get<std::string>(*id) : std::string();
}

}  // namespace

RunRecordsWriter::RunRecordsWriter(const std::string& out_dir, std::vector<Record> records,
                                   std::set<std::string> finished, std::function<std::string()> now)
    : csv_path_((std::filesystem::path(out_dir) / "records.csv").string()),
      json_path_((std::filesystem::path(out_dir) / "records.json").string()),
      journal_((std::filesystem::path(out_dir) / kJournalFile).string()),
      records_(std::move(records)),
      finished_(std::move(finished)),
      now_(std::move(now)) {}

void RunRecordsWriter::start_run(const Record& run) {
  run_ = run;
  journal_.append_run(run_);
}

void RunRecordsWriter::write_tables() { write_records(csv_path_, json_path_, records_, run_); }

void RunRecordsWriter::write_tables_if_empty() {
  try {
    if (records_.empty()) write_tables();
  } catch (const IoError&) {
    drop_tables();
    throw;
  }
}

void RunRecordsWriter::drop_tables() {
  std::error_code ignored;
  std::filesystem::remove(csv_path_, ignored);
  std::filesystem::remove(json_path_, ignored);
}

bool RunRecordsWriter::journal_holds(off_t before, off_t length) {
  off_t now = before;
  try {
    now = journal_.size();
  } catch (const IoError&) {
  }
  return now == before + length;
}

void RunRecordsWriter::finish(const Record& record) {
  const std::string id = config_id_of(record);
  const off_t before = journal_.size();
  const off_t length = off_t(journal_line("record", record).size());
  const auto same = std::find_if(records_.begin(), records_.end(),
                                 [&](const Record& r) { return config_id_of(r) == id; });
  const size_t index = size_t(same - records_.begin());
  const bool redone = same != records_.end();
  std::optional<Record> replaced;  // the (failed) record this one takes the place of
  auto apply = [&] {
    if (redone) {
      replaced = records_[index];
      records_[index] = record;
    } else {
      records_.push_back(record);
    }
  };
  bool appended = false;
  try {
    journal_.append_record(record);  // on failure it takes its line back itself
    appended = true;
    apply();
    run_.set("finished", now_());
    write_tables();
  } catch (const IoError&) {
    if (appended) {
      try {
        journal_.truncate(before);
      } catch (const IoError&) {
      }
    }
    if (journal_holds(before, length)) {
      if (!appended) apply();
      finished_.insert(id);
      kept_in_journal_ = true;
      drop_tables();  // they lag the journal now; the next run writes them from it
      throw;
    }
    if (appended) {
      if (redone)
        records_[index] = *replaced;
      else
        records_.pop_back();
      try {
        write_tables();
      } catch (const IoError&) {
        drop_tables();  // the disk refuses even that (one table may be a record ahead)
      }
    }
    throw;
  }
  finished_.insert(id);
}

void RunRecordsWriter::append_repetition(const Record& repetition) {
  const off_t before = journal_.size();
  const off_t length = off_t(journal_line("repetition", repetition).size());
  try {
    journal_.append_repetition(repetition);
  } catch (const IoError&) {
    kept_in_journal_ = journal_holds(before, length);
    throw;
  }
}

}  // namespace ldm
