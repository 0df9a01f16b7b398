#include "harness/compare/run_comparison.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "harness/compare/mann_whitney.h"
#include "harness/compare/samples.h"
#include "harness/util/error.h"

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

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// config_id writes each structure parameter as "-key=value" with odd characters as '_'
// (Configuration::id); leaving a parameter out of the identity removes that part.
std::string identity_of(const json& record, const std::set<std::string>& ignored) {
  std::string id = text(record, "config_id");
  std::stringstream params(text(record, "structure_params"));
  for (std::string item; std::getline(params, item, ';');) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || !ignored.count(item.substr(0, eq))) continue;
    std::string part = "-" + item;
    for (char& c : part)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '='))
        c = '_';
    const size_t at = id.find(part);
    if (at != std::string::npos) id.erase(at, part.size());
  }
  return id;
}

int status_rank(const std::string& status) {
  static const std::map<std::string, int> ranks = {
      {"ok", 0}, {"lossy", 1}, {"invalid", 2}, {"failed", 3}, {"missing", 4}};
  auto it = ranks.find(status);
  return it == ranks.end() ? 3 : it->second;
}

TimeChange compare_time(const std::string& subpass, const std::vector<double>& a,
                        const std::vector<double>& b, const CompareThresholds& t) {
  TimeChange c;
  c.subpass = subpass;
  c.base_samples = a.size();
  c.new_samples = b.size();
  c.base_median = median(a);
  c.new_median = median(b);
  c.relative_change = c.base_median > 0 ? (c.new_median - c.base_median) / c.base_median : 0;
  const bool large = std::fabs(c.relative_change) >= t.min_time_change;
  if (std::min(a.size(), b.size()) < kUTestMinSamples) {
    c.warning = "fewer than " + std::to_string(kUTestMinSamples) + " samples: not tested";
    c.verdict = large ? "UNSURE" : "SAME";
    return c;
  }
  if (std::min(a.size(), b.size()) < kUTestOptimalSamples)
    c.warning = "fewer than " + std::to_string(kUTestOptimalSamples) +
                " samples: the U test is weak, results may be unreliable";
  c.p_value = mann_whitney_u(a, b).p_value;
  const bool significant = c.p_value < t.alpha;
  if (!large) c.verdict = "SAME";
  else if (!significant) c.verdict = "UNSURE";
  else c.verdict = c.relative_change > 0 ? "SLOW" : "FAST";
  return c;
}

// The record's per-frame samples; empty when it names none (failed, or an older run).
FrameSamples samples_of(const RunRecords& run, const json& record) {
  const std::string file = text(record, "frame_samples_csv");
  if (file.empty()) return {};
  return load_frame_samples((std::filesystem::path(run.dir) / file).string());
}

void compare_pair(ConfigChange& c, const RunRecords& base, const json& a, const RunRecords& next,
                  const json& b, bool same_device, const CompareThresholds& t) {
  c.new_status = text(b, "status");
  c.status_worse = status_rank(c.new_status) > status_rank(c.base_status);

  const std::string timer_a = text(a, "timer"), timer_b = text(b, "timer");
  if (!same_device)
    c.time_note = "devices differ (" + text(a, "device") + " vs " + text(b, "device") + ")";
  else if (timer_a != timer_b)
    c.time_note = "timers differ (" + timer_a + " vs " + timer_b + ")";
  else {
    const FrameSamples sa = samples_of(base, a), sb = samples_of(next, b);
    for (const std::string& subpass : t.time_subpasses) {
      auto ia = sa.find(subpass), ib = sb.find(subpass);
      if (ia == sa.end() || ib == sb.end()) {
        c.time_note += (c.time_note.empty() ? "" : ", ") + subpass + " samples not in both";
        continue;
      }
      c.times.push_back(compare_time(subpass, ia->second, ib->second, t));
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
  json root;
  try {
    root = json::parse(in);
  } catch (const json::exception& e) {
    throw UserError(path.string() + ": not JSON: " + e.what());
  }
  if (!root.is_object() || !root.contains("records") || !root["records"].is_array())
    throw UserError(path.string() + ": not an ldmbench records.json (no \"records\" array)");
  run.run = root.value("run", json::object());
  for (size_t i = 0; i < root["records"].size(); ++i) {
    const json& r = root["records"][i];
    if (!r.is_object() || text(r, "config_id").empty())
      throw UserError(path.string() + ": record " + std::to_string(i) + " has no config_id");
    run.records.push_back(r);
  }
  return run;
}

bool ConfigChange::time_regression() const {
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
      compare_pair(c, base, a, next, *b, same_device, t);
    }
    out.matched.push_back(std::move(c));
  }
  for (const json& r : next.records)
    if (!used.count(&r)) out.added.push_back(identity_of(r, t.ignored_params));
  const std::string commit_a = text(base.run, "git_commit"), commit_b = text(next.run, "git_commit");
  if (!commit_a.empty() && commit_a == commit_b)
    out.warnings.push_back("both runs are of commit " + commit_a);
  if (text(base.run, "device") != text(next.run, "device"))
    out.warnings.push_back("devices differ: " + text(base.run, "device") + " vs " +
                           text(next.run, "device") + "; times are not compared");
  return out;
}

