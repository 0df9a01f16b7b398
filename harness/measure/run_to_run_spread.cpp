#include "harness/measure/run_to_run_spread.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/json_input.h"

namespace ldm {

RunToRunSpread spread_from_processes(const std::vector<ProbeMedians>& processes) {
  RunToRunSpread out;
  out.processes = processes.size();
  double sum_of_squares = 0;
  for (size_t a = 0; a < processes.size(); ++a)
    for (size_t b = a + 1; b < processes.size(); ++b)
      for (const auto& [key, median_a] : processes[a]) {
        const auto other = processes[b].find(key);
        if (other == processes[b].end() || !(median_a > 0) || !(other->second > 0)) continue;
        const double log_ratio = std::log(median_a / other->second);
        sum_of_squares += log_ratio * log_ratio;
        ++out.pairs;
      }
  if (out.pairs) out.spread = std::sqrt(sum_of_squares / double(out.pairs));
  return out;
}

bool same_load(double load_average_a, double busy_cpus_a, double load_average_b, double busy_cpus_b) {
  if (std::isfinite(busy_cpus_a) && std::isfinite(busy_cpus_b))
    return std::fabs(busy_cpus_a - busy_cpus_b) <= kCalibrationMaxLoadChange;
  return std::isfinite(load_average_a) && std::isfinite(load_average_b) &&
         std::fabs(load_average_a - load_average_b) <= kCalibrationMaxLoadChange;
}

std::string calibration_staleness(const RunToRunSpread& cached, int64_t now, double load_average_now,
                                  double busy_cpus_now) {
  char text[160];
  const int64_t age = now - cached.measured_at;
  if (age > kCalibrationMaxAgeSeconds || age < 0) {
    std::snprintf(text, sizeof text, "measured %.1f h ago (more than %d h)", double(age) / 3600,
                  int(kCalibrationMaxAgeSeconds / 3600));
    return text;
  }
  // One comparison for staleness and pooling (same_load): busy CPUs where both sides have
  // them, else the load averages; nothing known, nothing stale.
  const bool by_busy_cpus = std::isfinite(busy_cpus_now) && std::isfinite(cached.busy_cpus);
  const bool load_known = by_busy_cpus || (std::isfinite(load_average_now) && std::isfinite(cached.load_average));
  if (load_known && !same_load(cached.load_average, cached.busy_cpus, load_average_now, busy_cpus_now)) {
    if (by_busy_cpus)
      std::snprintf(text, sizeof text,
                    "other processes keep %.2f CPUs busy now, %.2f before the probe (differs by more than %.1f)",
                    busy_cpus_now, cached.busy_cpus, kCalibrationMaxLoadChange);
    else
      std::snprintf(text, sizeof text, "load average %.2f now, %.2f at the probe (differs by more than %.1f)",
                    load_average_now, cached.load_average, kCalibrationMaxLoadChange);
    return text;
  }
  if (!std::isfinite(cached.spread)) return "no spread measured";
  return "";
}

RunToRunSpread pool_with_earlier_probes(const RunToRunSpread& fresh, const std::vector<ProbeEntry>& earlier,
                                        int64_t now) {
  RunToRunSpread out = fresh;
  const ProbeEntry own{fresh.spread,       fresh.pairs,  fresh.processes, fresh.measured_at,
                       fresh.load_average, fresh.commit, fresh.medians,   fresh.busy_cpus};
  out.probes.clear();
  for (const ProbeEntry& e : earlier) {
    const int64_t age = now - e.measured_at;
    if (age >= 0 && age <= kCalibrationMaxAgeSeconds && e.pairs && std::isfinite(e.spread)) out.probes.push_back(e);
  }
  if (out.probes.size() + 1 > kCalibrationKeptProbes)
    out.probes.erase(out.probes.begin(), out.probes.end() - std::ptrdiff_t(kCalibrationKeptProbes - 1));
  out.probes.push_back(own);
  std::vector<ProbeMedians> processes;
  double rms_sum_of_squares = 0;  // entries without medians
  size_t rms_pairs = 0, process_count = 0, pooled = 0;
  for (const ProbeEntry& e : out.probes) {
    // Another load, another spread; another build, other times: only probes by this build at
    // about this one's load (same_load) pool with it. A probe whose load is unknown pools only
    // with itself.
    const bool own_probe = &e == &out.probes.back();
    const bool at_this_load =
        own_probe || same_load(e.load_average, e.busy_cpus, fresh.load_average, fresh.busy_cpus);
    if (!at_this_load || (!own_probe && e.commit != fresh.commit)) continue;
    if (e.medians.size() >= 2 || (own_probe && !e.medians.empty())) {
      processes.insert(processes.end(), e.medians.begin(), e.medians.end());
    } else {
      rms_sum_of_squares += e.spread * e.spread * double(e.pairs);
      rms_pairs += e.pairs;
    }
    process_count += e.processes;
    ++pooled;
  }
  const RunToRunSpread across = spread_from_processes(processes);
  const double sum_of_squares = rms_sum_of_squares + (across.pairs ? across.spread * across.spread * double(across.pairs) : 0);
  const size_t pairs = rms_pairs + across.pairs;
  // Probes with their medians alone: their spread as computed (the root of its own square
  // would differ in the last bits, and a probe pooled with nothing must keep its value).
  if (rms_pairs == 0) {
    if (across.pairs) out.spread = across.spread;
  } else if (pairs) {
    out.spread = std::sqrt(sum_of_squares / double(pairs));
  }
  out.pairs = pairs;
  out.processes = process_count;
  out.pooled_probes = pooled;
  return out;
}

double widened_log_half_width(double within, double spread, size_t repetitions, double z,
                              RepetitionProcesses processes) {
  if (!std::isfinite(spread) || spread < 0) return within;
  const double w = std::isfinite(within) && within > 0 ? within : 0;
  if (repetitions > 1 && processes == RepetitionProcesses::Shared) return std::max(w, z * spread);
  const double k = double(std::max<size_t>(1, repetitions));
  // One repetition: this run's offset and the other's are both in the spread.
  // K repetitions in K processes: this run's are in the t interval; the other run's median of K.
  const double between = repetitions <= 1 ? z * spread : z * spread / std::sqrt(2 * k);
  return std::sqrt(w * w + between * between);
}

double frame_precision_floor(const RunToRunSpread* spread, double z) {
  if (!spread || !std::isfinite(spread->spread) || spread->spread <= 0) return 0.0;
  return z * spread->spread / (3.0 * std::sqrt(2.0));
}

std::string calibration_key(const std::string& device, const std::string& driver, const std::string& host) {
  Fnv1a hash;
  for (const std::string* part : {&device, &driver, &host}) {
    hash.add_string(*part);
  }
  std::string readable;
  for (char c : host + "-" + driver)
    readable += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  char digest[20];
  std::snprintf(digest, sizeof digest, "%016llx", static_cast<unsigned long long>(hash.value()));
  return "spread-" + readable.substr(0, 60) + "-" + digest + ".json";
}

std::string spread_to_json(const RunToRunSpread& s) {
  nlohmann::ordered_json j;
  j["spread"] = std::isfinite(s.spread) ? nlohmann::ordered_json(s.spread) : nlohmann::ordered_json();
  j["pairs"] = s.pairs;
  j["processes"] = s.processes;
  j["measured_at"] = s.measured_at;
  j["load_average"] = std::isfinite(s.load_average) ? nlohmann::ordered_json(s.load_average)
                                                    : nlohmann::ordered_json();
  j["busy_cpus"] = std::isfinite(s.busy_cpus) ? nlohmann::ordered_json(s.busy_cpus) : nlohmann::ordered_json();
  j["probe_seconds"] = s.probe_seconds;
  j["device"] = s.device;
  j["driver"] = s.driver;
  j["host"] = s.host;
  j["commit"] = s.commit;
  j["pooled_probes"] = s.pooled_probes;
  nlohmann::ordered_json probes = nlohmann::ordered_json::array();
  for (const ProbeEntry& e : s.probes) {
    nlohmann::ordered_json p;
    p["spread"] = e.spread;
    p["pairs"] = e.pairs;
    p["processes"] = e.processes;
    p["measured_at"] = e.measured_at;
    p["load_average"] = std::isfinite(e.load_average) ? nlohmann::ordered_json(e.load_average) : nlohmann::ordered_json();
    p["busy_cpus"] = std::isfinite(e.busy_cpus) ? nlohmann::ordered_json(e.busy_cpus) : nlohmann::ordered_json();
    p["commit"] = e.commit;
    nlohmann::ordered_json medians = nlohmann::ordered_json::array();
    for (const ProbeMedians& process : e.medians) medians.push_back(process);
    p["medians"] = medians;
    probes.push_back(p);
  }
  j["probes"] = probes;
  return j.dump(2) + "\n";
}

RunToRunSpread spread_from_json(const std::string& text, const std::string& origin) {
  const nlohmann::json j = parse_json_strictly(text, origin);
  if (!j.is_object()) throw UserError(origin + ": a run-to-run spread must be a JSON object");
  RunToRunSpread s;
  auto number = [&](const char* key, bool required) {
    const auto it = j.find(key);
    if (it == j.end() || it->is_null()) {
      if (required) throw UserError(origin + ": \"" + key + "\" is missing");
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (!it->is_number()) throw UserError(origin + ": \"" + key + "\" must be a number");
    return it->get<double>();
  };
  auto text_of = [&](const char* key) {
    const auto it = j.find(key);
    if (it == j.end()) return std::string();
    if (!it->is_string()) throw UserError(origin + ": \"" + key + "\" must be a string");
    return it->get<std::string>();
  };
  s.spread = number("spread", true);
  if (!(s.spread >= 0) || s.spread > 5)
    throw UserError(origin + ": \"spread\" must be between 0 and 5 (a log ratio), not " + std::to_string(s.spread));
  const double pairs = number("pairs", false), processes = number("processes", false);
  s.pairs = pairs >= 0 ? size_t(pairs) : 0;
  s.processes = processes >= 0 ? size_t(processes) : 0;
  const double at = number("measured_at", false);
  s.measured_at = std::isfinite(at) ? int64_t(at) : 0;
  s.load_average = number("load_average", false);
  s.busy_cpus = number("busy_cpus", false);
  const double seconds = number("probe_seconds", false);
  s.probe_seconds = std::isfinite(seconds) ? seconds : 0;
  s.device = text_of("device");
  s.driver = text_of("driver");
  s.host = text_of("host");
  s.commit = text_of("commit");
  const double pooled = number("pooled_probes", false);
  s.pooled_probes = pooled >= 1 ? size_t(pooled) : 1;
  // The probes pooled so far (absent in a file written before pooling, or by hand).
  if (const auto probes = j.find("probes"); probes != j.end()) {
    if (!probes->is_array()) throw UserError(origin + ": \"probes\" must be an array");
    for (const auto& p : *probes) {
      const auto field = [&](const char* key) {
        const auto it = p.is_object() ? p.find(key) : p.end();
        return it != p.end() && it->is_number() ? it->get<double>() : std::numeric_limits<double>::quiet_NaN();
      };
      ProbeEntry e;
      e.spread = field("spread");
      const double entry_pairs = field("pairs"), entry_processes = field("processes"), at_ = field("measured_at");
      if (!(e.spread >= 0) || e.spread > 5 || !(entry_pairs >= 1))
        throw UserError(origin + ": every entry of \"probes\" needs a spread between 0 and 5 and pairs");
      e.pairs = size_t(entry_pairs);
      e.processes = entry_processes >= 0 ? size_t(entry_processes) : 0;
      e.measured_at = std::isfinite(at_) ? int64_t(at_) : 0;
      e.load_average = field("load_average");
      e.busy_cpus = field("busy_cpus");
      if (const auto commit = p.find("commit"); commit != p.end() && commit->is_string()) e.commit = commit->get<std::string>();
      if (const auto medians = p.find("medians"); medians != p.end()) {
        if (!medians->is_array()) throw UserError(origin + ": a probe's \"medians\" must be an array");
        for (const auto& process : *medians) {
          if (!process.is_object()) throw UserError(origin + ": a probe process's medians must be an object");
          ProbeMedians m;
          for (const auto& [key, value] : process.items()) {
            if (!value.is_number()) throw UserError(origin + ": median \"" + key + "\" must be a number");
            m[key] = value.get<double>();
          }
          e.medians.push_back(std::move(m));
        }
      }
      s.probes.push_back(e);
    }
  }
  return s;
}

}  // namespace ldm
