#include "harness/run/run_command.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>

#include "harness/measuring/measure_configuration.h"
#include "harness/settings/record_schema.h"
#include "harness/measuring/repetitions.h"
#include "harness/measuring/timing_columns.h"
#include "harness/stats/intervals.h"
#include "harness/run/run_summary.h"
#include "harness/run/sweep_progress.h"
#include "harness/passes/pass.h"
#include "harness/records/harness_columns.h"
#include "harness/records/journal.h"
#include "harness/records/output_folder.h"
#include "harness/records/record.h"
#include "harness/records/run_folder.h"
#include "harness/records/run_lock.h"
#include "harness/records/run_records_writer.h"
#include "harness/reference/reference_cache.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/interrupt.h"
#include "harness/util/process.h"
#include "harness/util/text.h"
#include "harness/util/version.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {
namespace {

std::string timestamp(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::ostringstream out;
  out << std::put_time(&local, format);
  return out.str();
}

}  // namespace

// Everything the user can get wrong is checked here, before any GPU work or file output.
void validate_axes(const RunSettings& s) {
  for (const auto& config : expand_configurations(s)) {
    if (config.structure != kNoStructure)
      make_structure(config.structure, StructureParams(config.params, "--param " + config.structure));
    make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
  }
  for (const auto& [structure, params] : s.structure_params) {
    (void)params;
    // A pass's own parameters go the same way: --param hbao:steps=16.
    if (std::find(s.structures.begin(), s.structures.end(), structure) == s.structures.end() &&
        std::find(s.passes.begin(), s.passes.end(), structure) == s.passes.end())
      throw UserError("--param " + structure + ":...: structure '" + structure +
                      "' is not among --structure or --pass");
  }
  const bool budget = std::find(s.sizing.begin(), s.sizing.end(), SizingPolicy::Budget) != s.sizing.end();
  if (budget && s.sizing_budget_mib <= 0)
    throw UserError("--sizing budget needs --sizing-budget-mib <MiB>");
  if (!budget && s.sizing_budget_mib > 0)
    throw UserError("--sizing-budget-mib is only used by --sizing budget");
}

namespace {

std::string config_id_of(const Record& r) {
  const RecordValue* id = r.get("config_id");
  return id ? std::get<std::string>(*id) : std::string();
}

std::string status_of(const Record& r) {
  const RecordValue* status = r.get("status");
  return status ? std::get<std::string>(*status) : std::string();
}

}  // namespace

std::vector<std::string> run_key_parts(const std::vector<std::string>& arguments) {
  // How intervals are widened is not what is measured: --calibration keeps the sweep.
  static const std::set<std::string> with_value = {"--out", "--step", "--interleaved-session", "--calibration"};
  static const std::set<std::string> flags = {"--overwrite", "--redo-failed"};
  std::vector<std::string> parts;
  for (size_t i = 0; i < arguments.size(); ++i) {
    const std::string& a = arguments[i];
    if (with_value.count(a)) {
      ++i;
      continue;
    }
    const size_t equals = a.find('=');
    if (flags.count(a) || (equals != std::string::npos && with_value.count(a.substr(0, equals)))) continue;
    parts.push_back(a);
  }
  return parts;
}

void list_configurations(const std::vector<PlannedConfiguration>& configurations, std::ostream& out) {
  for (size_t k = 0; k < configurations.size(); ++k) {
    const auto& [config, settings] = configurations[k];
    out << k << "\t" << config.id() << "\t" << settings.width << "x" << settings.height << "\t"
        << settings.frames << "+" << settings.warmup << " frames\n";
  }
}

void check_cache_dir(const std::string& cache_dir) {
  std::filesystem::path dir = reference_cache_dir(cache_dir);
  std::error_code error;
  for (std::filesystem::path p = dir; !p.empty(); p = p.parent_path()) {
    if (std::filesystem::exists(p, error)) {
      if (!std::filesystem::is_directory(p, error))
        throw UserError("--cache-dir: '" + p.string() + "' is not a folder" +
                        (p == dir ? "" : " (in the cache path '" + dir.string() + "')"));
      // Found now, not when the first reference is stored (an I/O error mid-run).
      if (::access(p.c_str(), W_OK | X_OK) != 0)
        throw UserError("--cache-dir: '" + p.string() + "' is not writable" +
                        (p == dir ? "" : " (in the cache path '" + dir.string() + "')") + ": " +
                        errno_text(errno));
      return;
    }
    if (p == p.parent_path()) break;
  }
}

std::string sweep_key(const std::vector<std::string>& parts, const std::map<std::string, Scene>& scenes) {
  Fnv1a h;
  for (const auto& part : parts) h.add_string(part);
  for (const auto& [spec, scene] : scenes) {
    h.add_string(spec);
    h.add(scene.identity_hash());  // every field of the loaded scene and its source's bytes
  }
  h.add_string(git_commit());
  h.add_string(ldmbench_version());
  return hex64(h.value());
}

