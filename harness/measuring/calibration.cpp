#include "harness/measuring/calibration.h"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "harness/measuring/machine_state.h"
#include "harness/util/error.h"
#include "harness/util/files.h"
#include "harness/util/json_input.h"
#include "harness/util/process.h"
#include "harness/util/version.h"

namespace ldm {
namespace {

// Configurations of different cost (a factor of about 3 between the cheapest and the
// dearest frame here), small enough that a probe process takes about a second.
const std::vector<std::string> kProbeRun = {"run",           "--scene",      "cornell",       "--structure",
                                            "psppsll,habuffer,ppfla",       "-N",            "8,32",
                                            "-R",            "64",           "--image-size",  "64x64",
                                            "--no-reference", "--no-images", "--calibration", "skip",
                                            // A fixed number of frames: a run's default time target would
                                            // let a loaded machine stretch every configuration to its 2 s
                                            // cap (a 30 s probe); 9 frames' median varies a little more,
                                            // which only widens the spread (the safe side).
                                            "--time-target", "0", "--frames", "9"};

// The sub-passes whose spread is measured: the times tables and decisions read. (The sizing
// policy's sub-millisecond census and readback vary far more in relative terms; their own
// frame intervals are wide already.)
const std::set<std::string> kProbedSubpasses = {"build", "pass", "frame"};

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string();
}

int64_t now_seconds() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path + ": cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ProbeMedians probe_medians(const std::string& records_json) {
  const nlohmann::json j = parse_json_strictly(read_text(records_json), records_json);
  ProbeMedians out;
  const std::string suffix = "_ms_median";
  for (const auto& r : j.at("records")) {
    if (r.value("status", "") != "ok") continue;
    const std::string id = r.value("config_id", "");
    for (const auto& [key, value] : r.items())
      if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          value.is_number()) {
        const std::string subpass = key.substr(0, key.size() - suffix.size());
        if (kProbedSubpasses.count(subpass)) out[id + "/" + subpass] = value.get<double>();
      }
  }
  return out;
}

std::string describe(const RunToRunSpread& s) {
  std::ostringstream text;
  char spread[32];
  std::snprintf(spread, sizeof spread, "%.3f", s.spread);
  text << spread << " (" << s.pairs << " log ratios from " << s.processes << " processes";
  if (s.pooled_probes > 1) text << " of " << s.pooled_probes << " probes pooled";
  if (s.measured_at) {
    char when[32];
    const std::time_t t = std::time_t(s.measured_at);
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    text << ", " << when;
  }
  if (std::isfinite(s.load_average)) {
    char load[32];
    std::snprintf(load, sizeof load, ", load %.2f", s.load_average);
    text << load;
  }
  if (std::isfinite(s.busy_cpus)) {
    char busy[48];
    std::snprintf(busy, sizeof busy, ", %.2f CPUs busy with other work", s.busy_cpus);
    text << busy;
  }
  text << ")";
  return text.str();
}

// The probes a cached entry holds: its list, or (written before pooling) itself.
std::vector<ProbeEntry> probes_of(const RunToRunSpread& cached) {
  if (!cached.probes.empty()) return cached.probes;
  return {ProbeEntry{cached.spread, cached.pairs, cached.processes, cached.measured_at, cached.load_average,
                     cached.commit, {}, cached.busy_cpus}};
}

}  // namespace

RunToRunSpread probe_and_pool(const DeviceInfo& device, const ProbeOptions& options, std::ostream& log) {
  const RunToRunSpread fresh = run_calibration_probe(device, options, log);
  std::vector<ProbeEntry> earlier;
  const std::string cache = calibration_cache_file(device).string();
  if (std::filesystem::is_regular_file(cache)) {
    try {
      earlier = probes_of(read_calibration_file(cache));
    } catch (const UserError& e) {
      log << "calibration: the cached probes are not pooled: " << e.what() << "\n";
    }
  }
  return pool_with_earlier_probes(fresh, earlier, now_seconds());
}

CalibrationChoice parse_calibration_choice(const std::string& option_value, const char* environment_value) {
  CalibrationChoice choice;
  std::string value = option_value;
  choice.origin = "--calibration";
  if (value.empty() && environment_value && *environment_value) {
    value = environment_value;
    choice.origin = "LDM_CALIBRATION";
  }
  if (value.empty()) {
    choice.origin = "default";
    return choice;
  }
  if (value == "auto") return choice;
  if (value == "skip") {
    choice.kind = CalibrationChoice::Kind::Skip;
    return choice;
  }
  if (!std::filesystem::is_regular_file(value))
    throw UserError(choice.origin + " " + value +
                    ": neither auto, skip nor a spread file (`ldmbench calibrate --out FILE` writes one)");
  choice.kind = CalibrationChoice::Kind::File;
  choice.file = value;
  return choice;
}

