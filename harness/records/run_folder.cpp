#include "harness/records/run_folder.h"

#include <filesystem>
#include <regex>

#include "harness/records/run_lock.h"
#include "harness/util/error.h"
#include "harness/util/files.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

const RecordValue* last_sweep_key(const JournalContents& journal) {
  return journal.runs.empty() ? nullptr : journal.runs.back().get("sweep_key");
}

// Files write_file_atomically leaves when the process is killed mid-write.
bool is_leftover_temporary(const fs::path& path) {
  static const std::regex pattern(R"(^\..+\.tmp[0-9]+(\.[A-Za-z0-9]+)?$)");
  return std::regex_match(path.filename().string(), pattern);
}

void remove_temporaries(const fs::path& dir) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) return;
  for (const auto& entry : fs::directory_iterator(dir, error))
    if (entry.is_regular_file(error) && is_leftover_temporary(entry.path()))
      fs::remove(entry.path(), error);
}

}  // namespace

RunFolderPlan plan_run_folder(const std::string& out_dir, const std::string& sweep_key,
                              bool overwrite) {
  RunFolderPlan plan;
  std::error_code error;
  const fs::path dir(out_dir);
  if (!fs::exists(dir, error)) return plan;
  if (!fs::is_directory(dir, error))
    throw UserError("--out: '" + out_dir + "' exists and is not a folder");
  if (folder_is_empty_but_lock(out_dir)) return plan;  // (the lock of this very command)
  if (overwrite) {
    plan.state = RunFolderState::Replace;
    return plan;
  }
  const fs::path journal = dir / kJournalFile;
  if (!fs::exists(journal, error))
    throw UserError("--out: '" + out_dir + "' is not empty and holds no " + kJournalFile +
                    " of a run to resume; choose another folder, or --overwrite to replace its "
                    "records and images");
  plan.previous = read_journal(journal.string());
  // A journal that holds nothing (its first append failed: a full disk) is an empty folder's.
  if (plan.previous.runs.empty() && plan.previous.records.empty() && plan.previous.repetitions.empty())
    return plan;
  const RecordValue* key = last_sweep_key(plan.previous);
  if (!key || *key != RecordValue(sweep_key))
    throw UserError("--out: '" + out_dir + "' holds the records of a different sweep (another "
                    "command, scene contents or ldmbench build); rerun that command to resume "
                    "it, choose another folder, or --overwrite to replace its records and images");
  plan.state = RunFolderState::Resume;
  return plan;
}

void prepare_run_folder(const std::string& out_dir, const RunFolderPlan& plan) {
  const fs::path dir(out_dir);
  std::error_code error;
  if (plan.state == RunFolderState::Replace) {
    for (const char* name : {kJournalFile, "records.csv", "records.json"}) fs::remove(dir / name, error);
    fs::remove_all(dir / "images", error);
    fs::remove_all(dir / "samples", error);
  }
  fs::create_directories(dir / "images", error);
  if (error) throw_file_error("--out: cannot create '" + (dir / "images").string() + "'", error.value());
  remove_temporaries(dir);
  remove_temporaries(dir / "images");
  remove_temporaries(dir / "samples");
}

void remove_configuration_images(const std::string& images_dir, const std::string& image_stem) {
  // "<stem>.exr", "<stem>-ssim.png", "<stem>-diff.exr", ... and their temporaries; not the
  // images of a configuration whose id merely starts with this one's ("...-r32-att").
  static const std::regex suffix(R"(^(-[a-z]+)?\.[a-z]+$)");
  std::error_code error;
  if (!fs::is_directory(images_dir, error)) return;
  for (const auto& entry : fs::directory_iterator(images_dir, error)) {
    std::string name = entry.path().filename().string();
    if (is_leftover_temporary(entry.path())) {  // ".<stem><suffix>.tmp<pid>.<ext>"
      name = name.substr(1);
      name = name.substr(0, name.rfind(".tmp")) + entry.path().extension().string();
    }
    if (name.rfind(image_stem, 0) == 0 &&
        std::regex_match(name.substr(image_stem.size()), suffix))
      fs::remove(entry.path(), error);
  }
}

}  // namespace ldm
