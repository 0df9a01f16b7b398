#include "harness/compare/run_comparison.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "harness/measure/frame_samples.h"
#include "harness/measure/run_to_run_spread.h"
#include "harness/gl/device_selection.h"
#include "harness/settings/harness_axes.h"
#include "harness/settings/record_schema.h"
#include "harness/records/record_validation.h"
#include "harness/stats/intervals.h"
#include "harness/stats/time_tests.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"
#include "harness/util/text.h"

namespace ldm {
namespace {

using nlohmann::json;

std::string text(const json& record, const char* key) {
  auto it = record.find(key);
  return it != record.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// A numeric column, or -1 where the record lacks it (failed records, runs without references).
double number(const json& record, const std::string& key) {
  auto it = record.find(key);
  return it != record.end() && it->is_number() ? it->get<double>() : -1;
}

double boost_quantile_t(double df, double p) {
  return boost::math::quantile(boost::math::students_t(df), p);
}
double boost_quantile_normal(double p) { return boost::math::quantile(boost::math::normal(), p); }

// The identity axes other than the structure parameters that --ignore-param may leave out,
// named by their record columns: N and R_LDM (n_views, r_ldm), so that a configuration
// measured at two view counts pairs as one (the timing calibration's genuinely slower
// configuration).
std::vector<const HarnessAxis*> ignorable_axes() {
  return {find_harness_axis("views"), find_harness_axis("r_ldm")};
}

// The axis's fragment of the record's config_id ("-n16"), as its declaration makes it from
// the value in its column; "" where the record has none.
std::string axis_fragment(const json& record, const HarnessAxis& axis) {
  const auto it = record.find(axis.spec.column);
  if (it == record.end() || !it->is_number_integer()) return "";
  return axis.id_fragment({{axis.spec.key, std::to_string(it->get<int64_t>())}}, false);
}

// config_id writes each structure parameter as "-key=value" with odd characters as '_'
// (Configuration::id); leaving a parameter (or N, R_LDM) out of the identity removes that part.
std::string identity_of(const json& record, const std::set<std::string>& ignored) {
  std::string id = text(record, "config_id");
  std::vector<std::string> parts;
  for (const HarnessAxis* axis : ignorable_axes())
    if (ignored.count(axis->spec.column)) parts.push_back(axis_fragment(record, *axis));
  std::stringstream params(text(record, "structure_params"));
  for (std::string item; std::getline(params, item, ';');) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || !ignored.count(item.substr(0, eq))) continue;
    std::string part = "-" + item;
    for (char& c : part)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '='))
        c = '_';
    parts.push_back(part);
  }
  for (const std::string& part : parts) {
    if (part.empty()) continue;
    // A whole fragment: "-n16" must not cut "-n160".
    for (size_t at = id.find(part); at != std::string::npos; at = id.find(part, at + 1)) {
      const size_t end = at + part.size();
      if (end == id.size() || id[end] == '-') {
        id.erase(at, part.size());
        break;
      }
    }
  }
  return id;
}

// The structure parameters' keys a record names ("k=4;local=1" -> k, local).
std::set<std::string> parameter_keys(const json& record) {
  std::set<std::string> keys;
  std::stringstream params(text(record, "structure_params"));
  for (std::string item; std::getline(params, item, ';');)
    if (const size_t eq = item.find('='); eq != std::string::npos && eq > 0) keys.insert(item.substr(0, eq));
  return keys;
}

// For each parameter --ignore-param could leave out (the records' structure parameters, N,
// R_LDM), how many of BASE's `missing` records it pairs one to one with NEW's `added`
// records; those that pair any, most first. A pairing that makes two records of either side
// one identity is not counted (compare_runs refuses it).
std::vector<PairingHint> pairing_hints(const std::vector<const json*>& missing,
                                       const std::vector<const json*>& added,
                                       const std::set<std::string>& ignored) {
  std::set<std::string> candidates;
  for (const HarnessAxis* axis : ignorable_axes()) candidates.insert(axis->spec.column);
  for (const auto* side : {&missing, &added})
    for (const json* r : *side)
      for (const std::string& key : parameter_keys(*r)) candidates.insert(key);
  std::vector<PairingHint> hints;
  for (const std::string& param : candidates) {
    if (ignored.count(param)) continue;
    std::set<std::string> without = ignored;
    without.insert(param);
    std::map<std::string, int> in_new, in_base;
    for (const json* r : added) ++in_new[identity_of(*r, without)];
    for (const json* r : missing) ++in_base[identity_of(*r, without)];
    PairingHint hint{param, 0, missing.size()};
    for (const auto& [identity, count] : in_base)
      if (count == 1 && in_new.count(identity) && in_new[identity] == 1) ++hint.paired;
    if (hint.paired) hints.push_back(hint);
  }
  std::stable_sort(hints.begin(), hints.end(),
                   [](const PairingHint& a, const PairingHint& b) { return a.paired > b.paired; });
  return hints;
}

