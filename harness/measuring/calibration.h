#pragma once
// Where a run's run-to-run spread (harness/measure/run_to_run_spread.h) comes from:
//   --calibration auto   (default) the cached probe of this device, driver, host and build
//                        (under $XDG_CACHE_HOME/ldmbench, else ~/.cache/ldmbench), probed
//                        again first when it is missing, older than a day, or measured at
//                        a load average more than 0.5 from today's;
//   --calibration skip   none: intervals stay within-run, and every record says so
//                        (time_calibration); what tests and CI use for speed;
//   --calibration FILE   a spread saved by `ldmbench calibrate --out FILE`.
// LDM_CALIBRATION=auto|skip|FILE does the same for batch use; the option wins.
//
// The probe (`ldmbench calibrate`): ProbeOptions::processes runs of a fixed set of
// configurations of different cost (cornell, three structures, N 8 and 32, 9 frames each),
// each a separate `ldmbench run` process, back to back; every pair of processes gives one log
// ratio per configuration and sub-pass (build, pass, frame).
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "harness/gl/egl_context.h"
#include "harness/measure/run_to_run_spread.h"

namespace ldm {

struct CalibrationChoice {
  enum class Kind { Auto, Skip, File } kind = Kind::Auto;
  std::string file;    // Kind::File
  std::string origin;  // "--calibration", "LDM_CALIBRATION" or "default", for messages
};

// The choice from the option's value ("" when not given) and the environment variable's
// (null when unset). Throws UserError naming the origin when a file does not exist.
CalibrationChoice parse_calibration_choice(const std::string& option_value, const char* environment_value);

struct ProbeOptions {
  int processes = 4;
  double gap_seconds = 0;  // pause between processes
  std::string program;     // the ldmbench binary (default: this one)
};

// Runs the probe: `processes` separate ldmbench runs, their records read back. Throws
// UserError when a probe process fails.
RunToRunSpread run_calibration_probe(const DeviceInfo& device, const ProbeOptions& options, std::ostream& log);

// Runs the probe and pools it with the earlier probes of the day in this device's cache
// entry at about its load (pool_with_earlier_probes, harness/measure/run_to_run_spread.h).
RunToRunSpread probe_and_pool(const DeviceInfo& device, const ProbeOptions& options, std::ostream& log);

// The cache folder and this device's entry in it.
std::filesystem::path calibration_cache_dir();
std::filesystem::path calibration_cache_file(const DeviceInfo& device);

// Reads a saved spread (throws UserError naming the file on bad input), writes one
// atomically (throws IoError).
RunToRunSpread read_calibration_file(const std::string& path);

// Why the cached spread must be probed again now, or "" (calibration_staleness() with the
// load average and the CPUs other processes keep busy, read now: a quarter second).
std::string calibration_staleness_now(const RunToRunSpread& cached);
void write_calibration_file(const std::string& path, const RunToRunSpread& spread);

struct ResolvedCalibration {
  std::optional<RunToRunSpread> spread;  // none: skipped
  std::string source;                    // the record's time_calibration
  std::string file;                      // the file it was read from or saved to, if any
};

// Resolves the choice for `device`: skip, a file, or the cache (probing first where it is
// stale, and saying why on `log`).
ResolvedCalibration resolve_calibration(const CalibrationChoice& choice, const DeviceInfo& device,
                                        std::ostream& log);

}  // namespace ldm
