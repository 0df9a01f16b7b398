// `ldmbench sweep FILE`: the configurations of a sweep file (harness/run/sweep_plan.h),
// measured by the same run_configurations() as `ldmbench run`, resumable, sharded; or, with
// --memory-plan, only their memory, from the census (harness/run/memory_plan.h).
#include <filesystem>
#include <iostream>
#include <memory>

#include "harness/run/memory_plan.h"
#include "harness/run/sweep_plan.h"
#include "harness/cli/commands.h"
#include "harness/gl/egl_context.h"
#include "harness/settings/run_setting_options.h"
#include "harness/util/error.h"
#include "harness/util/files.h"

namespace ldm::cli {
namespace {

struct SweepOptions {
  std::string file, out_dir, shard = "0/1", cache_dir, platform = "auto";
  std::string step, interleaved_session, calibration;
  // --repetitions and --isolation, declared with the run-wide settings they override.
  RunSettingOverrides timing;
  bool overwrite = false, redo_failed = false, dry_run = false, gl_debug = false;
  GpuOption gpu;
  bool memory_plan = false;
};

constexpr const char* kMemoryPlanFile = "memory-plan.csv";

void list_configurations(const SweepPlan& plan, const Shard& shard, std::ostream& out) {
  const std::vector<size_t> members = shard_members(plan, shard);
  for (size_t k : members) {
    const auto& [config, settings] = plan.configurations[k];
    out << k << "\t" << config.id() << "\t" << settings.width << "x" << settings.height << "\t"
        << settings.frames << "+" << settings.warmup << " frames\n";
  }
  out << plan.path << ": " << plan.configurations.size() << " configurations ("
      << plan.combinations << " combinations of the axes)";
  if (shard.count > 1) out << "; shard " << shard.text() << ": " << members.size();
  out << "\n";
}

// --out for a memory plan: a folder (made if missing), never a file. Checked before any GPU
// work, so that bad input writes nothing.
void check_memory_plan_folder(const std::string& out_dir) {
  if (out_dir.empty()) return;
  std::error_code error;
  if (std::filesystem::exists(out_dir, error) && !std::filesystem::is_directory(out_dir, error))
    throw UserError("--out " + out_dir + ": not a folder");
}

// Plans every configuration of the shard in order: one progress line each on stderr, the
// CSV on stdout and, with --out, in <out>/memory-plan.csv (written whole or not at all).
// Exit status as a sweep's: 3 when some configuration is refused (a sweep's "failed").
int write_memory_plan(const SweepPlan& plan, const Shard& shard, const SweepOptions& o) {
  check_memory_plan_folder(o.out_dir);
  ContextOptions context = default_context_options();
  context.platform = parse_egl_platform(o.platform);
  context.debug_output = o.gl_debug;
  context.gpu = gpu_request_from_environment(o.gpu.text());
  auto gl = HeadlessContext::create(context);
  MemoryPlanner planner(plan.scenes);
  const std::vector<size_t> members = shard_members(plan, shard);
  std::vector<MemoryPlanRow> rows;
  bool any_refused = false;
  for (size_t i = 0; i < members.size(); ++i) {
    const MemoryPlanRow row = planner.plan(plan.configurations[members[i]]);
    std::cerr << "[" << i + 1 << "/" << members.size() << "] " << row.config.id() << ": "
              << row.status;
    if (row.status == "planned") std::cerr << ", " << row.bytes_allocated << " bytes";
    else std::cerr << " (" << row.status_detail << ")";
    std::cerr << "\n";
    any_refused |= row.status == "refused";
    rows.push_back(row);
  }
  const std::string csv = memory_plan_csv(rows);
  std::cout << csv << std::flush;
  if (!o.out_dir.empty()) {
    std::filesystem::create_directories(o.out_dir);
    const std::string path = (std::filesystem::path(o.out_dir) / kMemoryPlanFile).string();
    write_text_atomically(path, csv);
    std::cerr << "memory plan: " << path << "\n";
  }
  return any_refused ? kExitSomeFailed : kExitOk;
}

}  // namespace

Runner add_sweep_command(CLI::App& app, const std::string& command_line,
                         const std::vector<std::string>& arguments) {
  auto o = std::make_shared<SweepOptions>();
  auto* sweep = app.add_subcommand(
      "sweep", "Measure the configurations of a sweep file (docs/guide/sweeps.md): resumable, "
               "shardable (--shard), through the same path as `ldmbench run`");
  sweep->add_option("FILE", o->file, "Sweep file (JSON)")->required();
  sweep->add_option("--out", o->out_dir,
                    "Output folder (default: results/runs/<timestamp>). A folder holding the same "
                    "sweep (and shard) is resumed: finished configurations are skipped");
  sweep->add_option("--shard", o->shard,
                    "Run only slice INDEX of COUNT (0-based, e.g. $SLURM_ARRAY_TASK_ID/8): "
                    "interleaved, balanced along every axis (docs/guide/sweeps.md); join slices "
                    "with `ldmbench merge`")
      ->capture_default_str();
  auto* redo_failed = sweep->add_flag("--redo-failed", o->redo_failed,
                  "Measure again the configurations the folder holds as failed (else kept)");
  auto* overwrite = sweep->add_flag("--overwrite", o->overwrite,
                  "Replace the records and images in --out when they belong to another sweep");
  auto* dry_run = sweep->add_flag("--dry-run", o->dry_run,
                                  "List the configurations (index, id, image size, frames) and write nothing");
  auto* memory_plan = sweep->add_flag(
           "--memory-plan", o->memory_plan,
           "Measure nothing: per configuration, the bytes each buffer allocates, from the fragment "
           "census and the structure's prepare() (no build), as CSV on stdout and, with --out, in "
           "DIR/memory-plan.csv: bytes_allocated as the record's, buffers, k and lossy (fixed "
           "arrays), status planned or refused (exit 3, "
           "as a sweep's failed configurations) (docs/guide/sweeps.md#memory-plan)")
      ->excludes(dry_run);
  sweep->add_option("--cache-dir", o->cache_dir,
                    "Reference cache folder (default: $XDG_CACHE_HOME/ldmbench/references, else "
                    "~/.cache/ldmbench/references)");
  sweep->add_option("--egl-platform", o->platform, "EGL platform: auto, device, surfaceless")
      ->check(CLI::IsMember({"auto", "device", "surfaceless"}))
      ->capture_default_str();
  add_gpu_option(sweep, o->gpu);
  sweep->add_flag("--gl-debug", o->gl_debug, "Print OpenGL debug messages");
  add_run_setting_overrides(sweep, o->timing, {"timing.repetitions", "timing.isolation"}, "the file");
  auto* step = sweep->add_option("--step", o->step,
                    "Measure only the next repetition of each of these configuration ids "
                    "(ID[,ID...]) and stop (the children of --isolation process and `ldmbench "
                    "interleave`)");
  sweep->add_option("--calibration", o->calibration,
                    "The run-to-run spread that widens every time interval: auto, skip or FILE, as "
                    "for `ldmbench run` (default: LDM_CALIBRATION, else auto)");
  auto* session = sweep->add_option("--interleaved-session", o->interleaved_session,
                    "The `ldmbench interleave` session this run belongs to (recorded)");
  // A memory plan measures nothing: options about measuring or resuming would be ignored.
  for (CLI::Option* measuring : {redo_failed, overwrite, step, session}) memory_plan->excludes(measuring);
  for (CLI::Option* measuring : o->timing.options) memory_plan->excludes(measuring);

  return [o, command_line, arguments]() {
    const Shard shard = parse_shard(o->shard);
    const auto gpu = gpu_request_from_environment(o->gpu.text());  // a bad value: before any work
    RunSettings base;
    base.reference.cache_dir = o->cache_dir;
    const SweepPlan plan = plan_sweep(o->file, base);
    for (const auto& warning : plan.spec.warnings) std::cerr << "ldmbench: warning: " << warning << "\n";
    for (const auto& [spec, scene] : plan.scenes)
      for (const auto& warning : scene.warnings) std::cerr << "ldmbench: warning: " << warning << "\n";
    if (o->dry_run) {
      list_configurations(plan, shard, std::cout);
      return kExitOk;
    }
    if (o->memory_plan) return write_memory_plan(plan, shard, *o);
    bool references = false;
    for (const auto& planned : plan.configurations) references |= planned.settings.reference.enabled;
    if (references) check_cache_dir(o->cache_dir);

    ConfigurationRun run;
    for (size_t k : shard_members(plan, shard)) run.configurations.push_back(plan.configurations[k]);
    run.scenes = &plan.scenes;
    run.out_dir = o->out_dir;
    run.overwrite = o->overwrite;
    run.redo_failed = o->redo_failed;
    RunSettings timing = plan.configurations.front().settings;  // the file's, then the options'
    apply_run_setting_overrides(o->timing, timing);
    run.repetitions = timing.repetitions;
    run.isolation = timing.isolation;
    run.arguments = arguments;
    run.step = o->step;
    run.calibration = parse_calibration_choice(o->calibration, std::getenv("LDM_CALIBRATION"));
    if (!o->interleaved_session.empty()) run.metadata.set("interleaved_session", o->interleaved_session);
    run.context = default_context_options();
    run.context.platform = parse_egl_platform(o->platform);
    run.context.debug_output = o->gl_debug;
    run.context.gpu = gpu;
    // Repetitions and isolation change what is measured: another sweep for resuming.
    run.sweep_key = sweep_key({"sweep", plan.sweep_hash, "shard", shard.text(), "repetitions",
                               std::to_string(run.repetitions), "isolation",
                               repetition_isolation_name(run.isolation)},
                              plan.scenes);
    run.metadata.set("sweep_file", o->file);
    run.metadata.set("sweep_hash", plan.sweep_hash);
    run.metadata.set("shard", shard.text());
    run.metadata.set("sweep_configurations", uint64_t(plan.configurations.size()));
    return run_configurations(run, command_line, std::cout);
  };
}

}  // namespace ldm::cli