int status_rank(const std::string& status) {
  static const std::map<std::string, int> ranks = {
      {"ok", 0}, {"lossy", 1}, {"invalid", 2}, {"failed", 3}, {"missing", 4}};
  auto it = ranks.find(status);
  return it == ranks.end() ? 3 : it->second;
}

// One side's times of a sub-pass: the medians of its repetitions, its frames, and (one
// repetition) the relative standard error of its median from the frames' interval.
struct SideTimes {
  std::vector<double> medians;
  size_t frames = 0;
  double frame_se = std::numeric_limits<double>::infinity();
  double median = 0;  // of the medians: the record's
};

std::optional<SideTimes> side_times(const std::vector<TimingSeries>& repetitions, const std::string& subpass) {
  SideTimes side;
  for (const TimingSeries& r : repetitions) {
    const std::vector<double>* values = r.find(subpass);
    if (!values || values->empty()) return std::nullopt;
    side.medians.push_back(median_of(*values));
    side.frames += values->size();
    if (repetitions.size() == 1) {
      const Interval interval = median_interval(*values, kTimeConfidence);
      side.frame_se = median_relative_se(side.medians.back(), interval.low, interval.high, interval.coverage);
    }
  }
  if (side.medians.empty()) return std::nullopt;
  side.median = median_of(side.medians);
  return side;
}

// The test of one sub-pass (verdicts come later, once every test's p is Holm-corrected).
TimeChange test_time(const std::string& subpass, const SideTimes& a, const SideTimes& b, bool paired,
                     const CompareThresholds& t, double calibrated_spread) {
  TimeChange c;
  c.subpass = subpass;
  c.base_repetitions = a.medians.size();
  c.new_repetitions = b.medians.size();
  c.base_samples = a.frames;
  c.new_samples = b.frames;
  c.base_median = a.median;
  c.new_median = b.median;
  const auto positive = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return x > 0; });
  };
  if (!positive(a.medians) || !positive(b.medians)) {
    // A sub-pass that (nearly) never runs: no ratio to test.
    c.relative_change = a.median > 0 ? b.median / a.median - 1 : 0;
    c.warning = "a repetition's median is 0 ms: not tested";
    return c;
  }
  TimeTest test;
  const size_t ka = a.medians.size(), kb = b.medians.size();
  if (paired && ka == kb && ka >= 2) {
    test = paired_log_t(a.medians, b.medians);
  } else if (ka >= 2 && kb >= 2) {
    test = welch_log_t(a.medians, b.medians);
  } else {
    // A side of one repetition cannot show its process offset: its frames' standard error
    // plus an assumed spread (or the other side's measured one, if larger).
    double spread = t.process_spread;
    c.spread_source = t.process_spread_given ? "--process-spread" : "default";
    if (!t.process_spread_given && calibrated_spread > 0) {
      spread = calibrated_spread;
      c.spread_source = "calibration";
    }
    for (const SideTimes* other : {&a, &b})
      if (other->medians.size() >= 2 && log_moments(other->medians).stddev > spread) {
        spread = log_moments(other->medians).stddev;
        c.spread_source = "repetitions";
      }
    c.process_spread = spread;
    double variance = 0;
    for (const SideTimes* side : {&a, &b}) {
      if (side->medians.size() >= 2) {
        const double s = log_moments(side->medians).stddev;
        variance += s * s / double(side->medians.size());
      } else {
        variance += side->frame_se * side->frame_se + spread * spread;
      }
    }
    test = log_z_test(std::log(b.median / a.median), std::sqrt(variance));
    char text[200];
    std::snprintf(text, sizeof text,
                  "%s has one repetition: its verdict assumes independent frames plus a "
                  "process-to-process spread of %.3g%% (%s); measure with repetitions "
                  "(see the repetitions line below)",
                  ka < 2 && kb < 2 ? "each run" : ka < 2 ? "BASE" : "NEW", 100 * spread,
                  c.spread_source == "calibration" ? "this machine's calibration, time_run_to_run_spread"
                  : c.spread_source == "--process-spread" ? "--process-spread"
                                                         : "an assumed default: `ldmbench calibrate` measures it");
    c.warning = text;
  }
  c.method = time_test_method_name(test.method);
  c.relative_change = std::expm1(test.log_ratio);
  c.p_value = test.p_value;
  c.se = test.se;
  c.df = test.df;
  return c;
}