int run_benchmark(const RunSettings& settings, const std::string& command_line,
                  const std::vector<std::string>& arguments, std::ostream& log) {
  validate_axes(settings);
  std::map<std::string, Scene> scenes;
  for (const auto& spec : settings.scenes) {
    const Scene& scene = scenes.emplace(spec, load_scene(spec)).first->second;
    for (const auto& warning : scene.warnings) std::cerr << "ldmbench: warning: " << warning << "\n";
  }
  if (settings.reference.enabled) check_cache_dir(settings.reference.cache_dir);

  ConfigurationRun run;
  for (const auto& config : expand_configurations(settings)) run.configurations.push_back({config, settings});
  run.scenes = &scenes;
  run.out_dir = settings.out_dir;
  run.overwrite = settings.overwrite;
  run.redo_failed = settings.redo_failed;
  run.repetitions = settings.repetitions;
  run.isolation = settings.isolation;
  run.arguments = arguments;
  run.step = settings.step;
  run.context = settings.context;
  run.calibration = parse_calibration_choice(settings.calibration, std::getenv("LDM_CALIBRATION"));
  if (!settings.interleaved_session.empty()) run.metadata.set("interleaved_session", settings.interleaved_session);
  if (settings.dry_run) {
    list_configurations(run.configurations, log);
    log << run.configurations.size() << " configurations\n";
    return kExitOk;
  }
  run.sweep_key = sweep_key(run_key_parts(arguments), scenes);
  return run_configurations(run, command_line, log);
}

namespace {

double number_of(const Record& r, const std::string& key) {
  const RecordValue* v = r.get(key);
  if (!v) return -1;
  if (const double* d = std::get_if<double>(v)) return *d;
  if (const int64_t* i = std::get_if<int64_t>(v)) return double(*i);
  return -1;
}

// "  build 12.3 ±1.2% ms  frame 45.6 ±0.8% ms": the progress line's times with their
// intervals, to the digits the intervals support (the record keeps every digit).
std::string timed_sums(const Record& r) {
  std::string out;
  for (const char* subpass : {"build", "frame"}) {
    const std::string name = subpass;
    const double median = number_of(r, name + "_ms_median");
    if (median < 0) continue;
    out += "  ";
    out += name;
    out += ' ';
    out += format_time_with_interval(median, number_of(r, name + "_ms_ci_low"),
                                     number_of(r, name + "_ms_ci_high"));
    out += " ms";
  }
  return out;
}

int64_t repetition_of(const Record& r) {
  const RecordValue* v = r.get("repetition");
  const int64_t* i = v ? std::get_if<int64_t>(v) : nullptr;
  return i ? *i : -1;
}

// The repetitions a folder holds of each unfinished configuration: for each, the journaled
// repetitions 0, 1, ... in turn (the latest of each index), as far as their samples files
// exist; a gap or a missing file ends the prefix (the rest is measured again). For a failed
// configuration measured again, only the repetitions journaled after its failed record.
std::map<std::string, std::vector<Record>> repetitions_in_progress(
    const JournalContents& journal, const std::set<std::string>& finished,
    const std::set<std::string>& redone, const std::string& out_dir) {
  std::map<std::string, size_t> record_line;  // the latest record of each configuration
  for (size_t i = 0; i < journal.records.size(); ++i)
    record_line[config_id_of(journal.records[i])] = journal.record_lines[i];
  std::map<std::string, std::map<int64_t, Record>> by_index;
  for (size_t i = 0; i < journal.repetitions.size(); ++i) {
    const Record& r = journal.repetitions[i];
    const std::string id = config_id_of(r);
    if (finished.count(id) || repetition_of(r) < 0) continue;
    if (redone.count(id) && journal.repetition_lines[i] < record_line[id]) continue;
    by_index[id][repetition_of(r)] = r;
  }
  std::map<std::string, std::vector<Record>> out;
  for (auto& [id, reps] : by_index) {
    std::vector<Record>& kept = out[id];
    for (int64_t j = 0; reps.count(j); ++j) {
      const RecordValue* file = reps[j].get("frame_samples_csv");
      const std::string* name = file ? std::get_if<std::string>(file) : nullptr;
      std::error_code error;
      if (!name || !std::filesystem::is_regular_file(std::filesystem::path(out_dir) / *name, error)) break;
      kept.push_back(reps[j]);
    }
  }
  return out;
}

// Removes files a configuration wrote (it failed or was abandoned): no orphan stays.
void remove_files(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    std::error_code error;
    std::filesystem::remove(path, error);
  }
}

