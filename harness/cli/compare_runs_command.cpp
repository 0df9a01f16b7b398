// `ldmbench compare BASE NEW`: regression tracking between two run folders
// (harness/compare/run_comparison.h); exit 1 only for the regression kinds of --fail-on.
#include <iostream>
#include <memory>
#include <algorithm>
#include <sstream>

#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/compare/run_comparison.h"
#include "harness/util/error.h"

namespace ldm::cli {
namespace {

struct CompareRunsOptions {
  std::string base, next, fail_on;
  std::vector<std::string> ignored_params;
  CompareThresholds thresholds;
  bool json = false;
};

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) items.push_back(item);
  return items;
}

std::vector<std::string> fail_on_kinds(const std::string& text) {
  std::vector<std::string> kinds;
  if (text.empty() || text == "none") return kinds;
  for (const std::string& kind : comma_list(text)) {
    const auto& known = regression_kinds();
    if (std::find(known.begin(), known.end(), kind) == known.end())
      throw UserError("--fail-on: unknown regression kind '" + kind +
                      "' (expected a comma list of time, memory, accuracy, status, or none)");
    kinds.push_back(kind);
  }
  return kinds;
}

}  // namespace

Runner add_compare_runs_command(CLI::App& app) {
  auto o = std::make_shared<CompareRunsOptions>();
  auto* cmd = app.add_subcommand(
      "compare", "Compare two runs configuration by configuration: time (on the repetitions' "
                 "medians, Holm-corrected, with the minimum detectable change), memory, accuracy "
                 "against the reference noise, status");
  cmd->add_option("base", o->base, "The baseline: a run folder or its records.json")->required();
  cmd->add_option("new", o->next, "The run to judge: a run folder or its records.json")->required();
  cmd->add_option("--fail-on", o->fail_on,
                  "Exit 1 when a configuration regresses in one of these kinds: a comma list "
                  "of time, memory, accuracy, status, work (or none)")
      ->capture_default_str();
  cmd->add_option("--time-subpasses", o->thresholds.time_subpasses,
                  "Sub-passes whose per-frame times are compared (from the frame_samples_csv files)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--alpha", o->thresholds.alpha,
                  "Family-wise significance level of the time tests: Holm's correction over "
                  "every configuration and sub-pass keeps the chance of any false FAST/SLOW "
                  "below it")
      ->check(CLI::Range(1e-9, 0.5))
      ->capture_default_str();
  cmd->add_option("--power", o->thresholds.power,
                  "Power at which each test's minimum detectable change is reported")
      ->check(CLI::Range(0.5, 0.999))
      ->capture_default_str();
  // A tolerance: a non-negative number, its default shown.
  auto tolerance = [cmd](const std::string& name, double& value, const std::string& description) {
    cmd->add_option(name, value, description)->check(CLI::NonNegativeNumber)->capture_default_str();
  };
  tolerance("--min-time-change", o->thresholds.min_time_change,
            "Relative time change of interest (0.05: 5%): FAST or SLOW need at least this and the "
            "test's minimum detectable change");
  auto* spread = cmd->add_option("--process-spread", o->thresholds.process_spread,
                  "Assumed relative standard deviation of one process's median, for a run measured "
                  "with one repetition (which cannot show it); default: the records' calibration "
                  "(time_run_to_run_spread / sqrt 2, `ldmbench calibrate`), else this")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  tolerance("--memory-tolerance", o->thresholds.memory_tolerance,
            "Relative growth of bytes_allocated/bytes_used allowed (0: exact)");
  tolerance("--work-tolerance", o->thresholds.work_tolerance,
            "Relative growth allowed of a work counter that depends on arrival order (insertion "
            "walks, retries); deterministic counters are compared exactly");
  tolerance("--noise-factor", o->thresholds.noise_factor,
            "MSE growth allowed, in multiples of the reference's ref_noise_mse");
  cmd->add_option("--ignore-param", o->ignored_params,
                  "Leave this structure parameter (or n_views, r_ldm) out of the identity, to "
                  "compare two values of it as one configuration (repeatable)");
  cmd->add_flag("!--no-time", o->thresholds.compare_time,
                "Compare no times (memory, accuracy and status only): what the CI guard does, "
                "since a CI machine's times say nothing about a change");
  cmd->add_flag("--json", o->json, "Print the comparison as JSON instead of a table");
  return [o, spread]() {
    const std::vector<std::string> fail_on = fail_on_kinds(o->fail_on);
    CompareThresholds thresholds = o->thresholds;
    thresholds.process_spread_given = spread->count() > 0;
    thresholds.ignored_params.insert(o->ignored_params.begin(), o->ignored_params.end());
    const RunRecords base = load_run_records(o->base);
    const RunRecords next = load_run_records(o->next);
    const RunComparison comparison = compare_runs(base, next, thresholds);
    if (o->json)
      std::cout << comparison_json(comparison, thresholds).dump(2) << "\n";
    else
      std::cout << comparison_table(comparison);
    size_t failing = 0;
    for (const std::string& kind : fail_on) failing += count_regressions(comparison, kind);
    if (failing) {
      std::cerr << "ldmbench compare: regressions in --fail-on " << o->fail_on << "\n";
      return 1;
    }
    return kExitOk;
  };
}

}  // namespace ldm::cli