// The verdict of a tested change once its corrected p value and MDE are known.
void judge_time(TimeChange& c, const CompareThresholds& t) {
  if (c.p_value < 0) {
    c.verdict = std::fabs(c.relative_change) >= t.min_time_change ? "UNSURE" : "SAME";
    return;
  }
  const double change = std::fabs(std::log1p(c.relative_change));
  const double mde = std::log1p(c.minimum_detectable);
  const double needed = std::max(std::log1p(t.min_time_change), mde);
  if (c.p_adjusted < t.alpha && change >= needed)
    c.verdict = c.relative_change > 0 ? "SLOW" : "FAST";
  else if (change < needed)
    c.verdict = "SAME";
  else
    c.verdict = "UNSURE";
}

// The record's per-frame samples; empty when it names none (failed, or an older run).
std::vector<TimingSeries> samples_of(const RunRecords& run, const json& record) {
  const std::string file = text(record, "frame_samples_csv");
  if (file.empty()) return {};
  return load_frame_samples((std::filesystem::path(run.dir) / file).string());
}

// The spread of one run's log median from the records' calibration (time_run_to_run_spread
// is the spread of the difference of two runs: sqrt 2 times one's), the larger of the two;
// -1 when neither carries one.
double calibrated_spread(const json& a, const json& b) {
  double out = -1;
  for (const json* r : {&a, &b}) {
    const double s = number(*r, "time_run_to_run_spread");
    if (s > 0) out = std::max(out, s / std::sqrt(2.0));
  }
  return out;
}

// Whether `column` is declared deterministic (an undeclared counter, from another build's
// schema, is given the tolerance).
bool deterministic_work(const std::string& column) {
  const ColumnSpec* spec = find_column(column);
  return spec && spec->deterministic;
}

void compare_work(ConfigChange& c, const json& a, const json& b, const CompareThresholds& t) {
  auto counters = [](const json& record) {
    std::map<std::string, double> out;
    for (const auto& [key, value] : record.items())
      if (key.rfind("work_", 0) == 0 && key != "work_replay_ms" && value.is_number()) out[key] = value.get<double>();
    return out;
  };
  const std::map<std::string, double> in_a = counters(a), in_b = counters(b);
  bool more = false, less = false;
  for (const auto& [column, base] : in_a) {
    const auto found = in_b.find(column);
    if (found == in_b.end()) {
      c.work_only_in_base.push_back(column);
      continue;
    }
    WorkChange w{column, base, found->second, deterministic_work(column), ""};
    const double allowed = w.deterministic ? 0.0 : t.work_tolerance * std::fabs(base);
    if (w.next > base + allowed) w.verdict = "MORE";
    else if (w.next < base - allowed) w.verdict = "LESS";
    else w.verdict = "SAME";
    more = more || w.verdict == "MORE";
    less = less || w.verdict == "LESS";
    c.work.push_back(std::move(w));
  }
  for (const auto& [column, value] : in_b)
    if (!in_a.count(column)) c.work_only_in_new.push_back(column);
  if (!c.work.empty()) c.work_verdict = more ? "MORE" : less ? "LESS" : "SAME";
}

void compare_pair(ConfigChange& c, const RunRecords& base, const json& a, const RunRecords& next,
                  const json& b, bool same_device, bool paired, const CompareThresholds& t) {
  c.new_status = text(b, "status");
  c.status_worse = status_rank(c.new_status) > status_rank(c.base_status);

  const std::string timer_a = text(a, "timer"), timer_b = text(b, "timer");
  if (!t.compare_time)
    c.time_note = "not compared (--no-time)";
  else if (c.cross == "cross-driver")
    c.time_note = "drivers differ (" + c.base_driver + " vs " + c.new_driver + ")";
  else if (!same_device)
    c.time_note = "devices differ (" + text(a, "device") + " vs " + text(b, "device") + ")";
  else if (timer_a != timer_b)
    c.time_note = "timers differ (" + timer_a + " vs " + timer_b + ")";
  else {
    const std::vector<TimingSeries> sa = samples_of(base, a), sb = samples_of(next, b);
    for (const std::string& subpass : t.time_subpasses) {
      const auto ta = side_times(sa, subpass), tb = side_times(sb, subpass);
      if (!ta || !tb) {
        c.time_note += (c.time_note.empty() ? "" : ", ") + subpass + " samples not in both";
        continue;
      }
      c.times.push_back(test_time(subpass, *ta, *tb, paired, t, calibrated_spread(a, b)));
    }
  }

  c.base_allocated = number(a, "bytes_allocated");
  c.new_allocated = number(b, "bytes_allocated");
  c.base_used = number(a, "bytes_used");
  c.new_used = number(b, "bytes_used");
  if (c.base_allocated >= 0 && c.new_allocated >= 0 && c.base_used >= 0 && c.new_used >= 0) {
    const auto grew = [&](double base, double next) { return next > base * (1 + t.memory_tolerance); };
    if (grew(c.base_allocated, c.new_allocated) || grew(c.base_used, c.new_used)) c.memory_verdict = "MORE";
    else if (c.new_allocated < c.base_allocated || c.new_used < c.base_used) c.memory_verdict = "LESS";
    else c.memory_verdict = "SAME";
  }

  compare_work(c, a, b, t);

  c.base_mse = number(a, "mse");
  c.new_mse = number(b, "mse");
  c.base_mssim = number(a, "mssim");
  c.new_mssim = number(b, "mssim");
  c.noise_mse = number(a, "ref_noise_mse");
  if (c.base_mse >= 0 && c.new_mse >= 0 && c.noise_mse > 0) {
    const double allowed = t.noise_factor * c.noise_mse;
    const double delta = c.new_mse - c.base_mse;
    c.accuracy_verdict = delta > allowed ? "WORSE" : delta < -allowed ? "BETTER" : "SAME";
  }
}