const std::vector<std::string>& regression_kinds() {
  static const std::vector<std::string> kinds = {"time", "memory", "accuracy", "status"};
  return kinds;
}

size_t count_regressions(const RunComparison& comparison, const std::string& kind) {
  return std::count_if(comparison.matched.begin(), comparison.matched.end(), [&](const ConfigChange& c) {
    if (kind == "time") return c.time_regression();
    if (kind == "memory") return c.memory_regression();
    if (kind == "accuracy") return c.accuracy_regression();
    if (kind == "status") return c.status_worse;
    throw std::invalid_argument("unknown regression kind " + kind);
  });
}

std::string comparison_table(const RunComparison& comparison) {
  std::vector<std::vector<std::string>> rows = {
      {"configuration", "status", "time", "memory MiB", "mse / noise", "mssim"}};
  for (const ConfigChange& c : comparison.matched) {
    std::string status = c.base_status == c.new_status ? c.new_status : c.base_status + " -> " + c.new_status;
    if (c.status_worse) status += " WORSE";
    std::string time;
    for (const TimeChange& t : c.times) {
      time += (time.empty() ? "" : ", ") + t.subpass + " " + fixed(100 * t.relative_change, "%+.1f%%") +
              " " + t.verdict;
      if (t.p_value >= 0) time += fixed(t.p_value, " (p=%.2g)");
    }
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
    rows.push_back({c.identity, status, time.empty() ? "-" : time, memory, accuracy, mssim});
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
  out += "regressions:";
  for (const std::string& kind : regression_kinds())
    out += " " + kind + " " + std::to_string(count_regressions(comparison, kind));
  return out + "\n";
}

nlohmann::ordered_json comparison_json(const RunComparison& comparison, const CompareThresholds& t) {
  using oj = nlohmann::ordered_json;
  const auto num = [](double v) { return v < 0 ? oj(nullptr) : oj(v); };
  oj root;
  root["thresholds"] = {{"time_subpasses", t.time_subpasses},
                        {"alpha", t.alpha},
                        {"min_time_change", t.min_time_change},
                        {"memory_tolerance", t.memory_tolerance},
                        {"noise_factor", t.noise_factor},
                        {"ignored_params", t.ignored_params}};
  root["configurations"] = oj::array();
  for (const ConfigChange& c : comparison.matched) {
    oj times = oj::array();
    for (const TimeChange& x : c.times)
      times.push_back({{"subpass", x.subpass},
                       {"base_samples", x.base_samples},
                       {"new_samples", x.new_samples},
                       {"base_median_ms", x.base_median},
                       {"new_median_ms", x.new_median},
                       {"relative_change", x.relative_change},
                       {"p_value", x.p_value < 0 ? oj(nullptr) : oj(x.p_value)},
                       {"verdict", x.verdict},
                       {"warning", x.warning}});
    root["configurations"].push_back(
        {{"identity", c.identity}, {"config_id", c.config_id}, {"device", c.device},
         {"status", {{"base", c.base_status}, {"new", c.new_status}, {"worse", c.status_worse}}},
         {"time", times}, {"time_note", c.time_note},
         {"memory", {{"base_allocated", num(c.base_allocated)}, {"new_allocated", num(c.new_allocated)},
                     {"base_used", num(c.base_used)}, {"new_used", num(c.new_used)},
                     {"verdict", c.memory_verdict}}},
         {"accuracy", {{"base_mse", num(c.base_mse)}, {"new_mse", num(c.new_mse)},
                       {"ref_noise_mse", num(c.noise_mse)}, {"base_mssim", num(c.base_mssim)},
                       {"new_mssim", num(c.new_mssim)}, {"verdict", c.accuracy_verdict}}}});
  }
  root["only_in_new"] = comparison.added;
  root["warnings"] = comparison.warnings;
  oj counts;
  for (const std::string& kind : regression_kinds()) counts[kind] = count_regressions(comparison, kind);
  root["regressions"] = counts;
  return root;
}

}  // namespace ldm