// Removes the samples files of repetitions that are combined into a record (or abandoned
// with it).
void remove_repetition_samples(const std::vector<Record>& repetitions, const std::string& out_dir) {
  for (const Record& r : repetitions) {
    const RecordValue* file = r.get("frame_samples_csv");
    const std::string* name = file ? std::get_if<std::string>(file) : nullptr;
    std::error_code error;
    if (name) std::filesystem::remove(std::filesystem::path(out_dir) / *name, error);
  }
}

}  // namespace

namespace {

// What a run folder holds already, as far as this sweep goes: the records (one per
// configuration), which of them count as finished (failed ones do not when redone), and
// the repetitions journaled of unfinished configurations.
struct FolderProgress {
  std::vector<Record> records;
  std::set<std::string> finished, redone;
  std::map<std::string, std::vector<Record>> partial;
  size_t partial_repetitions = 0;
};

FolderProgress folder_progress(const JournalContents& journal, bool redo_failed, const std::string& out_dir) {
  FolderProgress p;
  // Finished configurations of an interrupted run of the same sweep are kept, not redone;
  // failed ones are redone when asked (the new record takes the old one's place in the
  // tables; until then, and if the redo is interrupted, the old one stays).
  p.records = latest_per_configuration(journal.records);
  for (const Record& r : p.records) {
    if (redo_failed && status_of(r) == "failed")
      p.redone.insert(config_id_of(r));
    else
      p.finished.insert(config_id_of(r));
  }
  // Repetitions of unfinished configurations a killed run journaled are kept too.
  p.partial = repetitions_in_progress(journal, p.finished, p.redone, out_dir);
  for (const auto& [id, reps] : p.partial) p.partial_repetitions += reps.size();
  return p;
}

std::string default_out_dir(const std::string& out_dir) {
  return out_dir.empty() ? (std::filesystem::path("results") / "runs" / timestamp("%Y%m%d-%H%M%S")).string()
                         : out_dir;
}

// What the configurations this process measured cost beside their measured frames.
struct HarnessCost {
  size_t measured = 0;     // records measured here (repetitions count one each)
  double timed_ms = 0;     // their measured frames' timed work (frames_timed_ms)
  double verify_ms = 0, verify_warmup_ms = 0;  // their build checks: measured frames, warm-up
  void add(const Record& r) {
    if (!r.get("frames_timed_ms")) return;  // failed: nothing was timed
    ++measured;
    timed_ms += number_of(r, "frames_timed_ms");
    verify_ms += number_of(r, "verify_ms");
    verify_warmup_ms += number_of(r, "verify_warmup_ms");
  }
};

// "harness cost: 7.41 s wall for 2.96 s of measured frames (2.5x); build checks 1.2% of that
// in the measured frames, 2.1% more in warm-up": how much of the process's time went into the
// frames the records are made of (issue 21).
std::string harness_cost_line(const HarnessCost& cost) {
  if (cost.measured == 0 || cost.timed_ms <= 0) return "";
  const double wall = seconds_since_process_start(), timed = cost.timed_ms / 1000.0;
  std::ostringstream out;
  out << "harness cost: " << four_digits(wall) << " s wall for " << four_digits(timed)
      << " s of measured frames (" << four_digits(wall / timed) << "x); build checks "
      << four_digits(100.0 * cost.verify_ms / cost.timed_ms) << "% of that in the measured frames, "
      << four_digits(100.0 * cost.verify_warmup_ms / cost.timed_ms) << "% more in warm-up\n";
  return out.str();
}

// The end of a run: the summary table, the records' paths and outcome counts, what the run
// cost beside its measured frames, the next command; the exit status from the outcomes.
int finish_run(const std::vector<Record>& records, size_t configurations, int interrupted_by,
               const std::string& out_dir, const std::string& report_hint, std::ostream& log,
               const HarnessCost& cost = {}) {
  const std::string csv_path = (std::filesystem::path(out_dir) / "records.csv").string();
  const std::string json_path = (std::filesystem::path(out_dir) / "records.json").string();
  std::map<std::string, int> outcomes;
  for (const Record& r : records) ++outcomes[status_of(r)];
  log << summary_table(records, kSummaryTableRows);
  log << "records: " << csv_path << " and " << json_path << " (";
  bool first = true;
  for (const auto& [status, count] : outcomes) {
    log << (first ? "" : ", ") << count << " " << status;
    first = false;
  }
  // An ok record with a flag (degenerate, time target missed, ...) is not a plain ok.
  const auto flagged = std::count_if(records.begin(), records.end(), [](const Record& r) {
    return status_of(r) == "ok" && !status_flags(r).empty();
  });
  if (flagged > 0) log << "; " << flagged << " ok with flags, see the status column";
  log << ")\n";
  log << harness_cost_line(cost);
  if (interrupted_by) {
    log << "interrupted by signal " << interrupted_by << ": " << records.size() << " of "
        << configurations << " configurations recorded; run the same command again "
        << "to measure the rest\n";
    return kExitInterruptedBase + interrupted_by;
  }
  log << "next: " << report_hint << " " << out_dir << "\n";
  const bool all_measured = outcomes["failed"] == 0 && outcomes["invalid"] == 0;
  return all_measured ? kExitOk : kExitSomeFailed;
}

// --isolation process: this process measures nothing; each repetition is a child,
// `<this program> <the same arguments> --out DIR --step ID`, round robin as in one process.
// The folder is planned (and an --overwrite carried out) here, once; the children resume it.
int drive_repetition_processes(const ConfigurationRun& job, const std::string& command_line,
                               const std::string& out_dir, std::ostream& log) {
  const RunFolderPlan plan = plan_run_folder(out_dir, job.sweep_key, job.overwrite);
  prepare_run_folder(out_dir, plan);
  {
    // The folder is this sweep's from now on: its children resume it.
    RecordJournal journal((std::filesystem::path(out_dir) / kJournalFile).string());
    Record run;
    run.set("command", command_line);
    run.set("sweep_key", job.sweep_key);
    run.set("started", timestamp("%Y-%m-%dT%H:%M:%S%z"));
    run.set("repetitions", uint64_t(std::max(1, job.repetitions)));
    run.set("isolation", repetition_isolation_name(job.isolation));
    for (const auto& [key, value] : job.metadata.fields()) run.put(key, value);
    journal.append_run(run);
  }
  install_stop_handlers();
  const std::string program = executable_path();
  if (program.empty()) throw UserError("--isolation process: cannot find this program's path (/proc/self/exe)");
  // The spread is resolved once, here, and every child reads the same one.
  const ResolvedCalibration calibration = [&] {
    auto context = HeadlessContext::create(job.context);
    return resolve_calibration(job.calibration, context->device(), log);
  }();
  std::vector<std::string> child = {program};
  bool has_out = false;
  for (size_t i = 0; i < job.arguments.size(); ++i) {
    const std::string& a = job.arguments[i];
    if (a == "--overwrite") continue;  // done here, once
    if (a == "--calibration") {
      ++i;
      continue;
    }
    if (a.rfind("--calibration=", 0) == 0) continue;
    if (a == "--out" || a.rfind("--out=", 0) == 0) has_out = true;
    child.push_back(a);
  }
  if (!has_out) {
    child.push_back("--out");
    child.push_back(out_dir);
  }
  child.push_back("--calibration");
  child.push_back(calibration.file.empty() ? "skip" : calibration.file);
  const std::string journal_path = (std::filesystem::path(out_dir) / kJournalFile).string();
  int interrupted_by = 0;
  // Each child measures the next repetition of every configuration that needs one (one
  // process start-up per round, not per configuration and round: a sweep of C
  // configurations and K repetitions starts K children, not C x K). No two repetitions of a
  // configuration share a process, which is what the isolation is for; the configurations
  // of one round share one, as in one process's round robin.
  std::map<std::string, size_t> last_counts;
  for (size_t child_number = 0; !interrupted_by; ++child_number) {
    const FolderProgress progress = folder_progress(read_journal(journal_path), job.redo_failed, out_dir);
    std::vector<std::string> ids;
    std::map<std::string, size_t> counts;
    for (const auto& planned : job.configurations) {
      const std::string id = planned.config.id();
      if (progress.finished.count(id)) continue;
      const auto partial = progress.partial.find(id);
      counts[id] = partial == progress.partial.end() ? 0 : partial->second.size();
      ids.push_back(id);  // a repetition to measure, or all journaled and to be combined
    }
    if (ids.empty()) break;
    // A child that recorded nothing would be started again for ever (it cannot, short of a
    // crash, which stops the run below; this is the guard).
    if (child_number > 0 && counts == last_counts) {
      log << "ldmbench: the last child measured no configuration; stopping\n";
      return kExitFailure;
    }
    last_counts = counts;
    if ((interrupted_by = stop_signal())) break;
    std::vector<std::string> argv = child;
    argv.push_back("--step");
    argv.push_back(joined(ids, ","));
    log << std::flush;
    const ProcessResult result = run_process(argv, false, true);
    if (!result.started) throw UserError("--isolation process: cannot start " + program + ": " + result.output);
    if (result.status > kExitInterruptedBase) interrupted_by = result.status - kExitInterruptedBase;
    else if (result.status != kExitOk && result.status != kExitSomeFailed) {
      log << "ldmbench: the child measuring repetition " << (child_number + 1) << " of " << ids.size()
          << " configuration(s) exited " << result.status << "\n";
      if (result.status == kExitUsage || result.status == kExitIoError) return result.status;
      return kExitFailure;
    }
  }
  if (!interrupted_by) interrupted_by = stop_signal();
  const FolderProgress done = folder_progress(read_journal(journal_path), false, out_dir);
  return finish_run(done.records, job.configurations.size(), interrupted_by, out_dir, job.report_hint, log);
}

}  // namespace

