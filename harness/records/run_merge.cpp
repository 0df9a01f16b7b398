#include "harness/records/run_merge.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "harness/records/journal.h"
#include "harness/records/record_validation.h"
#include "harness/records/run_folder.h"
#include "harness/records/run_lock.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

struct Slice {
  std::string dir;
  Record run;  // the last run entry
  std::vector<Record> records;
  size_t shard_index = 0;
};

// "i/n" of a run entry's shard; throws UserError naming the journal for anything else.
std::pair<size_t, size_t> shard_of(const std::string& shard, const std::string& journal) {
  unsigned long index = 0, count = 0;
  char tail = 0;
  if (std::sscanf(shard.c_str(), "%lu/%lu%c", &index, &count, &tail) != 2 || count == 0 || index >= count ||
      shard.find_first_not_of("0123456789/") != std::string::npos)
    throw UserError("merge: " + journal + ": the run's shard '" + shard + "' is not INDEX/COUNT");
  return {index, count};
}

Slice read_slice(const std::string& dir, const MergeOptions& options) {
  const fs::path journal = fs::path(dir) / kJournalFile;
  std::error_code error;
  if (!fs::is_regular_file(journal, error))
    throw UserError("merge: '" + dir + "' holds no " + kJournalFile + " (not a run folder)");
  JournalContents contents = read_journal(journal.string());
  if (contents.runs.empty()) throw UserError("merge: '" + journal.string() + "' has no run entry");
  Slice slice;
  slice.dir = dir;
  slice.run = contents.runs.back();
  // Records merged are records trusted: every column one of the schema's of the build that
  // wrote it (a renamed key would grow a column of its own in the merged tables), and none
  // it always writes missing; each refusal names the journal's line.
  check_journal_records(contents, options.columns, options.always_written, "merge: " + journal.string());
  slice.records = latest_per_configuration(contents.records);
  const std::string shard = slice.run.text("shard");
  if (!shard.empty()) slice.shard_index = shard_of(shard, journal.string()).first;
  return slice;
}

// Files of one folder of a run (images/ or samples/) into the merged run, by hard link
// where the file system allows, else by copy. A file already there (the reference image
// that several shards share, named by its cache key) is kept.
void link_or_copy_folder(const fs::path& from, const fs::path& to) {
  std::error_code error;
  if (!fs::is_directory(from, error)) return;
  fs::create_directories(to, error);
  if (error) throw UserError("merge: cannot create '" + to.string() + "': " + error.message());
  for (const auto& entry : fs::directory_iterator(from)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name[0] == '.') continue;  // a killed write's temporary
    const fs::path target = to / name;
    if (fs::exists(target, error)) continue;
    fs::create_hard_link(entry.path(), target, error);
    if (error) {
      error.clear();
      fs::copy_file(entry.path(), target, error);
      if (error) throw UserError("merge: cannot copy '" + entry.path().string() + "': " + error.message());
    }
  }
}

}  // namespace

