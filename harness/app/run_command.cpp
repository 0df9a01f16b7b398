#include "harness/app/run_command.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>

#include "harness/app/measure_configuration.h"
#include "harness/passes/pass.h"
#include "harness/records/record.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
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

// Everything the user can get wrong is checked here, before any GPU work or file output.
void validate_axes(const RunSettings& s) {
  for (const auto& config : expand_configurations(s)) {
    make_structure(config.structure, StructureParams(config.params, "--param " + config.structure));
    make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
  }
  for (const auto& [structure, params] : s.structure_params) {
    (void)params;
    if (std::find(s.structures.begin(), s.structures.end(), structure) == s.structures.end())
      throw UserError("--param " + structure + ":...: structure '" + structure +
                      "' is not among --structure");
  }
}

}  // namespace

int run_benchmark(const RunSettings& settings, const std::string& command_line, std::ostream& log) {
  validate_axes(settings);
  std::map<std::string, Scene> scenes;
  for (const auto& spec : settings.scenes) scenes.emplace(spec, load_scene(spec));

  auto context = HeadlessContext::create(settings.context);
  const DeviceInfo& device = context->device();
  log << "device: " << device.gl_renderer << " (" << device.gl_version << ", EGL "
      << device.egl_platform << ")\n";

  const std::string out_dir = settings.out_dir.empty()
                                  ? (std::filesystem::path("results") / "runs" /
                                     timestamp("%Y%m%d-%H%M%S")).string()
                                  : settings.out_dir;
  const MeasurementPaths paths{out_dir, (std::filesystem::path(out_dir) / "images").string()};
  std::error_code error;
  std::filesystem::create_directories(paths.images_dir, error);
  if (error) throw UserError("--out: cannot create '" + paths.images_dir + "': " + error.message());
  const std::string csv_path = (std::filesystem::path(out_dir) / "records.csv").string();
  const std::string json_path = (std::filesystem::path(out_dir) / "records.json").string();

  Record run;
  run.set("command", command_line);
  run.set("started", timestamp("%Y-%m-%dT%H:%M:%S%z"));
  run.set("device", device.gl_renderer);
  run.set("gl_version", device.gl_version);
  run.set("egl_platform", device.egl_platform);
  run.set("git_commit", git_commit());
  run.set("ldmbench_version", ldmbench_version());

  const auto configurations = expand_configurations(settings);
  std::vector<Record> records;
  std::map<std::string, int> outcomes;
  for (size_t i = 0; i < configurations.size(); ++i) {
    const Configuration& config = configurations[i];
    log << "[" << i + 1 << "/" << configurations.size() << "] " << config.id() << " ... "
        << std::flush;
    Record record;
    const auto started = std::chrono::steady_clock::now();
    try {
      record = measure_configuration(scenes.at(config.scene), config, settings, device, paths);
    } catch (const std::exception& e) {
      record = Record();
      describe_configuration(record, config, settings, device);
      record.set("status", "failed");
      record.set("status_detail", e.what());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    record.set("wall_seconds", seconds);
    const std::string status = std::get<std::string>(*record.get("status"));
    ++outcomes[status];
    log << status;
    if (const RecordValue* build = record.get("build_ms_median"))
      log << "  build " << format_csv_value(*build) << " ms";
    if (const RecordValue* ao = record.get("ao_ms_median"))
      log << "  ao " << format_csv_value(*ao) << " ms";
    if (status != "ok") log << "  (" << std::get<std::string>(*record.get("status_detail")) << ")";
    log << "\n";
    records.push_back(std::move(record));
    run.set("finished", timestamp("%Y-%m-%dT%H:%M:%S%z"));
    write_records(csv_path, json_path, records, run);
  }

  log << "records: " << csv_path << " and " << json_path << " (";
  bool first = true;
  for (const auto& [status, count] : outcomes) {
    log << (first ? "" : ", ") << count << " " << status;
    first = false;
  }
  log << ")\n";
  const bool all_measured = outcomes["failed"] == 0 && outcomes["invalid"] == 0;
  return all_measured ? kExitOk : kExitSomeFailed;
}

}  // namespace ldm