std::map<std::string, size_t> recorded_repetitions(const std::string& out_dir, size_t repetitions) {
  const FolderProgress p =
      folder_progress(read_journal((std::filesystem::path(out_dir) / kJournalFile).string()), false, out_dir);
  std::map<std::string, size_t> out;
  for (const auto& id : p.finished) out[id] = repetitions;
  for (const auto& [id, reps] : p.partial) out[id] = reps.size();
  return out;
}

namespace {

// Two configurations of one id would be measured twice and journaled as one (-N 4,4).
void check_distinct_ids(const std::vector<PlannedConfiguration>& configurations) {
  std::map<std::string, size_t> seen;
  for (size_t k = 0; k < configurations.size(); ++k) {
    const auto [it, fresh] = seen.emplace(configurations[k].config.id(), k);
    if (!fresh)
      throw UserError("configurations " + std::to_string(it->second + 1) + " and " + std::to_string(k + 1) +
                      " are the same, " + it->first + " (a value given twice?)");
  }
}

// The run entry of the journal: what measured, on what, how.
Record run_entry(const ConfigurationRun& job, const std::string& command_line, const DeviceInfo& device,
                 size_t repetitions, const FolderProgress& state) {
  Record run;
  run.set("command", command_line);
  run.set("sweep_key", job.sweep_key);
  run.set("started", timestamp("%Y-%m-%dT%H:%M:%S%z"));
  run.set("device", device.gl_renderer);
  run.set("gl_version", device.gl_version);
  run.set("device_id", device.device_id);
  run.set("gl_driver", device.gl_driver);
  run.set("egl_platform", device.egl_platform);
  run.set("git_commit", git_commit());
  run.set("ldmbench_version", ldmbench_version());
  run.set("schema_columns", declared_columns_text());
  run.set("schema_always_written", always_written_columns_text());
  run.set("repetitions", uint64_t(repetitions));
  run.set("isolation", repetition_isolation_name(job.isolation));
  run.set("resumed_records", uint64_t(state.records.size()));
  if (state.partial_repetitions) run.set("resumed_repetitions", uint64_t(state.partial_repetitions));
  for (const auto& [key, value] : job.metadata.fields()) run.put(key, value);
  return run;
}

// "resuming: ..." of a folder that holds records or repetitions already.
void print_resume(const FolderProgress& state, const std::string& out_dir, std::ostream& detail) {
  detail << "resuming: " << state.records.size() << " configuration(s) already recorded in " << out_dir << "/"
         << kJournalFile;
  if (state.partial_repetitions) detail << ", " << state.partial_repetitions << " repetition(s) of unfinished ones";
  if (!state.redone.empty()) detail << " (" << state.redone.size() << " failed one(s) to redo)";
  detail << "\n";
}

// "[3/12] ID (repetition 2/5) ... ": the start of a configuration's progress line.
std::string progress_prefix(size_t i, size_t count, const std::string& id, const Repetition& repetition) {
  std::ostringstream prefix;
  prefix << "[" << i + 1 << "/" << count << "] " << id;
  if (repetition.count > 1) prefix << " (repetition " << repetition.index + 1 << "/" << repetition.count << ")";
  prefix << " ... ";
  return prefix.str();
}

// The record of a configuration that failed: it keeps no file, its record says why, and
// names none (the images of its first repetition neither, when a later one fails).
Record failed_record(const PlannedConfiguration& planned, const DeviceInfo& device, const Repetition& repetition,
                     const std::exception& e) {
  Record record = measurement_record();
  describe_configuration(record, planned.config, planned.settings, device);
  record.set(columns::kStatus, "failed");
  std::ostringstream why;
  if (repetition.count > 1) why << "repetition " << repetition.index + 1 << ": ";
  why << e.what();
  record.set(columns::kStatusDetail, why.str());
  return record;
}

// The configuration ids of a --step (comma-separated: ids never hold a comma).
std::set<std::string> step_ids(const std::string& step) {
  std::set<std::string> ids;
  std::string id;
  std::istringstream in(step);
  while (std::getline(in, id, ','))
    if (!id.empty()) ids.insert(id);
  return ids;
}

// The measuring of one process (`ldmbench run`, or one --step of it): round robin over the
// configurations, each repetition recorded through the run's RunRecordsWriter, the
// repetitions of a configuration combined into its record after the last.
class ConfigurationLoop {
 public:
  ConfigurationLoop(const ConfigurationRun& job, const std::string& out_dir, std::ostream& log)
      : job_(job), out_dir_(out_dir), log_(log), repetitions_(size_t(std::max(1, job.repetitions))),
        stepping_(!job.step.empty()), steps_(step_ids(job.step)), detail_(stepping_ ? discarded_ : log) {}

