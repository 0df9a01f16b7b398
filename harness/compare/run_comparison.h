#pragma once
// `ldmbench compare BASE NEW`: what changed between two runs, configuration by configuration.
// Configurations are matched by identity (config_id and device; a configuration found only
// on another device is still matched, but its times are not compared). Per configuration:
//   time      each chosen sub-pass, judged on the level that carries the variance
//             (harness/stats/time_tests.h): the repetitions' medians (Welch's t on their
//             logs; paired t when both runs come from one interleaved session), or, for a
//             run of one repetition, its frames' median plus an assumed process-to-process
//             spread (the frames of one process are not independent of its offset). Every
//             p value is Holm-corrected over all the time tests of the comparison, and each
//             test reports its minimum detectable change (MDE) at alpha / tests and the
//             chosen power. FAST/SLOW need a corrected p < alpha and a change of at least
//             max(--min-time-change, MDE); a change below the MDE is SAME ("could not detect
//             < x%"); a change above both that the test cannot confirm is UNSURE. Refused
//             across devices or timers.
//   device    each record's driver (gl_driver, or for records from before it, derived from
//             device, gl_vendor, gl_version) and device (GL_RENDERER): a configuration whose
//             two records ran on different drivers or device models is a cross-driver or
//             cross-device comparison, shown as such, whose differences are not regressions.
//   memory    bytes_allocated and bytes_used, exact.
//   accuracy  the MSE change against the reference's noise floor (ref_noise_mse): a change
//             smaller than the noise the reference itself carries is no change.
//   status    ok -> lossy -> invalid -> failed is a worsening; a configuration of BASE that
//             NEW lacks is one too.
//   work      every work_* counter both records carry (harness/measure/work_counters.h):
//             one the schema declares deterministic exactly (any increase is MORE), an
//             arrival-dependent one within --work-tolerance. Device-independent, so it is
//             what a CI machine without a GPU can guard performance by.
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ldm {

struct RunRecords {
  std::string path;  // the records.json read
  std::string dir;   // its folder: frame_samples_csv paths are relative to it
  nlohmann::json run;
  std::vector<nlohmann::json> records;
};

// A run folder (holding records.json) or a records.json file. Throws UserError naming the
// file for anything else.
RunRecords load_run_records(const std::string& folder_or_file);

struct CompareThresholds {
  std::vector<std::string> time_subpasses = {"build", "frame"};
  bool compare_time = true;  // false: times are not compared at all (the CI guard)
  // Family-wise: the chance of any false FAST/SLOW among all the time tests (Holm).
  double alpha = 0.05;
  double power = 0.8;             // of the minimum detectable change
  double min_time_change = 0.05;  // relative change of interest: smaller ones are SAME
  // Assumed relative standard deviation between two processes' medians of the same work,
  // for a run of one repetition (which cannot show it). Measured on the development machine
  // (docs/timing.md, "Comparing"); a run with repetitions uses its own instead.
  // Without --process-spread, the records' own calibration (time_run_to_run_spread / sqrt 2:
  // the spread of one run's median, from `ldmbench calibrate`) is used where they carry one.
  double process_spread = kDefaultProcessSpread;
  bool process_spread_given = false;
  double memory_tolerance = 0;    // relative growth of bytes allowed before MORE
  double noise_factor = 1;        // MSE change allowed, in multiples of ref_noise_mse
  // Relative growth allowed of a work counter that depends on arrival order (deterministic
  // ones: none). 5 %: above the spread of PSPPSLL's insertion walks between runs on zink.
  double work_tolerance = 0.05;
  std::set<std::string> ignored_params;  // structure parameters left out of the identity
  static constexpr double kDefaultProcessSpread = 0.10;
};

struct TimeChange {
  std::string subpass;
  size_t base_repetitions = 0, new_repetitions = 0;
  size_t base_samples = 0, new_samples = 0;  // frames, over every repetition
  double base_median = 0, new_median = 0;
  double relative_change = 0;       // the test's estimate of new / base - 1
  double change_low = 0, change_high = 0;  // its (1 - alpha) interval, uncorrected
  std::string method;               // welch_log_t, paired_log_t, assumed_spread_z
  double p_value = -1;              // -1: not tested
  double p_adjusted = -1;           // Holm over every time test of the comparison
  double minimum_detectable = -1;   // relative; inf when nothing was detectable
  std::string verdict;              // FAST, SLOW, SAME, UNSURE
  std::string warning;              // e.g. a single repetition
  double se = 0, df = 0;            // of the test (log scale), for the MDE
  // The process-to-process spread (log standard deviation of one run's median) the test
  // rests on: measured from the repetitions, or assumed (--process-spread or the records'
  // calibration) for a side of one; and where it came from.
  double process_spread = -1;
  std::string spread_source;
};

// Repetitions per side a comparison needs to detect `target` (relative, 0.1 = 10 %) at
// two-sided level alpha with `power`, when one run's log median varies by `spread`:
// 2 ((z_{1-alpha/2} + z_power) spread / log(1 + target))^2, rounded up, at least 2.
size_t repetitions_for_detectable_change(double spread, double target, double alpha, double power);
// One work counter of a configuration in both runs.
struct WorkChange {
  std::string column;
  double base = 0, next = 0;
  bool deterministic = true;  // the schema's flag: compared exactly
  std::string verdict;        // MORE, LESS, SAME
  double relative_change() const { return base != 0 ? next / base - 1 : (next != 0 ? INFINITY : 0); }
};

struct ConfigChange {
  std::string identity, config_id, device;
  std::string base_driver, new_driver;  // gl_driver of each side ("" when not in NEW)
  // "cross-driver", "cross-device" (same driver, another GPU model), or "" (the same device,
  // or another GPU of its model): a cross comparison has verdicts but no regressions.
  std::string cross;
  std::string base_status, new_status;  // new_status "missing": not in NEW
  std::vector<TimeChange> times;
  std::string time_note;  // why times were not compared
  // memory: -1 where a record lacks the column
  double base_allocated = -1, new_allocated = -1, base_used = -1, new_used = -1;
  std::string memory_verdict;  // MORE, LESS, SAME, or "" (not compared)
  // accuracy
  double base_mse = -1, new_mse = -1, noise_mse = -1, base_mssim = -1, new_mssim = -1;
  std::string accuracy_verdict;  // WORSE, BETTER, SAME, or ""
  bool status_worse = false;
  // work: the counters both records carry, and those only one does (renamed or new ones:
  // reported, not judged)
  std::vector<WorkChange> work;
  std::vector<std::string> work_only_in_base, work_only_in_new;
  std::string work_verdict;  // MORE (any counter), LESS (none more, some less), SAME, or ""

  bool time_regression() const;
  bool memory_regression() const { return cross.empty() && memory_verdict == "MORE"; }
  bool accuracy_regression() const { return cross.empty() && accuracy_verdict == "WORSE"; }
  bool status_regression() const { return cross.empty() && status_worse; }
  bool work_regression() const { return cross.empty() && work_verdict == "MORE"; }
};

// A parameter whose --ignore-param would pair configurations of BASE missing from NEW with
// configurations only in NEW (two runs of one sweep at two values of it): found by pairing
// them with it left out, so the suggestion is known to work.
struct PairingHint {
  std::string param;  // a structure parameter's key, or n_views, r_ldm
  size_t paired = 0;  // how many of the missing configurations it pairs
  size_t missing = 0; // of how many
};

struct RunComparison {
  std::vector<ConfigChange> matched;   // BASE order; includes those missing from NEW
  std::vector<std::string> added;      // identities only in NEW
  std::vector<PairingHint> pairing_hints;  // best first; empty when nothing is missing
  std::vector<std::string> warnings;   // run-level (different commits, devices, ...)
  size_t time_tests = 0;               // how many the Holm correction spans
  bool paired = false;                 // both runs from one interleaved session
};

// A record's driver: its gl_driver, else (a record from before the column) the name
// gl_driver_name() gives its device, gl_vendor and gl_version.
std::string record_driver(const nlohmann::json& record);

RunComparison compare_runs(const RunRecords& base, const RunRecords& next,
                           const CompareThresholds& thresholds);

// The regression kinds --fail-on accepts.
const std::vector<std::string>& regression_kinds();
// How many configurations regress in `kind` (one of regression_kinds()).
size_t count_regressions(const RunComparison& comparison, const std::string& kind);

std::string comparison_table(const RunComparison& comparison);
// One time change as the table shows it: "frame +3.1% SAME (could not detect < 12%)".
std::string describe_time_change(const TimeChange& change);
// A configuration's work verdict as the table shows it: "SAME (41 counters)", or the
// counters that grew: "MORE work_ao_entries_read_total +12% (247446 -> 277135), ...".
std::string describe_work_change(const ConfigChange& change);
// A relative change as a percentage ("12%", "3.1%"; inf: "any change").
std::string percent_text(double relative);
nlohmann::ordered_json comparison_json(const RunComparison& comparison,
                                       const CompareThresholds& thresholds);

}  // namespace ldm
