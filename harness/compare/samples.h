#pragma once
// Per-frame times in a record: `<subpass>_ms_samples` holds every measured frame's
// milliseconds as one text value, "1.2345;1.3012;..." (6 significant digits, frame order),
// compact enough for records.csv and what `ldmbench compare` tests a time change on.
#include <string>
#include <vector>

#include "harness/measure/gpu_timer.h"

namespace ldm {

// The times of `subpass` over `frames`, in order; frames without it are skipped.
std::vector<double> frame_samples(const std::vector<FrameTimes>& frames, const std::string& subpass);
std::string format_samples(const std::vector<double>& samples);
// Throws UserError naming `where` for anything but ';'-separated finite numbers.
std::vector<double> parse_samples(const std::string& text, const std::string& where);

}  // namespace ldm