  int run(const std::string& command_line);

 private:
  // What a measured repetition came to.
  struct Outcome {
    Record record;
    bool failed = false;
    std::vector<std::string> written;  // every file this configuration wrote
  };

  void open_context_and_calibration();
  void start_records(const RunFolderPlan& plan, const std::string& command_line);
  size_t repetitions_to_measure();
  // Finished, or (in a step) not one of the step's, or measured by this step already.
  bool skipped(const std::string& id) const {
    return writer_->finished(id) || (stepping_ && (!steps_.count(id) || stepped_ids_.count(id)));
  }
  // A step ends when each of its configurations is finished or measured once here.
  bool step_done() const {
    return stepping_ && std::all_of(steps_.begin(), steps_.end(), [&](const std::string& id) {
             return writer_->finished(id) || stepped_ids_.count(id);
           });
  }
  [[noreturn]] void stop_for_io(const IoError& e, const std::string& id, const std::vector<std::string>& written);
  void combine(const std::string& id, const std::vector<Record>& reps, const RunSettings& settings);
  void combine_journaled_repetitions();
  void measure_round(size_t round);
  // Measures repetition `round` of configuration i; false when the run is to stop.
  bool measure_one(size_t i, size_t round, bool& context_used);
  // Measures it; nullopt when a signal abandoned it (interrupted_by_ set).
  std::optional<Outcome> measure(const PlannedConfiguration& planned, const Repetition& repetition,
                                 const std::function<void()>& begin_line);
  void record_outcome(const PlannedConfiguration& planned, const Repetition& repetition, Outcome outcome);

