#pragma once
// `ldmbench compare BASE NEW`: what changed between two runs, configuration by configuration.
// Configurations are matched by identity (config_id and device; a configuration found only
// on another device is still matched, but its times are not compared). Per configuration:
//   time      each chosen sub-pass's per-frame samples (the record's frame_samples_csv) under the
//             Mann-Whitney U test; FAST/SLOW need significance AND a minimum relative change
//             of the median (nvbench's rule), SAME is a change below that minimum, UNSURE a
//             large change the samples cannot confirm. Refused across devices or timers.
//   memory    bytes_allocated and bytes_used, exact.
//   accuracy  the MSE change against the reference's noise floor (ref_noise_mse): a change
//             smaller than the noise the reference itself carries is no change.
//   status    ok -> lossy -> invalid -> failed is a worsening; a configuration of BASE that
//             NEW lacks is one too.
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
  double alpha = 0.05;            // significance level of the U test
  double min_time_change = 0.05;  // relative change of the median FAST/SLOW needs
  double memory_tolerance = 0;    // relative growth of bytes allowed before MORE
  double noise_factor = 1;        // MSE change allowed, in multiples of ref_noise_mse
  std::set<std::string> ignored_params;  // structure parameters left out of the identity
};

struct TimeChange {
  std::string subpass;
  size_t base_samples = 0, new_samples = 0;
  double base_median = 0, new_median = 0, relative_change = 0;
  double p_value = -1;  // -1: not tested
  std::string verdict;  // FAST, SLOW, SAME, UNSURE
  std::string warning;  // e.g. too few samples
};

struct ConfigChange {
  std::string identity, config_id, device;
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

  bool time_regression() const;
  bool memory_regression() const { return memory_verdict == "MORE"; }
  bool accuracy_regression() const { return accuracy_verdict == "WORSE"; }
};

struct RunComparison {
  std::vector<ConfigChange> matched;   // BASE order; includes those missing from NEW
  std::vector<std::string> added;      // identities only in NEW
  std::vector<std::string> warnings;   // run-level (different commits, devices, ...)
};

RunComparison compare_runs(const RunRecords& base, const RunRecords& next,
                           const CompareThresholds& thresholds);

// The regression kinds --fail-on accepts.
const std::vector<std::string>& regression_kinds();
// How many configurations regress in `kind` (one of regression_kinds()).
size_t count_regressions(const RunComparison& comparison, const std::string& kind);

std::string comparison_table(const RunComparison& comparison);
nlohmann::ordered_json comparison_json(const RunComparison& comparison,
                                       const CompareThresholds& thresholds);

}  // namespace ldm
