#pragma once
// `ldmbench merge OUT RUN...`: the run folders of a sweep's shards (`ldmbench sweep --shard
// i/n`) joined into one run folder, as if one process had measured them all. Everything is
// checked before OUT is touched:
//   - every RUN holds a journal (records.jsonl); its records (the latest per configuration)
//     and its last run entry are read;
//   - the runs agree on ldmbench_version, git_commit, device and sweep_hash (a folder of
//     `ldmbench run` has no sweep_hash and is compared by its command) — else refused,
//     unless allow_mismatch (then each difference is a warning);
//   - no configuration appears in two runs (always refused: which measurement is right?);
//   - OUT is missing or empty, or `overwrite` (its records, images and samples are removed).
// OUT then gets records.jsonl (one run entry saying what was merged, then every record),
// records.csv, records.json, and every file of the runs' images/ and samples/ (hard links
// where possible, else copies; paths in records stay valid). Runs are ordered by their shard
// index, then as given.
#include <string>
#include <vector>

#include "harness/records/columns.h"
#include "harness/records/record.h"

namespace ldm {

struct MergeOptions {
  bool allow_mismatch = false;
  bool overwrite = false;
  std::string command;  // stored in the merged run entry
  // The schema of this build that every merged record is checked against (the caller's:
  // record_columns() and always_written_columns() of harness/settings/record_schema.h, which
  // stands above the records).
  std::vector<ColumnSpec> columns;
  std::vector<std::string> always_written;
};

struct MergeResult {
  size_t records = 0;
  std::vector<std::string> warnings;  // mismatches allowed, shards missing
};

// Throws UserError naming the folder or configuration at fault.
MergeResult merge_runs(const std::string& out_dir, const std::vector<std::string>& run_dirs,
                       const MergeOptions& options);

}  // namespace ldm
