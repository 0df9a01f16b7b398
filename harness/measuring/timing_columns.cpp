#include "harness/measuring/timing_columns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "harness/passes/raster_baseline.h"
#include "harness/records/harness_columns.h"
#include "harness/settings/run_setting_table.h"

namespace ldm {
namespace {

double number_or_absent(const Record& r, const std::string& key) {
  const RecordValue* v = r.get(key);
  if (!v) return -1;
  if (const int64_t* i = std::get_if<int64_t>(v)) return double(*i);
  if (const double* d = std::get_if<double>(v)) return *d;
  return -1;
}

std::string joined_counts(const std::vector<size_t>& counts) {
  std::string out;
  for (size_t c : counts) {
    if (!out.empty()) out += ';';
    out += std::to_string(c);
  }
  return out;
}

}  // namespace

void add_timing_columns(Record& r, const TimingOutcome& t) {
  size_t total = 0;
  for (size_t f : t.frames_per_repetition) total += f;
  const size_t repetitions = t.frames_per_repetition.size();
  r.set(columns::kRepetitions, repetitions);
  r.set(columns::kFramesMeasured, total);
  r.set(columns::kFramesPerRepetition, joined_counts(t.frames_per_repetition));
  // The run-wide settings that carry a column (time_target, time_cap_s, time_clock_warmup_s),
  // from their declarations (harness/settings/run_setting_table.cpp).
  for (const RunSetting& setting : run_setting_table())
    if (const auto* field = std::get_if<double TimePrecision::*>(&setting.field); field && setting.column)
      r.set(*setting.column, t.precision.**field);
  if (t.precision.effective_target() != t.precision.target)
    r.set(columns::kTimeTargetEffective, t.precision.effective_target());
  r.set(columns::kTimeTargetMet, t.target_met);
  r.set(columns::kTimeInterval, repetitions > 1 ? kRepetitionInterval : kFrameInterval);
  for (const auto& s : t.summaries) {
    r.set(s.subpass + "_ms_median", s.median);
    r.set(s.subpass + "_ms_min", s.min);
    r.set(s.subpass + "_ms_max", s.max);
    r.set(s.subpass + "_ms_stddev", s.stddev);
    r.set(s.subpass + "_ms_ci_low", s.interval.low);
    r.set(s.subpass + "_ms_ci_high", s.interval.high);
    if (repetitions > 1) r.set(s.subpass + "_ms_rep_spread", s.repetition_spread);
  }
  if (const TimingSummary* frame = find_summary(t.summaries, "frame")) {
    r.set(columns::kTimeIntervalCoverage, frame->interval.coverage);
    r.set(columns::kTimeHalfWidth, relative_half_width(frame->interval, frame->median));
  }
  const TimingSummary* build = find_summary(t.summaries, "build");
  const TimingSummary* raster = find_summary(t.summaries, kRasterBaselineSubpass);
  if (build && raster && raster->median > 0) r.set(columns::kBuildVsRaster, build->median / raster->median);
  const TimingSummary* touch = find_summary(t.summaries, kRasterTouchSubpass);
  if (build && touch && touch->median > 0) r.set(columns::kBuildVsRasterTouch, build->median / touch->median);
  const double fragments = number_or_absent(r, "fragments");
  if (build && build->median > 0 && fragments >= 0)
    r.set(columns::kFragmentsPerSecond, fragments / (build->median * 1e-3));
}

void widen_time_intervals(Record& r, const RunToRunSpread* spread, const std::string& source,
                          RepetitionProcesses processes) {
  if (!r.get("frame_ms_median")) return;  // nothing timed (a failed record)
  r.set(columns::kTimeCalibration, source);
  if (!spread || !std::isfinite(spread->spread)) return;
  const RecordValue* interval_kind = r.get("time_interval");
  const std::string* kind = interval_kind ? std::get_if<std::string>(interval_kind) : nullptr;
  if (kind && kind->find(kRunToRunSuffix) != std::string::npos) return;  // widened already
  const double reps = number_or_absent(r, "repetitions");
  const size_t repetitions = reps >= 1 ? size_t(reps) : 1;
  const double z = normal_quantile(0.5 + kTimeConfidence / 2);
  const std::string suffix = "_ms_ci_low";
  std::vector<std::string> subpasses;
  for (const auto& [key, value] : r.fields())
    if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
      subpasses.push_back(key.substr(0, key.size() - suffix.size()));
  for (const std::string& sub : subpasses) {
    const double median = number_or_absent(r, sub + "_ms_median");
    const double low = number_or_absent(r, sub + "_ms_ci_low"), high = number_or_absent(r, sub + "_ms_ci_high");
    if (!(median > 0) || !(low > 0) || !(high >= median)) continue;  // a 0 ms sub-pass has no spread
    const double within = std::max(std::log(median / low), std::log(high / median));
    const double h = widened_log_half_width(within, spread->spread, repetitions, z, processes);
    r.set(sub + "_ms_ci_low", median * std::exp(-h));
    r.set(sub + "_ms_ci_high", median * std::exp(h));
  }
  if (const RecordValue* half = r.get("time_half_width")) r.put("time_half_width_within_run", *half);
  const double median = number_or_absent(r, "frame_ms_median");
  const double low = number_or_absent(r, "frame_ms_ci_low"), high = number_or_absent(r, "frame_ms_ci_high");
  if (median > 0) r.set(columns::kTimeHalfWidth, relative_half_width(Interval{low, high, kTimeConfidence}, median));
  r.set(columns::kTimeInterval, (kind ? *kind : std::string()) + kRunToRunSuffix);
  r.set(columns::kTimeRunToRunSpread, spread->spread);
}

void set_verify_share(Record& r) {
  const RecordValue* verify = r.get("verify_ms");
  const RecordValue* timed = r.get("frames_timed_ms");
  const double* verify_ms = verify ? std::get_if<double>(verify) : nullptr;
  const double* timed_ms = timed ? std::get_if<double>(timed) : nullptr;
  if (verify_ms && timed_ms && *timed_ms > 0) r.set(columns::kVerifyShare, *verify_ms / *timed_ms);
}

std::string time_target_warning(const TimingOutcome& t) {
  if (t.target_met || t.precision.target <= 0) return "";
  char text[200];
  std::snprintf(text, sizeof text,
                "time target missed: a repetition stopped at its cap (%g s or %d frames) "
                "before the median's %g%% interval was within +-%g%%",
                t.precision.cap_seconds, t.precision.max_frames, 100 * kTimeConfidence,
                100 * t.precision.effective_target());
  return text;
}

std::string format_supported_digits(double median, double low, double high) {
  char buffer[48];
  const double half = std::max(median - low, high - median);
  if (!std::isfinite(median) || !std::isfinite(half) || half <= 0 || median <= 0) {
    std::snprintf(buffer, sizeof buffer, "%.4g", median);
    return buffer;
  }
  // Decimals down to the half-width's first significant digit, and at least 2 significant
  // digits of the median (12.3 ±0.4 -> "12.3"; 123 ±40 -> "120"; 0.0123 ±0.01 -> "0.012").
  // (A hair above each power of ten, so that 0.00999999 from 12.35 - 12.34 counts as 0.01.)
  int decimals = -int(std::floor(std::log10(half) + 1e-9));
  decimals = std::max(decimals, 1 - int(std::floor(std::log10(median) + 1e-9)));
  decimals = std::min(decimals, 9);
  if (decimals >= 0) {
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, median);
  } else {
    const double unit = std::pow(10.0, -decimals);
    std::snprintf(buffer, sizeof buffer, "%.0f", std::round(median / unit) * unit);
  }
  return buffer;
}

std::string format_time_with_interval(double median, double low, double high) {
  const double half = std::max(median - low, high - median);
  if (!std::isfinite(median) || !std::isfinite(half) || median <= 0) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", median);
    return buffer;
  }
  char percent[24];
  const double relative = 100 * half / median;
  std::snprintf(percent, sizeof percent, relative < 10 ? "%.1f" : "%.0f", relative);
  std::string out = format_supported_digits(median, low, high);
  out += " ±";
  out += percent;
  out += '%';
  return out;
}

}  // namespace ldm