std::string fixed(double v, const char* format) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

std::string mib(double bytes) { return bytes < 0 ? "-" : fixed(bytes / (1024.0 * 1024.0), "%.3g"); }

std::vector<std::string> distinct(const std::vector<json>& records, const std::function<std::string(const json&)>& of) {
  std::vector<std::string> out;
  for (const json& r : records)
    if (const std::string v = of(r); std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  return out;
}

// Says once, for the run, when the two sides ran on different drivers or devices: their
// differences are then what the drivers or devices do, not regressions.
void add_device_warnings(const RunRecords& base, const RunRecords& next, size_t other_gpus, RunComparison& out) {
  const auto cross = [&](const std::string& kind) {
    return std::count_if(out.matched.begin(), out.matched.end(), [&](const ConfigChange& c) { return c.cross == kind; });
  };
  const auto device = [](const json& r) { return text(r, "device"); };
  const std::string base_drivers = joined(distinct(base.records, record_driver));
  const std::string new_drivers = joined(distinct(next.records, record_driver));
  if (const auto n = cross("cross-driver"))
    out.warnings.push_back("baseline on " + base_drivers + ", candidate on " + new_drivers +
                           ": a cross-driver comparison (" + std::to_string(n) +
                           " configuration(s)), differences are not regressions; times are not compared");
  if (const auto n = cross("cross-device"))
    out.warnings.push_back("baseline on " + joined(distinct(base.records, device)) + ", candidate on " +
                           joined(distinct(next.records, device)) + ": a cross-device comparison (" +
                           std::to_string(n) + " configuration(s)), differences are not regressions; "
                           "times are not compared");
  if (other_gpus)
    out.warnings.push_back(std::to_string(other_gpus) + " configuration(s) ran on another GPU of the same "
                           "model (device_id differs): times compared, but the spread between GPUs of one "
                           "model is not in their intervals");
}

// The median 1-minute load average over a run's records at their repetitions' start; -1
// where no record has it (runs from before the machine state was recorded).
double median_load(const RunRecords& run) {
  std::vector<double> loads;
  for (const json& r : run.records)
    if (const double load = number(r, "load_average_start"); load >= 0) loads.push_back(load);
  if (loads.empty()) return -1;
  std::nth_element(loads.begin(), loads.begin() + long(loads.size() / 2), loads.end());
  return loads[loads.size() / 2];
}

// Says when the two runs ran at different loads of their machine: a record's interval
// holds another run's median at the load it was calibrated at (the run-to-run spread
// depends on the load), not across a change of load. Measured on the 2-core machine: a
// quiet run's intervals held a run at load 2-4 in 3 of 36 configurations (docs/timing.md).
void add_load_warning(const RunRecords& base, const RunRecords& next, RunComparison& out) {
  const double a = median_load(base), b = median_load(next);
  if (a < 0 || b < 0 || std::fabs(a - b) <= kCalibrationMaxLoadChange) return;
  char text[260];
  std::snprintf(text, sizeof text,
                "the runs were measured at different loads of their machine (median load average %.2f and %.2f): "
                "time changes may be the load's, and each run's intervals hold only at its own load",
                a, b);
  out.warnings.push_back(text);
}

}  // namespace

