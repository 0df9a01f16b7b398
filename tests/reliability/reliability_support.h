#pragma once
// Shared by the reliability suite (issue 19): the smallest sweeps, and the check that a run
// folder is consistent (what every test of locks, full disks and injected faults asks).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harness/image/image.h"
#include "harness/records/record_validation.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm::reliability {

namespace fs = std::filesystem;

// One frame of 16x16 pixels from 8x8 LDMs, no reference: a configuration in well under a second.
inline const std::string kTiny =
    " -R 8 --width 16 --height 16 --frames 1 --warmup 0 --time-target 0 --no-reference ";

inline std::string write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// The journal's entries of one kind ("record", "repetition", "run"), in order; a torn last
// line (a kill, an append cut short) is left out, as readers do.
inline std::vector<nlohmann::json> journal_entries(const fs::path& out, const std::string& kind) {
  std::vector<nlohmann::json> entries;
  const std::string text = test::read_text((out / "records.jsonl").string());
  size_t begin = 0;
  while (begin < text.size()) {
    const size_t end = text.find('\n', begin);
    if (end == std::string::npos) break;
    const auto entry = nlohmann::json::parse(text.substr(begin, end - begin));
    if (entry.contains(kind)) entries.push_back(entry[kind]);
    begin = end + 1;
  }
  return entries;
}

// What a run folder holds, and everything wrong with it.
struct FolderState {
  std::vector<std::string> ids;                 // the recorded configurations, first-seen order
  std::map<std::string, size_t> journaled;      // config_id -> records journaled
  std::vector<std::string> problems;
};

// A run folder is consistent when its journal parses, its tables are what the journal
// gives, every file a journal entry names exists whole (images read back), no file of
// images/ or samples/ is an orphan, and no temporary or lock file is left behind.
inline FolderState inspect_folder(const fs::path& out) {
  FolderState state;
  if (!fs::exists(out)) return state;
  std::vector<nlohmann::json> records, repetitions;
  try {
    records = journal_entries(out, "record");
    repetitions = journal_entries(out, "repetition");
  } catch (const std::exception& e) {
    state.problems.push_back(std::string("journal: ") + e.what());
    return state;
  }
  std::map<std::string, nlohmann::json> latest;
  for (const auto& r : records) {
    const std::string id = r.value("config_id", "");
    if (!latest.count(id)) state.ids.push_back(id);
    latest[id] = r;
    ++state.journaled[id];
  }
  try {
    check_tables_match_journal(out.string());
  } catch (const std::exception& e) {
    state.problems.push_back(e.what());
  }
  std::set<std::string> named;  // stems of every file an entry names
  auto name_files = [&](const nlohmann::json& entry, bool whole) {
    for (const auto& [key, value] : entry.items()) {
      if (!value.is_string()) continue;
      const std::string text = value.get<std::string>();
      const bool file = key == "frame_samples_csv" || key.ends_with("_exr") || key.ends_with("_png");
      if (!file) continue;
      named.insert((out / text).parent_path().string() + "/" + fs::path(text).stem().string());
      if (!whole) continue;
      const fs::path path = out / text;
      if (!fs::is_regular_file(path) || fs::file_size(path) == 0) {
        state.problems.push_back(entry.value("config_id", "?") + ": " + key + " names " + text +
                                 ", which is missing or empty");
      } else if (path.extension() == ".exr" || path.extension() == ".png") {
        try {
          read_image(path.string());
        } catch (const std::exception& e) {
          state.problems.push_back(entry.value("config_id", "?") + ": " + text + " does not read: " + e.what());
        }
      }
    }
  };
  for (const auto& [id, r] : latest) name_files(r, true);
  // Repetitions of unfinished configurations keep their samples files (a resume uses them).
  for (const auto& r : repetitions)
    if (!latest.count(r.value("config_id", ""))) name_files(r, false);
  for (const char* folder : {"images", "samples"}) {
    if (!fs::is_directory(out / folder)) continue;
    for (const auto& entry : fs::directory_iterator(out / folder)) {
      const std::string stem = (out / folder).string() + "/" + entry.path().stem().string();
      if (!named.count(stem)) state.problems.push_back("orphan " + entry.path().string());
    }
  }
  for (const auto& entry : fs::recursive_directory_iterator(out))
    if (entry.path().filename().string().front() == '.')
      state.problems.push_back("left behind: " + entry.path().string());
  return state;
}

inline std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) out += "\n  " + line;
  return out;
}

}  // namespace ldm::reliability
