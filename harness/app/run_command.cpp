#include "harness/app/run_command.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>

#include "harness/app/measure_configuration.h"
#include "harness/app/run_summary.h"
#include "harness/app/sweep_progress.h"
#include "harness/passes/pass.h"
#include "harness/records/journal.h"
#include "harness/records/record.h"
#include "harness/records/run_folder.h"
#include "harness/reference/reference_cache.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/interrupt.h"
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

// Identifies a sweep of `ldmbench run` for resuming: the command's arguments without the
// program path, --out, --overwrite and --redo-failed.
std::vector<std::string> run_key_parts(const std::string& command_line) {
  std::istringstream words(command_line);
  std::vector<std::string> args;
  for (std::string word; words >> word;) args.push_back(word);
  std::vector<std::string> parts;
  for (size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--out") {
      ++i;
      continue;
    }
    if (args[i].rfind("--out=", 0) == 0 || args[i] == "--overwrite" || args[i] == "--redo-failed") continue;
    parts.push_back(args[i]);
  }
  return parts;
}

std::string config_id_of(const Record& r) {
  const RecordValue* id = r.get("config_id");
  return id ? std::get<std::string>(*id) : std::string();
}

std::string status_of(const Record& r) {
  const RecordValue* status = r.get("status");
  return status ? std::get<std::string>(*status) : std::string();
}

}  // namespace