RunRecords load_run_records(const std::string& folder_or_file) {
  namespace fs = std::filesystem;
  fs::path path(folder_or_file);
  if (fs::is_directory(path)) path /= "records.json";
  std::ifstream in(path);
  if (!in) throw UserError(path.string() + ": cannot read (expected a run folder or its records.json)");
  RunRecords run;
  run.path = path.string();
  run.dir = path.parent_path().string();
  std::stringstream bytes;
  bytes << in.rdbuf();
  // Strictly (util/json_input.h): a truncated file is an error naming its line, not an empty run.
  json root = parse_json_strictly(bytes.str(), path.string());
  if (!root.is_object() || !root.contains("records") || !root["records"].is_array())
    throw UserError(path.string() + ": not an ldmbench records.json (no \"records\" array)");
  run.run = root.value("run", json::object());
  for (size_t i = 0; i < root["records"].size(); ++i) {
    const json& r = root["records"][i];
    if (!r.is_object() || text(r, "config_id").empty())
      throw UserError(path.string() + ": record " + std::to_string(i) + " has no config_id");
    // Against the column schema (records/record_validation.h): a renamed or retyped column
    // is refused, not compared.
    const Record record = record_from_json(r, path.string() + ": record " + std::to_string(i + 1));
    if (const std::string problem = schema_problem(record, record_columns(), from_other_build(record)); !problem.empty())
      throw UserError(path.string() + ": record " + std::to_string(i + 1) + " (" + text(r, "config_id") +
                      "): " + problem);
    run.records.push_back(r);
  }
  // A run folder's tables are derived from its journal: they must agree with it.
  if (path.filename() == "records.json") check_tables_match_journal(run.dir);
  return run;
}

std::string record_driver(const json& record) {
  const std::string recorded = text(record, "gl_driver");
  if (!recorded.empty()) return recorded;
  return gl_driver_name(text(record, "device"), text(record, "gl_vendor"), text(record, "gl_version"));
}

bool ConfigChange::time_regression() const {
  if (!cross.empty()) return false;
  return std::any_of(times.begin(), times.end(), [](const TimeChange& t) { return t.verdict == "SLOW"; });
}

RunComparison compare_runs(const RunRecords& base, const RunRecords& next, const CompareThresholds& t) {
  RunComparison out;
  std::map<std::pair<std::string, std::string>, const json*> by_identity;
  std::map<std::string, std::vector<const json*>> by_config;
  std::set<const json*> used;
  for (const json& r : next.records) {
    const std::string id = identity_of(r, t.ignored_params);
    if (!by_identity.emplace(std::make_pair(id, text(r, "device")), &r).second)
      throw UserError(next.path + ": two records of " + id + " on " + text(r, "device") +
                      (t.ignored_params.empty() ? "" : " (after --ignore-param)"));
    by_config[id].push_back(&r);
  }
  // Two runs of one interleaved session (`ldmbench interleave`): repetition j of each was
  // measured beside the other's, so their ratio cancels what the pair shared.
  const std::string session_a = text(base.run, "interleaved_session"), session_b = text(next.run, "interleaved_session");
  out.paired = !session_a.empty() && session_a == session_b;
  size_t other_gpus = 0;  // pairs on two GPUs of one model
  for (const json& a : base.records) {
    ConfigChange c;
    c.config_id = text(a, "config_id");
    c.identity = identity_of(a, t.ignored_params);
    c.device = text(a, "device");
    c.base_status = text(a, "status");
    const json* b = nullptr;
    bool same_device = true;
    auto exact = by_identity.find({c.identity, c.device});
    if (exact != by_identity.end()) {
      b = exact->second;
    } else if (by_config[c.identity].size() == 1) {
      b = by_config[c.identity].front();  // the same configuration on another device
      same_device = false;
    }
    if (!b || used.count(b)) {
      c.new_status = "missing";
      c.status_worse = true;
      c.time_note = "not in NEW";
    } else {
      used.insert(b);
      c.base_driver = record_driver(a);
      c.new_driver = record_driver(*b);
      if (c.base_driver != c.new_driver) c.cross = "cross-driver";
      else if (!same_device) c.cross = "cross-device";
      const std::string id_a = text(a, "device_id"), id_b = text(*b, "device_id");
      if (c.cross.empty() && !id_a.empty() && !id_b.empty() && id_a != id_b) ++other_gpus;
      compare_pair(c, base, a, next, *b, same_device, out.paired, t);
    }
    out.matched.push_back(std::move(c));
  }
  std::vector<const json*> added;
  for (const json& r : next.records)
    if (!used.count(&r)) {
      out.added.push_back(identity_of(r, t.ignored_params));
      added.push_back(&r);
    }
  std::vector<const json*> missing;
  for (size_t i = 0; i < base.records.size(); ++i)
    if (out.matched[i].new_status == "missing") missing.push_back(&base.records[i]);
  if (!missing.empty() && !added.empty()) out.pairing_hints = pairing_hints(missing, added, t.ignored_params);
  // Holm over every time test at once (configurations x sub-passes); each test's MDE at
  // alpha / tests, the level of Holm's first and strictest step.
  std::vector<TimeChange*> tested;
  std::vector<double> p_values;
  for (ConfigChange& c : out.matched)
    for (TimeChange& change : c.times)
      if (change.p_value >= 0) {
        tested.push_back(&change);
        p_values.push_back(change.p_value);
      }
  out.time_tests = tested.size();
  const std::vector<double> adjusted = holm_adjusted(p_values);
  const double level = tested.empty() ? t.alpha : t.alpha / double(tested.size());
  for (size_t i = 0; i < tested.size(); ++i) {
    TimeChange& change = *tested[i];
    change.p_adjusted = adjusted[i];
    change.minimum_detectable = std::expm1(minimum_detectable_log_change(change.se, change.df, level, t.power));
    const double z = std::isfinite(change.df)
                         ? boost_quantile_t(change.df, 1 - t.alpha / 2)
                         : boost_quantile_normal(1 - t.alpha / 2);
    change.change_low = std::expm1(std::log1p(change.relative_change) - z * change.se);
    change.change_high = std::expm1(std::log1p(change.relative_change) + z * change.se);
  }
  for (ConfigChange& c : out.matched)
    for (TimeChange& change : c.times) judge_time(change, t);
  if (out.paired) out.warnings.push_back("both runs are of interleaved session " + session_a + ": paired time tests");
  const std::string commit_a = text(base.run, "git_commit"), commit_b = text(next.run, "git_commit");
  if (!commit_a.empty() && commit_a == commit_b)
    out.warnings.push_back("both runs are of commit " + commit_a);
  add_device_warnings(base, next, other_gpus, out);
  if (t.compare_time) add_load_warning(base, next, out);  // the load moves times alone
  return out;
}