  const ConfigurationRun& job_;
  const std::string out_dir_;
  std::ostream& log_;
  const size_t repetitions_;
  // A step (one repetition of each of its configurations, in a child) says only what it
  // measured: its parent has the rest.
  const bool stepping_;
  const std::set<std::string> steps_;
  std::ostringstream discarded_;
  std::ostream& detail_;

  std::unique_ptr<HeadlessContext> context_;
  DeviceInfo device_;
  ResolvedCalibration calibration_;
  const RunToRunSpread* spread_ = nullptr;
  MeasurementPaths paths_;
  FolderProgress state_;
  std::optional<RunRecordsWriter> writer_;
  std::optional<SweepProgress> progress_;
  HarnessCost cost_;
  int interrupted_by_ = 0;
  std::set<std::string> stepped_ids_;  // what this step measured: one repetition each
};

void ConfigurationLoop::open_context_and_calibration() {
  context_ = HeadlessContext::create(job_.context);
  device_ = context_->device();
  detail_ << "device: " << device_.gl_renderer << " (" << device_.gl_version << ", EGL " << device_.egl_platform
          << "; " << device_.device_choice << ")\n";
  // The run-to-run spread that widens every record's interval (harness/measuring/calibration.h).
  calibration_ = resolve_calibration(job_.calibration, device_, detail_);
  spread_ = calibration_.spread ? &*calibration_.spread : nullptr;
  detail_ << "time intervals: " << (spread_ ? "widened by the run-to-run spread, " : "") << calibration_.source
          << "\n";
}

void ConfigurationLoop::start_records(const RunFolderPlan& plan, const std::string& command_line) {
  paths_ = MeasurementPaths{out_dir_, (std::filesystem::path(out_dir_) / "images").string()};
  prepare_run_folder(out_dir_, plan);
  state_ = folder_progress(plan.previous, job_.redo_failed, out_dir_);
  const Record run = run_entry(job_, command_line, device_, repetitions_, state_);
  writer_.emplace(out_dir_, state_.records, state_.finished, [] { return timestamp("%Y-%m-%dT%H:%M:%S%z"); });
  install_stop_handlers();
  writer_->start_run(run);
  if (!plan.previous.records.empty() || state_.partial_repetitions) {
    print_resume(state_, out_dir_, detail_);
    writer_->write_tables();  // re-derived: consistent after any kill
  }
}

size_t ConfigurationLoop::repetitions_to_measure() {
  size_t to_measure = 0;
  for (const auto& planned : job_.configurations)
    if (!writer_->finished(planned.config.id()))
      to_measure += repetitions_ - std::min(repetitions_, state_.partial[planned.config.id()].size());
  return to_measure;
}

// An I/O failure (a full disk) stops the run: the configuration in flight leaves nothing
// (its files removed, no record; a resume measures it again), what is recorded stays
// consistent, and the error says so (exit kExitIoError).
void ConfigurationLoop::stop_for_io(const IoError& e, const std::string& id, const std::vector<std::string>& written) {
  const bool kept = writer_->kept_in_journal();
  if (!kept) remove_files(written);
  progress_->erase();
  std::string what = std::string(e.what()) + "\n  the run stopped";
  if (!id.empty())
    what += kept ? "; " + id + " is in the journal, and the tables follow it at the next run"
                 : "; " + id + " was abandoned (none of its files kept)";
  throw IoError(what + "; " + std::to_string(writer_->records().size()) + " of " +
                    std::to_string(job_.configurations.size()) + " configurations are recorded in " + out_dir_ +
                    "; once the cause is fixed, run the same command again to measure the rest",
                e.error_number());
}

// One record of all of a configuration's repetitions, their frames in one samples file.
void ConfigurationLoop::combine(const std::string& id, const std::vector<Record>& reps, const RunSettings& settings) {
  std::vector<std::string> combined_written;
  try {
    Record combined = combine_repetitions(reps, out_dir_, settings.precision);
    widen_time_intervals(combined, spread_, calibration_.source,
                         settings.isolation == RepetitionIsolation::Process ? RepetitionProcesses::Separate
                                                                            : RepetitionProcesses::Shared);
    const OutputFolder samples(out_dir_, (std::filesystem::path(out_dir_) / "samples").string(), &combined_written);
    combined.set(columns::kFrameSamplesCsv,
                 samples.write_text(samples_file_name(id, {}), combined_samples_csv(reps, out_dir_)));
    log_ << "    " << id << ": " << reps.size() << " repetitions, " << status_of(combined) << timed_sums(combined)
         << "\n";
    writer_->finish(std::move(combined));
  } catch (const IoError& e) {
    // Its repetitions stay journaled, with their samples: a resume combines them (unless
    // the combined record stayed in the journal, which replaces them).
    if (writer_->kept_in_journal()) remove_repetition_samples(reps, out_dir_);
    stop_for_io(e, id, combined_written);
  }
  remove_repetition_samples(reps, out_dir_);
}

// A run stopped (a full disk) after a configuration's last repetition was journaled but
// before their combined record was: every repetition is there, so combine them now.
void ConfigurationLoop::combine_journaled_repetitions() {
  for (const auto& [config, settings] : job_.configurations) {
    const std::string id = config.id();
    if (skipped(id)) continue;
    const auto found = state_.partial.find(id);
    if (found != state_.partial.end() && found->second.size() >= repetitions_) combine(id, found->second, settings);
  }
}

std::optional<ConfigurationLoop::Outcome> ConfigurationLoop::measure(const PlannedConfiguration& planned,
                                                                     const Repetition& repetition,
                                                                     const std::function<void()>& begin_line) {
  const Configuration& config = planned.config;
  const std::string id = config.id();
  Outcome outcome;
  const MeasurementPaths config_paths{paths_.out_dir, paths_.images_dir, &outcome.written};
  const auto started = std::chrono::steady_clock::now();
  // Frames past the point the run-to-run spread makes pointless are not measured
  // (frame_precision_floor(), harness/measure/run_to_run_spread.h).
  RunSettings settings = planned.settings;
  settings.precision.spread_floor = frame_precision_floor(spread_, normal_quantile(0.5 + kTimeConfidence / 2));
  try {
    outcome.record = measure_configuration(job_.scenes->at(config.scene), config, settings, device_,
                                           config_paths, repetition);
    if (repetitions_ == 1)
      widen_time_intervals(outcome.record, spread_, calibration_.source, RepetitionProcesses::Separate);
  } catch (const Interrupted& e) {
    // Abandoned cleanly: no record, no images; a rerun of the same command measures it.
    remove_files(outcome.written);
    if (repetition.index == 0) remove_configuration_images(paths_.images_dir, id + "-" + config.pass);
    begin_line();
    log_ << "abandoned (" << e.what() << ")\n";
    interrupted_by_ = e.signal();
    return std::nullopt;
  } catch (const IoError& e) {
    begin_line();
    log_ << "abandoned (I/O error)\n";
    stop_for_io(e, id, outcome.written);
  } catch (const std::exception& e) {
    remove_files(outcome.written);
    remove_configuration_images(paths_.images_dir, id + "-" + config.pass);
    outcome.record = failed_record(planned, device_, repetition, e);
    outcome.failed = true;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  outcome.record.set(columns::kWallSeconds, seconds);
  return outcome;
}

// Journals a measured repetition: the configuration's record when it has one repetition or
// failed, else a repetition, combined with the others after the last.
void ConfigurationLoop::record_outcome(const PlannedConfiguration& planned, const Repetition& repetition,
                                       Outcome outcome) {
  const std::string id = planned.config.id();
  std::vector<Record>& reps = state_.partial[id];
  try {
    if (repetitions_ == 1 || outcome.failed) {
      writer_->finish(outcome.record);
      if (outcome.failed) {
        remove_repetition_samples(reps, out_dir_);
        progress_->skip(repetitions_ - 1 - repetition.index);  // its later repetitions
      }
      return;
    }
    writer_->append_repetition(outcome.record);
  } catch (const IoError& e) {
    // A failed record that counts replaces its repetitions: their samples go.
    if (outcome.failed && writer_->kept_in_journal()) remove_repetition_samples(reps, out_dir_);
    stop_for_io(e, id, outcome.written);
  }
  reps.push_back(std::move(outcome.record));
  if (reps.size() < repetitions_) return;
  combine(id, reps, planned.settings);  // the last repetition
}

bool ConfigurationLoop::measure_one(size_t i, size_t round, bool& context_used) {
  const PlannedConfiguration& planned = job_.configurations[i];
  const std::string id = planned.config.id();
  if (skipped(id)) return true;
  const std::vector<Record>& reps = state_.partial[id];
  if (reps.size() > round) return true;  // this round's repetition is already journaled
  if ((interrupted_by_ = stop_signal())) return false;
  if (!context_used) {
    context_.reset();  // the old context goes before the new one is made current
    context_ = HeadlessContext::create(job_.context);
    context_used = true;
  }
  const Repetition repetition{reps.size(), repetitions_};
  if (stepping_) stepped_ids_.insert(id);
  // With the bar on a terminal, the bar shows the configuration in flight and its line
  // is printed whole when it ends; otherwise (logs, pipes) the line starts at once.
  const std::string prefix = progress_prefix(i, job_.configurations.size(), id, repetition);
  if (progress_->active())
    progress_->show(id);
  else
    log_ << prefix << std::flush;
  auto begin_line = [&] {
    if (!progress_->active()) return;
    progress_->erase();
    log_ << prefix;
  };
  std::optional<Outcome> outcome = measure(planned, repetition, begin_line);
  if (!outcome) return false;
  cost_.add(outcome->record);
  const std::string status = status_of(outcome->record);
  begin_line();
  log_ << status_cell(outcome->record) << timed_sums(outcome->record);
  if (status != "ok") log_ << "  (" << std::get<std::string>(*outcome->record.get("status_detail")) << ")";
  log_ << "\n" << std::flush;
  progress_->finished_one();
  record_outcome(planned, repetition, std::move(*outcome));
  return true;
}

// Round robin: repetition 1 of every configuration, then repetition 2, ... Each round
// after the first runs in a fresh GL context, so that no repetition shares another's.
void ConfigurationLoop::measure_round(size_t round) {
  bool context_used = round == 0 || stepping_;  // a step's process is fresh already
  for (size_t i = 0; i < job_.configurations.size() && !interrupted_by_; ++i)
    if (!measure_one(i, round, context_used)) break;
}

int ConfigurationLoop::run(const std::string& command_line) {
  const RunFolderPlan plan = plan_run_folder(out_dir_, job_.sweep_key, job_.overwrite);
  if (stepping_ && steps_.empty()) throw UserError("--step '" + job_.step + "': no configuration id");
  for (const std::string& id : steps_)
    if (std::none_of(job_.configurations.begin(), job_.configurations.end(),
                     [&](const PlannedConfiguration& p) { return p.config.id() == id; }))
      throw UserError("--step " + id + ": no such configuration in this sweep");
  open_context_and_calibration();
  start_records(plan, command_line);
  progress_.emplace(repetitions_to_measure(), SweepProgress::stderr_if_terminal());
  combine_journaled_repetitions();
  for (size_t round = 0; round < repetitions_ && !interrupted_by_ && !step_done(); ++round) measure_round(round);
  progress_->erase();
  try {
    writer_->write_tables_if_empty();
  } catch (const IoError& e) {
    stop_for_io(e, "", {});
  }
  if (stepping_) return interrupted_by_ ? kExitInterruptedBase + interrupted_by_ : kExitOk;
  return finish_run(writer_->records(), job_.configurations.size(), interrupted_by_, out_dir_, job_.report_hint,
                    log_, cost_);
}

}  // namespace

int run_configurations(const ConfigurationRun& job, const std::string& command_line, std::ostream& log) {
  const std::string out_dir = default_out_dir(job.out_dir);
  check_distinct_ids(job.configurations);
  // One writer per folder, from before it is read to the end (records/run_lock.h).
  const RunFolderLock lock(out_dir, command_line, log);
  if (job.isolation == RepetitionIsolation::Process && job.step.empty())
    return drive_repetition_processes(job, command_line, out_dir, log);
  ConfigurationLoop loop(job, out_dir, log);
  return loop.run(command_line);
}

}  // namespace ldm
