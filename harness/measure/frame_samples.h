#pragma once
// The per-frame times of a configuration, as `ldmbench run` writes them next to its records
// (samples/<config_id>-frames.csv, named by the record's frame_samples_csv column; see
// frame_samples_csv() in harness/measuring/measurement.h): "repetition,frame,subpass,ms", one row
// per sub-pass of each measured frame of each repetition. Files of older runs,
// "frame,subpass,ms", are one repetition. What `ldmbench compare` tests a time change on,
// and what the repetitions of a configuration are combined from.
#include <string>
#include <vector>

#include "harness/measure/timing_stats.h"

namespace ldm {

// One TimingSeries per repetition, in repetition order (numbered in turn from the first,
// 0 in a configuration's file, j in the file of its repetition j alone; frames in order
// within each). Throws UserError naming `where` and the line for anything else.
std::vector<TimingSeries> parse_frame_samples(const std::string& csv, const std::string& where);
// Reads and parses the file; throws UserError naming it when it cannot be read.
std::vector<TimingSeries> load_frame_samples(const std::string& path);

}  // namespace ldm