const std::vector<std::string>& regression_kinds() {
  static const std::vector<std::string> kinds = {"time", "memory", "accuracy", "status", "work"};
  return kinds;
}

size_t count_regressions(const RunComparison& comparison, const std::string& kind) {
  return std::count_if(comparison.matched.begin(), comparison.matched.end(), [&](const ConfigChange& c) {
    if (kind == "time") return c.time_regression();
    if (kind == "memory") return c.memory_regression();
    if (kind == "accuracy") return c.accuracy_regression();
    if (kind == "status") return c.status_regression();
    if (kind == "work") return c.work_regression();
    throw std::invalid_argument("unknown regression kind " + kind);
  });
}

std::string describe_time_change(const TimeChange& t) {
  std::string out = t.subpass + " " + fixed(100 * t.relative_change, "%+.1f%%") + " " + t.verdict;
  const double change = std::fabs(std::log1p(t.relative_change));
  if (t.p_value < 0) return out + " (not tested)";
  if (t.verdict == "SAME" && !(change >= std::log1p(t.minimum_detectable)))
    return out + " (could not detect < " + percent_text(t.minimum_detectable) + ")";
  if (t.verdict == "SAME") return out + " (below the change of interest)";
  return out + fixed(t.p_adjusted, " (p=%.2g Holm)");
}

std::string describe_work_change(const ConfigChange& c) {
  if (c.work_verdict.empty()) return "-";
  std::string changed;
  size_t shown = 0, more = 0;
  for (const WorkChange& w : c.work) {
    if (w.verdict != (c.work_verdict == "LESS" ? "LESS" : "MORE")) continue;
    ++more;
    if (shown++ >= 3) continue;  // the first three; the JSON has every one
    changed += (changed.empty() ? " " : ", ") + w.column + " " +
               (std::isfinite(w.relative_change()) ? fixed(100 * w.relative_change(), "%+.3g%%") : "from 0") +
               " (" + fixed(w.base, "%.6g") + " -> " + fixed(w.next, "%.6g") + ")";
  }
  if (more > 3) changed += ", and " + std::to_string(more - 3) + " more";
  if (c.work_verdict == "SAME") return "SAME (" + std::to_string(c.work.size()) + " counters)";
  return c.work_verdict + changed;
}

std::string percent_text(double relative) {
  if (!std::isfinite(relative)) return "any change";
  if (relative >= 10) return fixed(1 + relative, "x%.2g");  // beyond 1000%: as a ratio
  return fixed(100 * relative, relative < 0.1 ? "%.1f%%" : "%.0f%%");
}

namespace {
std::string repetitions_advice(const RunComparison& comparison, double median_detectable);
}  // namespace

