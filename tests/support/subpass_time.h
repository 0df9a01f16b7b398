#pragma once
// A sub-pass's time in a hand-made record, under the names add_timing_columns writes
// (harness/measuring/timing_columns.cpp): <subpass>_ms_median and its interval
// <subpass>_ms_ci_low / _ms_ci_high.
#include <string>

#include "harness/records/record.h"

namespace ldm::test {

inline void set_subpass_time(Record& r, const std::string& subpass, double median, double low, double high) {
  r.set(subpass + "_ms_median", median);
  r.set(subpass + "_ms_ci_low", low);
  r.set(subpass + "_ms_ci_high", high);
}

}  // namespace ldm::test
