#pragma once
// Repetitions of a configuration (`--repetitions K`): K independent measurements, each in
// a GL context of its own (a fresh structure, the scene uploaded again), measured round
// robin over a sweep's configurations (round 1 of every configuration, then round 2, ...)
// so that drift and the machine's load spread over all of them. Timing variance lives at
// several levels (Kalibera & Jones 2013): frames in one context share its offset (caches,
// clocks, thread placement, the load of that minute), so only repetitions show it.
//
// Each repetition is journaled as it finishes ({"repetition": record}, its frames in
// samples/<id>-rep<j>-frames.csv), so a killed sweep resumes with the repetitions it has;
// a configuration is done when its K repetitions are, and combine_repetitions() then makes
// its one record.
#include <string>
#include <vector>

#include "harness/measure/frame_stop_rule.h"
#include "harness/records/record.h"

namespace ldm {

// The record of a configuration from its repetitions' records (in repetition order; the
// first holds images and accuracy), reading each one's samples file under `out_dir`:
//   time      every sub-pass summarised over the repetitions (timing_stats.h: the median
//             of their medians, a t interval on their logs, the spread between them);
//   status    the worst of the repetitions' (ok < lossy < invalid < failed), and invalid
//             when a repetition's lists (checksum) or census differ from the first's: the
//             same build in another context must store the same fragments;
//   detail    every repetition's notes, each once;
//   wall      wall_seconds summed.
// The combined frames are not written here: combined_samples_csv() gives them.
Record combine_repetitions(const std::vector<Record>& repetitions, const std::string& out_dir,
                           const TimePrecision& precision);

// The samples CSV of all the repetitions, "repetition,frame,subpass,ms", from their files.
std::string combined_samples_csv(const std::vector<Record>& repetitions, const std::string& out_dir);

// The status order combine_repetitions() uses: 0 ok, 1 lossy, 2 invalid, 3 failed (and
// anything unknown).
int record_status_rank(const std::string& status);

}  // namespace ldm