RunToRunSpread run_calibration_probe(const DeviceInfo& device, const ProbeOptions& options, std::ostream& log) {
  const std::string program = options.program.empty() ? executable_path() : options.program;
  if (program.empty()) throw UserError("calibrate: cannot find this program's path (/proc/self/exe)");
  if (options.processes < 2) throw UserError("calibrate: --processes must be at least 2");
  const auto started = std::chrono::steady_clock::now();
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("ldmbench-calibrate-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::vector<ProbeMedians> processes;
  double load_sum = 0;
  int load_count = 0;
  // The load the spread belongs to is other processes', read before the probe's own start.
  const auto busy = busy_cpus_now();
  try {
    for (int p = 0; p < options.processes; ++p) {
      if (p && options.gap_seconds > 0) std::this_thread::sleep_for(std::chrono::duration<double>(options.gap_seconds));
      if (const auto load = current_load_average()) {
        load_sum += *load;
        ++load_count;
      }
      const std::string out = (folder / ("process-" + std::to_string(p))).string();
      std::vector<std::string> argv = {program};
      argv.insert(argv.end(), kProbeRun.begin(), kProbeRun.end());
      argv.insert(argv.end(), {"--out", out});
      log << "calibrate: probe process " << p + 1 << "/" << options.processes << "\n" << std::flush;
      const ProcessResult result = run_process(argv, true, true);
      if (!result.started || result.status != 0)
        throw UserError("calibrate: the probe process failed (exit " + std::to_string(result.status) + "):\n" +
                        result.output);
      processes.push_back(probe_medians(out + "/records.json"));
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
    throw;
  }
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
  RunToRunSpread spread = spread_from_processes(processes);
  if (!spread.pairs) throw UserError("calibrate: the probe processes measured nothing in common");
  spread.medians = processes;
  spread.measured_at = now_seconds();
  spread.load_average = load_count ? load_sum / load_count : std::nan("");
  spread.busy_cpus = busy ? *busy : std::nan("");
  spread.probe_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  spread.device = device.gl_renderer;
  spread.driver = device.gl_version;
  spread.host = host_name();
  spread.commit = git_commit();
  spread.source = "probe";
  return spread;
}

std::filesystem::path calibration_cache_dir() {
  const std::string folder = ldmbench_cache_dir("calibration");
  if (folder.empty())
    throw UserError("--calibration auto has no cache folder: neither XDG_CACHE_HOME (absolute) nor HOME is set; "
                    "give --calibration FILE or skip");
  return folder;
}

std::filesystem::path calibration_cache_file(const DeviceInfo& device) {
  // Not keyed by the build: the spread is the machine's, and a rebuild should not re-probe.
  return calibration_cache_dir() / calibration_key(device.gl_renderer, device.gl_version, host_name());
}

RunToRunSpread read_calibration_file(const std::string& path) { return spread_from_json(read_text(path), path); }

std::string calibration_staleness_now(const RunToRunSpread& cached) {
  const auto load = current_load_average();
  // Only an entry that knows its busy CPUs is judged by them (older ones by the load average).
  const auto busy = std::isfinite(cached.busy_cpus) ? busy_cpus_now() : std::nullopt;
  return calibration_staleness(cached, now_seconds(), load ? *load : std::nan(""), busy ? *busy : std::nan(""));
}

void write_calibration_file(const std::string& path, const RunToRunSpread& spread) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) {
    std::error_code error;
    std::filesystem::create_directories(parent, error);
    if (error) throw_file_error("cannot create " + parent.string(), error.value());
  }
  write_text_atomically(path, spread_to_json(spread));
}

ResolvedCalibration resolve_calibration(const CalibrationChoice& choice, const DeviceInfo& device,
                                        std::ostream& log) {
  ResolvedCalibration out;
  switch (choice.kind) {
    case CalibrationChoice::Kind::Skip:
      out.source = "skipped (" + choice.origin + " skip): intervals are within-run only";
      return out;
    case CalibrationChoice::Kind::File: {
      out.spread = read_calibration_file(choice.file);
      out.file = choice.file;
      out.source = "file " + choice.file + ": " + describe(*out.spread);
      return out;
    }
    case CalibrationChoice::Kind::Auto:
      break;
  }
  const std::string path = calibration_cache_file(device).string();
  std::string why = "none cached";
  if (std::filesystem::is_regular_file(path)) {
    try {
      RunToRunSpread cached = read_calibration_file(path);
      why = calibration_staleness_now(cached);
      if (why.empty()) {
        out.spread = cached;
        out.file = path;
        out.source = "cache " + path + ": " + describe(cached);
        return out;
      }
    } catch (const UserError& e) {
      why = std::string("unreadable (") + e.what() + ")";
    }
  }
  log << "calibrating the run-to-run spread of this machine (" << why
      << "; `ldmbench calibrate`, --calibration skip|FILE): a few seconds\n";
  RunToRunSpread measured = probe_and_pool(device, ProbeOptions{}, log);
  write_calibration_file(path, measured);
  out.spread = measured;
  out.file = path;
  out.source = "cache " + path + ": " + describe(measured) + ", probed for this run";
  log << "run-to-run spread: " << describe(measured) << "\n";
  return out;
}

}  // namespace ldm