std::string comparison_table(const RunComparison& comparison) {
  std::vector<std::vector<std::string>> rows = {
      {"configuration", "status", "time", "memory MiB", "mse / noise", "mssim", "work"}};
  for (const ConfigChange& c : comparison.matched) {
    std::string status = c.base_status == c.new_status ? c.new_status : c.base_status + " -> " + c.new_status;
    if (c.status_worse) status += " WORSE";
    if (!c.cross.empty()) status += " [" + c.cross + ": " + c.base_driver + " -> " + c.new_driver + "]";
    std::string time;
    for (const TimeChange& t : c.times) time += (time.empty() ? "" : ", ") + describe_time_change(t);
    if (!c.time_note.empty()) time += (time.empty() ? "" : "; ") + c.time_note;
    std::string memory = "-";
    if (!c.memory_verdict.empty())
      memory = mib(c.base_allocated) + "/" + mib(c.base_used) + " -> " + mib(c.new_allocated) + "/" +
               mib(c.new_used) + " " + c.memory_verdict;
    std::string accuracy = "-", mssim = "-";
    if (!c.accuracy_verdict.empty())
      accuracy = fixed(c.base_mse / c.noise_mse, "%.3g") + " -> " +
                 fixed(c.new_mse / c.noise_mse, "%.3g") + " " + c.accuracy_verdict;
    if (c.base_mssim >= 0 && c.new_mssim >= 0)
      mssim = fixed(c.base_mssim, "%.4f") + " -> " + fixed(c.new_mssim, "%.4f");
    rows.push_back({c.identity, status, time.empty() ? "-" : time, memory, accuracy, mssim,
                    describe_work_change(c)});
  }
  std::vector<size_t> width(rows.front().size(), 0);
  for (const auto& row : rows)
    for (size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (size_t i = 0; i < row.size(); ++i)
      line += row[i] + (i + 1 < row.size() ? std::string(width[i] - row[i].size() + 2, ' ') : "");
    out += line + "\n";
  }
  for (const std::string& id : comparison.added) out += "only in NEW: " + id + "\n";
  std::set<std::string> warned;
  for (const ConfigChange& c : comparison.matched)
    for (const TimeChange& t : c.times)
      if (!t.warning.empty() && warned.insert(t.warning).second) out += "warning: " + t.warning + "\n";
  for (const std::string& w : comparison.warnings) out += "warning: " + w + "\n";
  std::vector<double> detectable;
  for (const ConfigChange& c : comparison.matched)
    for (const TimeChange& t : c.times)
      if (t.p_value >= 0) detectable.push_back(t.minimum_detectable);
  if (!detectable.empty()) {
    std::sort(detectable.begin(), detectable.end());
    out += "time: " + std::to_string(comparison.time_tests) +
           " tests, Holm-corrected (the chance of any false FAST/SLOW at most alpha); "
           "minimum detectable change per test: median " +
           percent_text(detectable[detectable.size() / 2]) + ", best " + percent_text(detectable.front()) +
           ", worst " + percent_text(detectable.back()) + "\n";
    out += repetitions_advice(comparison, detectable[detectable.size() / 2]);
  }
  for (const PairingHint& h : comparison.pairing_hints)
    out += "hint: --ignore-param " + h.param + " pairs " + std::to_string(h.paired) + " of the " +
           std::to_string(h.missing) + " configurations missing from NEW with configurations only in NEW" +
           (h.paired == h.missing ? " (all of them)" : "") + "\n";
  out += "regressions:";
  for (const std::string& kind : regression_kinds())
    out += " " + kind + " " + std::to_string(count_regressions(comparison, kind));
  return out + "\n";
}

size_t repetitions_for_detectable_change(double spread, double target, double alpha, double power) {
  if (!(spread > 0) || !(target > 0)) return 2;
  const double z = boost_quantile_normal(1 - alpha / 2) + boost_quantile_normal(power);
  const double k = 2 * std::pow(z * spread / std::log1p(target), 2);
  return std::max<size_t>(2, size_t(std::ceil(k - 1e-9)));
}

namespace {

// What reaches a 10 % minimum detectable change on this machine, from the spread the tests
// rested on: "" when the comparison detects 10 % already.
std::string repetitions_advice(const RunComparison& comparison, double median_detectable) {
  constexpr double kTarget = 0.10;
  if (median_detectable <= kTarget) return "";
  std::vector<double> spreads;
  std::set<std::string> sources;
  for (const ConfigChange& c : comparison.matched)
    for (const TimeChange& t : c.times)
      if (t.p_value >= 0 && t.process_spread > 0) {
        spreads.push_back(t.process_spread);
        sources.insert(t.spread_source);
      }
  if (spreads.empty()) return "";
  std::sort(spreads.begin(), spreads.end());
  const double spread = spreads[spreads.size() / 2];
  std::string from;
  for (const std::string& s : sources) from += (from.empty() ? "" : ", ") + s;
  char text[400];
  std::snprintf(text, sizeof text,
                "repetitions: one run's median varies by about %.3g%% between processes here (%s); "
                "a %.0f%% change needs about %zu repetitions per side (--repetitions), or fewer pairs "
                "measured side by side (ldmbench interleave)\n",
                100 * spread, from.c_str(), 100 * kTarget,
                repetitions_for_detectable_change(spread, kTarget, 0.05, 0.8));
  return text;
}

}  // namespace

