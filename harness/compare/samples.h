#pragma once
// The per-frame times of a configuration, as `ldmbench run` writes them next to its records
// (samples/<config_id>-frames.csv, named by the record's frame_samples_csv column; see
// frame_samples_csv() in harness/app/measurement.h): "frame,subpass,ms", one row per
// sub-pass of each measured frame. What `ldmbench compare` tests a time change on.
#include <map>
#include <string>
#include <vector>

namespace ldm {

// Sub-pass -> its milliseconds, frame order.
using FrameSamples = std::map<std::string, std::vector<double>>;

// Throws UserError naming `where` and the line for anything but that CSV.
FrameSamples parse_frame_samples(const std::string& csv, const std::string& where);
// Reads and parses the file; throws UserError naming it when it cannot be read.
FrameSamples load_frame_samples(const std::string& path);

}  // namespace ldm
