#pragma once
// The time columns of a record, from the summaries of its repetitions' frames
// (harness/measure/timing_stats.h): per sub-pass the median, min, max, standard deviation,
// the kTimeConfidence interval and (with repetitions) the spread between repetitions; the
// protocol that produced them (repetitions, frames, precision target, interval method);
// and the ratios derived from the medians. One writer for a single repetition and for the
// combination of several, so that both records read alike.
#include <cstddef>
#include <string>
#include <vector>

#include "harness/measure/frame_stop_rule.h"
#include "harness/measure/run_to_run_spread.h"
#include "harness/measure/timing_stats.h"
#include "harness/records/record.h"

namespace ldm {

struct TimingOutcome {
  std::vector<TimingSummary> summaries;
  std::vector<size_t> frames_per_repetition;
  bool target_met = true;  // every repetition reached the precision target
  TimePrecision precision;
};

// Sets (or replaces) every time column; `r` must already hold "fragments" for
// fragments_per_second (a pass without a structure has none).
void add_timing_columns(Record& r, const TimingOutcome& timing);

// Widens every sub-pass's interval (<subpass>_ms_ci_low/high) so that it holds another
// run's median, by the run-to-run spread (harness/measure/run_to_run_spread.h:
// widened_log_half_width), and says so: time_interval gains kRunToRunSuffix,
// time_half_width_within_run keeps the frame interval's own half-width,
// time_run_to_run_spread and time_calibration name the spread and where it came from.
// Without a spread (calibration skipped), only time_calibration is set: the intervals stay
// within-run, and the record says that they do.
inline constexpr const char* kRunToRunSuffix = "+run_to_run_spread";
void widen_time_intervals(Record& r, const RunToRunSpread* spread, const std::string& calibration_source,
                          RepetitionProcesses processes);

// verify_share = verify_ms / frames_timed_ms, when the record has both (a structure's builds
// were checked and frames were timed).
void set_verify_share(Record& r);

// The status_detail warning of a repetition that missed the precision target, or "".
std::string time_target_warning(const TimingOutcome& timing);

// A time with its interval, to the digits the interval supports: the median rounded where
// the interval's half-width has its first significant digit (at least 2 significant
// digits), then the relative half-width: "12.3 ±3.1%". Without a usable interval, the
// median to 4 significant digits.
std::string format_time_with_interval(double median, double low, double high);

// The median rounded to the digits its interval supports (no ± part).
std::string format_supported_digits(double median, double low, double high);

}  // namespace ldm