namespace {
nlohmann::ordered_json work_json(const ConfigChange& c) {
  using oj = nlohmann::ordered_json;
  oj changes = oj::array();
  for (const WorkChange& w : c.work)
    if (w.verdict != "SAME")
      changes.push_back({{"column", w.column}, {"base", w.base}, {"new", w.next},
                         {"deterministic", w.deterministic}, {"verdict", w.verdict}});
  return {{"verdict", c.work_verdict}, {"counters", c.work.size()}, {"changes", changes},
          {"only_in_base", c.work_only_in_base}, {"only_in_new", c.work_only_in_new}};
}
}  // namespace

nlohmann::ordered_json comparison_json(const RunComparison& comparison, const CompareThresholds& t) {
  using oj = nlohmann::ordered_json;
  const auto num = [](double v) { return v < 0 ? oj(nullptr) : oj(v); };
  oj root;
  root["thresholds"] = {{"time_subpasses", t.time_subpasses},
                        {"alpha", t.alpha},
                        {"compare_time", t.compare_time},
                        {"multiplicity", "holm"},
                        {"power", t.power},
                        {"process_spread", t.process_spread},
                        {"min_time_change", t.min_time_change},
                        {"memory_tolerance", t.memory_tolerance},
                        {"noise_factor", t.noise_factor},
                        {"ignored_params", t.ignored_params}};
  root["configurations"] = oj::array();
  for (const ConfigChange& c : comparison.matched) {
    oj times = oj::array();
    for (const TimeChange& x : c.times)
      times.push_back({{"subpass", x.subpass},
                       {"method", x.method},
                       {"base_repetitions", x.base_repetitions},
                       {"new_repetitions", x.new_repetitions},
                       {"base_samples", x.base_samples},
                       {"new_samples", x.new_samples},
                       {"base_median_ms", x.base_median},
                       {"new_median_ms", x.new_median},
                       {"relative_change", x.relative_change},
                       {"change_interval", x.p_value < 0 ? oj(nullptr) : oj::array({x.change_low, x.change_high})},
                       {"p_value", x.p_value < 0 ? oj(nullptr) : oj(x.p_value)},
                       {"p_adjusted", x.p_adjusted < 0 ? oj(nullptr) : oj(x.p_adjusted)},
                       {"minimum_detectable_change",
                        x.p_value < 0 || !std::isfinite(x.minimum_detectable) ? oj(nullptr) : oj(x.minimum_detectable)},
                       {"process_spread", x.process_spread < 0 ? oj(nullptr) : oj(x.process_spread)},
                       {"process_spread_source", x.spread_source},
                       {"verdict", x.verdict},
                       {"summary", describe_time_change(x)},
                       {"warning", x.warning}});
    root["configurations"].push_back(
        {{"identity", c.identity}, {"config_id", c.config_id}, {"device", c.device},
         {"drivers", {{"base", c.base_driver}, {"new", c.new_driver}}}, {"cross", c.cross},
         {"status", {{"base", c.base_status}, {"new", c.new_status}, {"worse", c.status_worse}}},
         {"time", times}, {"time_note", c.time_note},
         {"memory", {{"base_allocated", num(c.base_allocated)}, {"new_allocated", num(c.new_allocated)},
                     {"base_used", num(c.base_used)}, {"new_used", num(c.new_used)},
                     {"verdict", c.memory_verdict}}},
         {"accuracy", {{"base_mse", num(c.base_mse)}, {"new_mse", num(c.new_mse)},
                       {"ref_noise_mse", num(c.noise_mse)}, {"base_mssim", num(c.base_mssim)},
                       {"new_mssim", num(c.new_mssim)}, {"verdict", c.accuracy_verdict}}},
         {"work", work_json(c)}});
  }
  root["time_tests"] = comparison.time_tests;
  root["paired"] = comparison.paired;
  root["only_in_new"] = comparison.added;
  root["warnings"] = comparison.warnings;
  root["pairing_hints"] = oj::array();
  for (const PairingHint& h : comparison.pairing_hints)
    root["pairing_hints"].push_back({{"ignore_param", h.param}, {"pairs", h.paired}, {"missing", h.missing}});
  oj counts;
  for (const std::string& kind : regression_kinds()) counts[kind] = count_regressions(comparison, kind);
  root["regressions"] = counts;
  return root;
}

}  // namespace ldm
