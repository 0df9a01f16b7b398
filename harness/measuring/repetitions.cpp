#include "harness/measuring/repetitions.h"

#include <filesystem>
#include <map>
#include <sstream>

#include "harness/measuring/measurement.h"
#include "harness/measuring/timing_columns.h"
#include "harness/measure/frame_samples.h"
#include "harness/records/harness_columns.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

double number_or_zero(const Record& r, const std::string& key) { return r.number(key).value_or(0.0); }

// A flag the repetition may lack (a record of an older build): taken as met.
bool flag_or_true(const Record& r, const std::string& key) { return !r.get(key) || r.flag(key); }

// One repetition's frames, from the samples file its record names.
TimingSeries repetition_frames(const Record& r, const std::string& out_dir) {
  const std::string file = r.text("frame_samples_csv");
  if (file.empty())
    throw UserError("repetition of " + r.text("config_id") + " names no samples file");
  const std::vector<TimingSeries> series =
      load_frame_samples((std::filesystem::path(out_dir) / file).string());
  if (series.size() != 1)
    throw UserError(file + ": expected the frames of one repetition, found " +
                    std::to_string(series.size()));
  return series.front();
}

void add_note(std::vector<std::string>& notes, const std::string& detail) {
  std::stringstream parts(detail);
  for (std::string part; std::getline(parts, part, ';');) {
    const size_t start = part.find_first_not_of(' ');
    if (start == std::string::npos) continue;
    part = part.substr(start);
    if (std::find(notes.begin(), notes.end(), part) == notes.end()) notes.push_back(part);
  }
}

}  // namespace

int record_status_rank(const std::string& status) {
  if (status == "ok") return 0;
  if (status == "lossy") return 1;
  if (status == "invalid") return 2;
  return 3;
}

Record combine_repetitions(const std::vector<Record>& repetitions, const std::string& out_dir,
                           const TimePrecision& precision) {
  if (repetitions.empty()) throw std::invalid_argument("combine_repetitions: no repetition");
  Record r = repetitions.front();
  r.erase("repetition");
  std::vector<TimingSeries> frames;
  TimingOutcome timing;
  timing.precision = precision;
  std::string status = r.text("status");
  std::vector<std::string> notes;
  double wall = 0;
  // The harness's own costs add up over the repetitions, as their frames do.
  std::map<std::string, double> sums;
  constexpr const char* kSummed[] = {"frames_timed_ms", "verify_ms", "verify_warmup_ms",
                                     "verify_full_checks", "verify_sampled_checks",
                                     "verify_sampled_pixels", "baseline_frames"};
  for (size_t j = 0; j < repetitions.size(); ++j) {
    const Record& rep = repetitions[j];
    frames.push_back(repetition_frames(rep, out_dir));
    timing.frames_per_repetition.push_back(frames.back().frames());
    timing.target_met = timing.target_met && flag_or_true(rep, "time_target_met");
    if (record_status_rank(rep.text("status")) > record_status_rank(status)) status = rep.text("status");
    add_note(notes, rep.text("status_detail"));
    wall += number_or_zero(rep, "wall_seconds");
    for (const char* key : kSummed) sums[key] += number_or_zero(rep, key);
    if (j == 0) continue;
    for (const char* key : {"lists_checksum", "fragments"}) {
      const RecordValue* first = repetitions.front().get(key);
      const RecordValue* here = rep.get(key);
      if (first && here && *first != *here) {
        status = record_status_rank(status) < record_status_rank("invalid") ? "invalid" : status;
        add_note(notes, "repetition " + std::to_string(j) + "'s " + key + " differs from repetition 0's");
      }
    }
  }
  timing.summaries = summarize_repetitions(frames);
  add_timing_columns(r, timing);
  std::string detail;
  for (const auto& note : notes) detail += (detail.empty() ? "" : "; ") + note;
  r.set(columns::kStatus, status);
  r.set(columns::kStatusDetail, detail);
  r.set(columns::kWallSeconds, wall);
  for (const char* key : kSummed) {
    if (!r.get(key)) continue;
    const std::string name = key;
    if (name.size() > 3 && name.compare(name.size() - 3, 3, "_ms") == 0) r.set(name, sums[name]);
    else r.set(name, int64_t(sums[name]));
  }
  set_verify_share(r);
  return r;
}

std::string combined_samples_csv(const std::vector<Record>& repetitions, const std::string& out_dir) {
  std::vector<TimingSeries> frames;
  for (const Record& rep : repetitions) frames.push_back(repetition_frames(rep, out_dir));
  return frame_samples_csv(frames);
}

}  // namespace ldm
