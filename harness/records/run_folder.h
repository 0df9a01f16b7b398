#pragma once
// What `ldmbench run --out DIR` does with what DIR already holds, decided before any GPU
// work so that a refusal writes nothing:
//   - DIR missing or empty: a fresh run.
//   - DIR/records.jsonl written by the same sweep (same command without --out/--overwrite,
//     same scene contents, same ldmbench build): resume; finished configurations are kept
//     and skipped, the rest are measured.
//   - anything else (another sweep's results, files that are not a run's): refused, unless
//     --overwrite, which removes the run's files (records.*, images/) and starts afresh.
#include <string>

#include "harness/records/journal.h"

namespace ldm {

enum class RunFolderState { Fresh, Resume, Replace };

struct RunFolderPlan {
  RunFolderState state = RunFolderState::Fresh;
  JournalContents previous;  // Resume: what the journal holds
};

inline constexpr const char* kJournalFile = "records.jsonl";

// Throws UserError (naming DIR and what it holds) when DIR cannot be used.
RunFolderPlan plan_run_folder(const std::string& out_dir, const std::string& sweep_key,
                              bool overwrite);
// Carries out the plan: removes a replaced run's files, creates DIR/images, and removes
// temporary files a killed run left behind (write_file_atomically's ".<name>.tmp<pid>...").
void prepare_run_folder(const std::string& out_dir, const RunFolderPlan& plan);
// Removes the images of one configuration, named "<image_stem>[-kind].<ext>" with the stem
// "<config id>-<pass>" (an abandoned configuration leaves no orphans).
void remove_configuration_images(const std::string& images_dir, const std::string& image_stem);

}  // namespace ldm
