#pragma once
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "harness/measuring/calibration.h"
#include "harness/run/exit_codes.h"
#include "harness/settings/run_settings.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

// One configuration to measure and the settings it is measured with (a sweep file may vary
// the image size or frames, which `ldmbench run` holds fixed).
struct PlannedConfiguration {
  Configuration config;
  RunSettings settings;
};

// What run_configurations() measures and where: `ldmbench run` and `ldmbench sweep` both
// end in it (one measurement path).
struct ConfigurationRun {
  std::vector<PlannedConfiguration> configurations;  // in order, ids unique
  const std::map<std::string, Scene>* scenes = nullptr;  // by spec, loaded and checked
  std::string out_dir;  // empty: results/runs/<timestamp>
  bool overwrite = false;
  bool redo_failed = false;  // measure again what the folder holds as failed
  int repetitions = 1;       // of every configuration, round robin (harness/measuring/repetitions.h)
  RepetitionIsolation isolation = RepetitionIsolation::Context;
  // The command's own arguments (after the program), which a child process of
  // --isolation process repeats with --step ID.
  std::vector<std::string> arguments;
  std::string step;  // measure only the next repetition of this configuration, quietly
  ContextOptions context;
  std::string sweep_key;  // identity of the sweep for resuming (records/run_folder.h)
  Record metadata;        // extra fields of the journal's run entries (sweep file, shard)
  std::string report_hint = "ldmbench report";  // the command printed at the end
  CalibrationChoice calibration;  // the run-to-run spread (harness/measuring/calibration.h)
};

// Measures every configuration not already finished in the folder: each record is appended
// to records.jsonl (fsync'd), and records.csv and records.json are re-derived; a
// configuration that throws becomes a "failed" record and the rest go on. Prints a progress
// line per configuration, a progress bar with ETA on a terminal (stderr), and at the end a
// summary table and the report command. Returns the exit status (kExit*).
int run_configurations(const ConfigurationRun& run, const std::string& command_line, std::ostream& log);

// A regular file where the reference cache folder should be is a user error (found up front).
void check_cache_dir(const std::string& cache_dir);
// Identifies a sweep: `parts` (the command's arguments, or a sweep file), every scene's
// content and the ldmbench build.
std::string sweep_key(const std::vector<std::string>& parts, const std::map<std::string, Scene>& scenes);

// Runs the sweep: validates every axis value, loads every scene and checks --out and
// --cache-dir before touching the GPU (so bad input writes nothing), then measures each
// configuration: its record is appended to records.jsonl (fsync'd), and records.csv and
// records.json are re-derived from the records. A configuration that throws becomes a
// "failed" record and the sweep goes on. An --out folder holding the same sweep resumes it
// (records/run_folder.h). `command_line` is stored in the run metadata.
// `arguments` are the command's own (argv after the program), for resuming and for child
// processes; `command_line` the whole of it, for the records.
int run_benchmark(const RunSettings& settings, const std::string& command_line,
                  const std::vector<std::string>& arguments, std::ostream& log);

// The arguments of a command line that identify a sweep of `ldmbench run` (without the
// program, --out, --overwrite, --redo-failed, --step and --interleaved-session).
std::vector<std::string> run_key_parts(const std::vector<std::string>& arguments);

// How many repetitions of each configuration the run folder holds: a configuration with a
// record (finished, failed included) counts `repetitions`; one in progress, those journaled.
std::map<std::string, size_t> recorded_repetitions(const std::string& out_dir, size_t repetitions);

// One line per configuration, "index<TAB>id<TAB>WxH<TAB>F+W frames", then a count: what
// --dry-run prints (and `ldmbench interleave` reads back from each build).
void list_configurations(const std::vector<PlannedConfiguration>& configurations, std::ostream& out);

// The checks run_benchmark makes on every axis value before any GPU work (structures and
// passes with their parameters, --param owners, the budget option); throws UserError.
// Shared with `ldmbench view` and `ldmbench sweep` (each combination of a sweep file).
void validate_axes(const RunSettings& settings);

}  // namespace ldm