void check_cache_dir(const std::string& cache_dir) {
  std::filesystem::path dir = cache_dir.empty() ? kDefaultReferenceCacheDir : cache_dir;
  std::error_code error;
  for (std::filesystem::path p = dir; !p.empty(); p = p.parent_path()) {
    if (std::filesystem::exists(p, error)) {
      if (!std::filesystem::is_directory(p, error))
        throw UserError("--cache-dir: '" + p.string() + "' is not a folder" +
                        (p == dir ? "" : " (in the cache path '" + dir.string() + "')"));
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
    h.add(scene.content_hash());
  }
  h.add_string(git_commit());
  h.add_string(ldmbench_version());
  return hex64(h.value());
}

int run_benchmark(const RunSettings& settings, const std::string& command_line, std::ostream& log) {
  validate_axes(settings);
  std::map<std::string, Scene> scenes;
  for (const auto& spec : settings.scenes) scenes.emplace(spec, load_scene(spec));
  if (settings.reference.enabled) check_cache_dir(settings.reference.cache_dir);

  ConfigurationRun run;
  for (const auto& config : expand_configurations(settings)) run.configurations.push_back({config, settings});
  run.scenes = &scenes;
  run.out_dir = settings.out_dir;
  run.overwrite = settings.overwrite;
  run.redo_failed = settings.redo_failed;
  run.context = settings.context;
  run.sweep_key = sweep_key(run_key_parts(command_line), scenes);
  return run_configurations(run, command_line, log);
}

int run_configurations(const ConfigurationRun& job, const std::string& command_line, std::ostream& log) {
  const std::string out_dir = job.out_dir.empty()
                                  ? (std::filesystem::path("results") / "runs" /
                                     timestamp("%Y%m%d-%H%M%S")).string()
                                  : job.out_dir;
  const RunFolderPlan plan = plan_run_folder(out_dir, job.sweep_key, job.overwrite);

  auto context = HeadlessContext::create(job.context);
  const DeviceInfo& device = context->device();
  log << "device: " << device.gl_renderer << " (" << device.gl_version << ", EGL "
      << device.egl_platform << ")\n";

  const MeasurementPaths paths{out_dir, (std::filesystem::path(out_dir) / "images").string()};
  prepare_run_folder(out_dir, plan);
  const std::string csv_path = (std::filesystem::path(out_dir) / "records.csv").string();
  const std::string json_path = (std::filesystem::path(out_dir) / "records.json").string();
  RecordJournal journal((std::filesystem::path(out_dir) / kJournalFile).string());
  install_stop_handlers();

  // Finished configurations of an interrupted run of the same sweep are kept, not redone;
  // failed ones are redone when asked (the new record takes the old one's place in the
  // tables; until then, and if the redo is interrupted, the old one stays).
  std::vector<Record> records = latest_per_configuration(plan.previous.records);
  std::set<std::string> finished;
  size_t redone = 0;
  for (const Record& r : records) {
    if (job.redo_failed && status_of(r) == "failed")
      ++redone;
    else
      finished.insert(config_id_of(r));
  }

  Record run;
  run.set("command", command_line);
  run.set("sweep_key", job.sweep_key);
  run.set("started", timestamp("%Y-%m-%dT%H:%M:%S%z"));
  run.set("device", device.gl_renderer);
  run.set("gl_version", device.gl_version);
  run.set("egl_platform", device.egl_platform);
  run.set("git_commit", git_commit());
  run.set("ldmbench_version", ldmbench_version());
  run.set("resumed_records", uint64_t(records.size()));
  for (const auto& [key, value] : job.metadata.fields()) run.put(key, value);
  journal.append_run(run);
  if (!plan.previous.records.empty()) {
    log << "resuming: " << records.size() << " configuration(s) already recorded in "
        << out_dir << "/" << kJournalFile;
    if (redone) log << " (" << redone << " failed one(s) to redo)";
    log << "\n";
    write_records(csv_path, json_path, records, run);  // re-derived: consistent after any kill
  }

  const auto& configurations = job.configurations;
  size_t to_measure = 0;
  for (const auto& planned : configurations) to_measure += finished.count(planned.config.id()) ? 0 : 1;
  SweepProgress progress(to_measure, SweepProgress::stderr_if_terminal());
  int interrupted_by = 0;
  for (size_t i = 0; i < configurations.size() && !interrupted_by; ++i) {
    const Configuration& config = configurations[i].config;
    const RunSettings& settings = configurations[i].settings;
    if (finished.count(config.id())) continue;
    if ((interrupted_by = stop_signal())) break;
    // With the bar on a terminal, the bar shows the configuration in flight and its line is
    // printed whole when it ends; otherwise (logs, pipes) the line starts at once.
    const std::string prefix =
        "[" + std::to_string(i + 1) + "/" + std::to_string(configurations.size()) + "] " + config.id() + " ... ";
    if (progress.active())
      progress.show(config.id());
    else
      log << prefix << std::flush;
    auto begin_line = [&] {
      if (!progress.active()) return;
      progress.erase();
      log << prefix;
    };
    Record record;
    const auto started = std::chrono::steady_clock::now();
    try {
      record = measure_configuration(job.scenes->at(config.scene), config, settings, device, paths);
    } catch (const Interrupted& e) {
      // Abandoned cleanly: no record, no images; a rerun of the same command measures it.
      remove_configuration_images(paths.images_dir, config.id() + "-" + config.pass);
      begin_line();
      log << "abandoned (" << e.what() << ")\n";
      interrupted_by = e.signal();
      break;
    } catch (const std::exception& e) {
      record = Record();
      describe_configuration(record, config, settings, device);
      record.set("status", "failed");
      record.set("status_detail", e.what());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    record.set("wall_seconds", seconds);
    const std::string status = status_of(record);
    begin_line();
    log << status;
    // Medians to 4 significant digits: a progress line, not the record (which keeps all).
    for (const char* subpass : {"build", "frame"})
      if (const RecordValue* ms = record.get(std::string(subpass) + "_ms_median"))
        if (const double* value = std::get_if<double>(ms)) {
          std::ostringstream text;  // leaves the log stream's own precision alone
          text << std::setprecision(4) << *value;
          log << "  " << subpass << " " << text.str() << " ms";
        }
    if (status != "ok") log << "  (" << std::get<std::string>(*record.get("status_detail")) << ")";
    log << "\n" << std::flush;
    journal.append_record(record);  // durable before the tables change
    // A redone configuration takes its failed record's place.
    const auto same = std::find_if(records.begin(), records.end(),
                                   [&](const Record& r) { return config_id_of(r) == config.id(); });
    if (same != records.end())
      *same = std::move(record);
    else
      records.push_back(std::move(record));
    run.set("finished", timestamp("%Y-%m-%dT%H:%M:%S%z"));
    write_records(csv_path, json_path, records, run);
    progress.finished_one();
  }
  progress.erase();
  if (records.empty()) write_records(csv_path, json_path, records, run);

  std::map<std::string, int> outcomes;
  for (const Record& r : records) ++outcomes[status_of(r)];
  log << summary_table(records, kSummaryTableRows);
  log << "records: " << csv_path << " and " << json_path << " (";
  bool first = true;
  for (const auto& [status, count] : outcomes) {
    log << (first ? "" : ", ") << count << " " << status;
    first = false;
  }
  log << ")\n";
  if (interrupted_by) {
    log << "interrupted by signal " << interrupted_by << ": " << records.size() << " of "
        << configurations.size() << " configurations recorded; run the same command again "
        << "to measure the rest\n";
    return kExitInterruptedBase + interrupted_by;
  }
  log << "next: " << job.report_hint << " " << out_dir << "\n";
  const bool all_measured = outcomes["failed"] == 0 && outcomes["invalid"] == 0;
  return all_measured ? kExitOk : kExitSomeFailed;
}

}  // namespace ldm
