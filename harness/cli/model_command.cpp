// `ldmbench model RUN... [--out FIT.json]` and `ldmbench model --predict RUN --fit FIT.json`:
// a cost model fitted on the records' work counters, per device, driver and sub-pass
// (time ≈ fixed + Σ cᵢ · counterᵢ, non-negative least squares with cross-validation by
// configuration; docs/guide/model.md). The fitting is the Python script
// scripts/model/ldmbench_model.py (NumPy, SciPy); this command checks the arguments first
// (a missing run or fit, bad folds exit 2 with no Python started), then runs it with the
// record schema, whence the counters' units.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "harness/settings/record_schema.h"
#include "harness/cli/commands.h"
#include "harness/cli/python_tool.h"
#include "harness/util/error.h"
#include "harness/util/process.h"

namespace ldm::cli {
namespace {

namespace fs = std::filesystem;

struct ModelOptions {
  std::vector<std::string> runs, by, subpasses;
  std::string out, predict, fit, device;
  int folds = 5;
  bool no_intercept = false, absolute = false, driver_stats = false;
};

// A RUN argument: a run folder with records.csv or records.json, or such a file.
void check_run(const std::string& option, const std::string& run) {
  const fs::path path(run);
  const std::string what = option.empty() ? run : option + " " + run;
  if (fs::is_directory(path)) {
    if (!fs::is_regular_file(path / "records.csv") && !fs::is_regular_file(path / "records.json"))
      throw UserError(what + ": a folder without records.csv or records.json (expected an ldmbench run folder)");
    return;
  }
  if (!fs::exists(path)) throw UserError(what + ": no such file or folder");
  if (path.extension() != ".csv" && path.extension() != ".json")
    throw UserError(what + ": expected a run folder, a records.csv or a records.json");
}

void check(const ModelOptions& o) {
  if (o.runs.empty() && o.predict.empty())
    throw UserError("give RUN... to fit, or --predict RUN --fit FIT.json");
  if (!o.runs.empty() && !o.fit.empty())
    throw UserError("--fit: the fit to apply comes from RUN... or from --fit FIT.json, not both");
  if (!o.fit.empty() && o.predict.empty()) throw UserError("--fit: only with --predict RUN");
  if (!o.predict.empty() && o.runs.empty() && o.fit.empty())
    throw UserError("--predict: needs --fit FIT.json (a saved fit) or RUN... to fit on");
  if (o.folds < 2) throw UserError("--folds " + std::to_string(o.folds) + ": at least 2");
  for (const std::string& run : o.runs) check_run("", run);
  if (!o.predict.empty()) check_run("--predict", o.predict);
  if (!o.fit.empty() && !fs::is_regular_file(o.fit)) throw UserError("--fit " + o.fit + ": no such file");
  if (!o.out.empty()) {
    if (fs::is_directory(o.out)) throw UserError("--out " + o.out + ": a folder (expected the fit's file, FIT.json)");
    const fs::path parent = fs::absolute(o.out).parent_path();
    if (!fs::is_directory(parent)) throw UserError("--out " + o.out + ": no folder " + parent.string());
  }
}

}  // namespace

Runner add_model_command(CLI::App& app) {
  auto o = std::make_shared<ModelOptions>();
  auto* cmd = app.add_subcommand(
      "model", "A cost model fitted on work counters, per device, driver and sub-pass: time = fixed + "
               "sum of c * counter (non-negative least squares, cross-validated by configuration), its "
               "coefficients in ns per unit, R^2 and held-out error; --predict applies a saved fit");
  cmd->add_option("runs", o->runs, "Run folders (or their records.csv / records.json) to fit on")
      ->expected(0, -1);
  cmd->add_option("--out", o->out, "Save the fit (FIT.json) for --predict");
  cmd->add_option("--predict", o->predict,
                  "Predict this run's times from its work counters (a run of any device: the counters "
                  "are device-independent), beside its measured times where it ran on the fit's device");
  cmd->add_option("--fit", o->fit, "The saved fit --predict applies (else RUN... are fitted first)");
  cmd->add_option("--device", o->device,
                  "--predict: the device whose fits to apply (GL_RENDERER or driver name, or part of it); "
                  "default: the fit's only device");
  cmd->add_option("--folds", o->folds, "Cross-validation folds, by configuration (default 5)");
  cmd->add_option("--by", o->by,
                  "Also fit separately per value of this record column (structure, scene), repeatable");
  cmd->add_option("--subpass", o->subpasses, "Fit only these sub-passes (frame: the whole frame), repeatable");
  cmd->add_flag("--no-intercept", o->no_intercept, "No fixed cost per frame: time is the counters' alone");
  cmd->add_flag("--absolute", o->absolute,
                "Minimise the squared error in ms (default: the squared relative error)");
  cmd->add_flag("--driver-stats", o->driver_stats,
                "Also fit on the driver's pipeline statistics (work_<subpass>_gl_*), which differ between drivers");
  return [o]() {
    check(*o);
    const std::string script = find_tool_script(python_tool("model"));
    const std::string python = find_tool_python(python_tool("model"));
    // The counters' units: this build's record schema, as `ldmbench columns --json`.
    std::string scratch = (fs::temp_directory_path() / "ldmbench-model-XXXXXX").string();
    if (!mkdtemp(scratch.data())) throw UserError("cannot make a temporary folder for the record schema");
    const fs::path columns = fs::path(scratch) / "columns.json";
    {
      std::ofstream file(columns);
      file << columns_json();
      if (!file) throw UserError(columns.string() + ": cannot write the record schema for the model");
    }
    std::vector<std::string> argv = {python, script};
    argv.insert(argv.end(), o->runs.begin(), o->runs.end());
    argv.insert(argv.end(), {"--columns", columns.string(), "--folds", std::to_string(o->folds)});
    if (!o->out.empty()) argv.insert(argv.end(), {"--out", o->out});
    if (!o->predict.empty()) argv.insert(argv.end(), {"--predict", o->predict});
    if (!o->fit.empty()) argv.insert(argv.end(), {"--fit", o->fit});
    if (!o->device.empty()) argv.insert(argv.end(), {"--device", o->device});
    for (const std::string& column : o->by) argv.insert(argv.end(), {"--by", column});
    for (const std::string& subpass : o->subpasses) argv.insert(argv.end(), {"--subpass", subpass});
    if (o->no_intercept) argv.push_back("--no-intercept");
    if (o->absolute) argv.push_back("--absolute");
    if (o->driver_stats) argv.push_back("--driver-stats");
    const ProcessResult result = run_process(argv, /*capture=*/false);
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
    if (!result.started) throw UserError(python + ": cannot run: " + result.output);
    return result.status;
  };
}

}  // namespace ldm::cli