MergeResult merge_runs(const std::string& out_dir, const std::vector<std::string>& run_dirs,
                       const MergeOptions& options) {
  if (run_dirs.empty()) throw UserError("merge: no run folder to merge");
  MergeResult result;
  std::vector<Slice> slices;
  for (const auto& dir : run_dirs) {
    if (fs::exists(out_dir) && fs::exists(dir) && fs::equivalent(out_dir, dir))
      throw UserError("merge: OUT '" + out_dir + "' is one of the runs");
    slices.push_back(read_slice(dir, options));
  }

  // One build, one device, one sweep.
  const Slice& first = slices.front();
  for (const Slice& s : slices) {
    for (const char* key : {"ldmbench_version", "git_commit", "device", "sweep_hash"}) {
      std::string a = first.run.text(key), b = s.run.text(key);
      std::string what = key;
      if (std::string(key) == "sweep_hash" && a.empty() && b.empty()) {
        // Folders of `ldmbench run`: the same sweep is the same command but for --out.
        a = first.run.text("sweep_key");
        b = s.run.text("sweep_key");
        what = "sweep (sweep_key)";
      }
      if (a == b) continue;
      const std::string message = "'" + s.dir + "' and '" + first.dir + "' differ in " + what +
                                  ": '" + b + "' vs '" + a + "'";
      if (!options.allow_mismatch)
        throw UserError("merge: " + message + " (--allow-mismatch to merge them anyway)");
      result.warnings.push_back(message);
    }
  }
  std::map<std::string, std::string> owner;  // config_id -> folder
  for (const Slice& s : slices)
    for (const Record& r : s.records) {
      const std::string id = r.text("config_id");
      const auto [it, fresh] = owner.emplace(id, s.dir);
      if (!fresh)
        throw UserError("merge: configuration " + id + " is in both '" + it->second + "' and '" +
                        s.dir + "' (shards of one sweep never share one)");
    }
  // Shards of one sweep: say which are missing (not an error: a partial merge is useful).
  std::set<size_t> seen;
  size_t count = 0;
  for (const Slice& s : slices) {
    const std::string shard = s.run.text("shard");
    if (shard.empty()) continue;
    seen.insert(s.shard_index);
    count = std::max<size_t>(count, shard_of(shard, s.dir).second);
  }
  for (size_t i = 0; i < count; ++i)
    if (!seen.count(i))
      result.warnings.push_back("shard " + std::to_string(i) + "/" + std::to_string(count) + " is not among the runs");

  std::stable_sort(slices.begin(), slices.end(),
                   [](const Slice& a, const Slice& b) { return a.shard_index < b.shard_index; });

  // OUT: fresh, or replaced when asked; the merged folder is not a sweep to resume.
  const std::string merged_key = "merged:" + (first.run.text("sweep_hash").empty()
                                                  ? first.run.text("sweep_key")
                                                  : first.run.text("sweep_hash"));
  std::error_code error;
  // One writer per folder (run_lock.h): OUT is locked before it is looked at.
  std::ostringstream lock_log;
  const RunFolderLock lock(out_dir, options.command, lock_log);
  if (fs::is_directory(out_dir, error) && !folder_is_empty_but_lock(out_dir) && !options.overwrite)
    throw UserError("merge: OUT '" + out_dir + "' is not empty; choose another folder, or "
                    "--overwrite to replace its records and images");
  const RunFolderPlan plan = plan_run_folder(out_dir, "", options.overwrite);
  prepare_run_folder(out_dir, plan);

  Record run;
  run.set("command", options.command);
  run.set("sweep_key", merged_key);
  for (const char* key : {"device", "gl_driver", "gl_version", "egl_platform", "git_commit", "ldmbench_version",
                          "sweep_file", "sweep_hash", "sweep_configurations"})
    if (const RecordValue* v = first.run.get(key)) run.put(key, *v);
  std::string merged_from;
  for (const Slice& s : slices)
    merged_from += (merged_from.empty() ? "" : ";") + s.dir +
                   (s.run.text("shard").empty() ? "" : " (shard " + s.run.text("shard") + ")");
  run.set("merged_from", merged_from);

  std::vector<Record> records;
  for (const Slice& s : slices) {
    link_or_copy_folder(fs::path(s.dir) / "images", fs::path(out_dir) / "images");
    link_or_copy_folder(fs::path(s.dir) / "samples", fs::path(out_dir) / "samples");
    for (const Record& r : s.records) records.push_back(r);
  }
  {
    RecordJournal journal((fs::path(out_dir) / kJournalFile).string());
    journal.append_run(run);
    for (const Record& r : records) journal.append_record(r);
  }
  write_records((fs::path(out_dir) / "records.csv").string(),
                (fs::path(out_dir) / "records.json").string(), records, run);
  result.records = records.size();
  return result;
}

}  // namespace ldm
