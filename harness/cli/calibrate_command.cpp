// `ldmbench calibrate`: measures this machine's run-to-run spread (harness/measuring/calibration.h)
// and caches it, or writes it to a file that `--calibration FILE` reads.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "harness/measuring/calibration.h"
#include "harness/measuring/machine_state.h"
#include "harness/cli/commands.h"
#include "harness/compare/run_comparison.h"
#include "harness/gl/egl_context.h"
#include "harness/measure/run_to_run_spread.h"

namespace ldm::cli {
namespace {

// The cache entry's state as `calibrate --show --json` prints it: where it is, whether it
// exists, its spread, and whether --calibration auto would read it as it is (current) or
// probe again (stale, with why). `ldmbench advise` reads it once and hands the file to
// every stage, so that all its stages judge time by one spread.
std::string cache_state_json(const std::string& cache) {
  nlohmann::ordered_json state;
  state["file"] = cache;
  state["cached"] = std::filesystem::is_regular_file(cache);
  if (state["cached"]) {
    const RunToRunSpread cached = read_calibration_file(cache);
    const std::string stale = calibration_staleness_now(cached);
    state["spread"] = cached.spread;
    state["current"] = stale.empty();
    state["stale"] = stale;
  } else {
    state["current"] = false;
    state["stale"] = "no spread cached for this device";
  }
  return state.dump();
}

struct CalibrateOptions {
  ProbeOptions probe;
  std::string out;
  bool show = false;
  bool json = false;
  GpuOption gpu;
};

}  // namespace

Runner add_calibrate_command(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  auto* cmd = app.add_subcommand(
      "calibrate",
      "Measure how far one run's median time lands from another run's on this device, driver and "
      "machine (A/A runs of a few configurations, each in its own process) and cache it: the spread "
      "that widens every record's time interval (--calibration auto reads it)");
  cmd->add_option("--processes", o->probe.processes, "Probe processes (every pair gives one log ratio per configuration and sub-pass)")
      ->check(CLI::Range(2, 100))
      ->capture_default_str();
  cmd->add_option("--gap", o->probe.gap_seconds, "Seconds between probe processes")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Write the spread to this file instead of the cache");
  cmd->add_flag("--show", o->show, "Print the cached spread of this device and whether it is current; measure nothing");
  cmd->add_flag("--json", o->json,
                "With --show: one JSON object (file, cached, spread, current, stale) for tools that "
                "hand the file to --calibration");
  add_gpu_option(cmd, o->gpu);
  return [o]() {
    export_gpu_option(o->gpu);  // the probe's processes read LDM_GPU
    ContextOptions options = default_context_options();
    options.gpu = gpu_request_from_environment(o->gpu.text());
    auto context = HeadlessContext::create(options);
    const DeviceInfo device = context->device();
    context.reset();
    const std::string cache = calibration_cache_file(device).string();
    if (o->show && o->json) {
      std::cout << cache_state_json(cache) << "\n";
      return 0;
    }
    if (o->show) {
      if (!std::filesystem::is_regular_file(cache)) {
        std::cout << "no run-to-run spread cached for this device (" << cache << ")\n";
        return 0;
      }
      const RunToRunSpread cached = read_calibration_file(cache);
      const std::string stale = calibration_staleness_now(cached);
      std::printf("run-to-run spread: %.4f, %s (%s)\n", cached.spread, stale.empty() ? "current" : ("stale: " + stale).c_str(),
                  cache.c_str());
      return 0;
    }
    const RunToRunSpread spread = probe_and_pool(device, o->probe, std::cerr);
    const std::string path = o->out.empty() ? cache : o->out;
    write_calibration_file(path, spread);
    std::printf("run-to-run spread: %.4f (RMS of %zu log ratios between %zu processes, %.1f s)\n", spread.spread,
                spread.pairs, spread.processes, spread.probe_seconds);
    if (spread.pooled_probes > 1) {
      char load[80];
      if (std::isfinite(spread.busy_cpus))
        std::snprintf(load, sizeof load, "%.2f CPUs busy with other work", spread.busy_cpus);
      else
        std::snprintf(load, sizeof load, "load average %.2f", spread.load_average);
      std::printf("pooled with %zu earlier probes of the last 24 h at this load +- %.1f (%s; this probe alone: %.4f)\n",
                  spread.pooled_probes - 1, kCalibrationMaxLoadChange, load, spread.probes.back().spread);
    }
    std::printf("an interval of one repetition is widened by +-%.1f%% (95%%); written to %s\n",
                100 * (std::exp(1.959964 * spread.spread) - 1), path.c_str());
    // One run's median varies by spread / sqrt 2 (the spread is that of a difference of two).
    const double per_run = spread.spread / std::sqrt(2.0);
    std::printf("ldmbench compare needs about %zu repetitions per side to detect a 10%% change "
                "(%zu for 20%%) at this spread\n",
                repetitions_for_detectable_change(per_run, 0.10, 0.05, 0.8),
                repetitions_for_detectable_change(per_run, 0.20, 0.05, 0.8));
    return 0;
  };
}

}  // namespace ldm::cli
