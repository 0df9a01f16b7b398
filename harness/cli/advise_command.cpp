// `ldmbench advise --scene S [--pass ao|indirect] [--budget-ms T] [--budget-mib M]
// [--max-error E | --min-mssim Q] [--structures ...] [--space FILE] --out DIR`: the
// configuration of a space that meets the budgets with the least error (or the fastest
// within the error bound), found by an adaptive search and verified at a normal run's
// precision (docs/guide/advise.md). The search is the Python script
// scripts/advise/ldmbench_advise.py, which measures through `ldmbench sweep` stages; this
// command checks what it can first (bad budgets and options exit 2 with nothing written
// and no Python started), then runs it with this binary and the axis registry.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "harness/settings/axis_registry.h"
#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/cli/python_tool.h"
#include "harness/util/error.h"
#include "harness/util/process.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm::cli {
namespace {

namespace fs = std::filesystem;

struct AdviseOptions {
  std::string scene, pass = "ao", space, out, image_size = "128x128", cache_dir, launcher = "local";
  std::vector<std::string> structures;
  std::optional<double> budget_ms, budget_mib, max_error, min_mssim, cost_share;
  std::optional<unsigned> reference_max_spp, levels;
  unsigned shards = 1;
  bool overwrite = false;
  GpuOption gpu;
};

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

void check_positive(const char* name, const std::optional<double>& v) {
  if (v && !(std::isfinite(*v) && *v > 0))
    throw UserError(std::string(name) + " " + number(*v) + ": expected a positive finite number");
}

void check_options(const AdviseOptions& o) {
  check_positive("--budget-ms", o.budget_ms);
  check_positive("--budget-mib", o.budget_mib);
  check_positive("--max-error", o.max_error);
  check_positive("--cost-share", o.cost_share);
  if (o.min_mssim && !(std::isfinite(*o.min_mssim) && *o.min_mssim > 0 && *o.min_mssim <= 1))
    throw UserError("--min-mssim " + number(*o.min_mssim) + ": expected a number in (0, 1]");
  if (o.max_error && o.min_mssim) throw UserError("--max-error and --min-mssim: give one error bound, not both");
  if (!o.budget_ms && !o.budget_mib && !o.max_error && !o.min_mssim)
    throw UserError("no budget: give --budget-ms, --budget-mib, --max-error or --min-mssim");
  const auto known = structure_names();
  for (const std::string& s : o.structures)
    if (std::find(known.begin(), known.end(), s) == known.end())
      throw UserError("--structures: unknown structure \"" + s + "\" (`ldmbench structures` lists them)");
  if (!o.space.empty() && !fs::is_regular_file(o.space))
    throw UserError("--space: " + o.space + ": no such file");
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw UserError("--out: '" + o.out + "' exists and is not a folder");
}

}  // namespace

Runner add_advise_command(CLI::App& app) {
  auto o = std::make_shared<AdviseOptions>();
  auto* cmd = app.add_subcommand(
      "advise", "The structure and parameters that meet a scene's budgets with the least error (or the "
                "fastest within an error bound): an adaptive search, verified at a normal run's precision");
  cmd->add_option("--scene", o->scene, "Built-in scene, scene file or mesh file")->required();
  cmd->add_option("--pass", o->pass,
                  "The pass (ao or indirect), or a comma list of AO methods (ao,gtao,hbao,rtao_gpu): the "
                  "method is then an axis of the search, each peer a candidate per value of its own "
                  "parameters (checked against `ldmbench passes`)");
  cmd->add_option("--budget-ms", o->budget_ms, "Frame time budget [ms] (median frame time)");
  cmd->add_option("--budget-mib", o->budget_mib, "Memory budget [MiB] (the structure's bytes allocated)");
  cmd->add_option("--max-error", o->max_error,
                  "Error bound (MSE against the reference): the fastest configuration within it is sought");
  cmd->add_option("--min-mssim", o->min_mssim, "Error bound as a least MSSIM against the reference");
  cmd->add_option("--structures", o->structures, "Only these structures (comma list)")->delimiter(',');
  cmd->add_option("--space", o->space,
                  "Space file: {\"axes\": {structures, views, r_ldm, trace, sizing, OWNER:KEY ...}} "
                  "(default: every structure, N 8,16,32, R_LDM 64,128, fixed arrays' k 4,8,16; indirect: N 8,16, "
                  "R_LDM 32,64, k 4,8,16, indirect:r_light 32,64)");
  cmd->add_option("--image-size", o->image_size, "Output image WIDTHxHEIGHT");
  cmd->add_option("--out", o->out, "Advise folder: new, empty, or an earlier advise of the same question "
                                   "(resumed)")->required();
  cmd->add_option("--cache-dir", o->cache_dir,
                  "Reference cache folder (default: $XDG_CACHE_HOME/ldmbench/references, else "
                  "~/.cache/ldmbench/references)");
  cmd->add_option("--reference-max-spp", o->reference_max_spp,
                  "Cap of the references' samples per pixel per half, every stage");
  cmd->add_option("--levels", o->levels, "Precision levels of the race before verification, 1 or 2 (default 2)")
      ->check(CLI::Range(1, 2));
  cmd->add_option("--cost-share", o->cost_share,
                  "After the first verification, further rounds of repeated verification (uncertain "
                  "candidates, the budget line) run while advise's recorded time stays within this share of "
                  "an exhaustive sweep's, estimated from that verification (default 1; 0.25 for a cheaper answer); the rounds left out "
                  "are named in the answer, and a rerun with a larger share measures them");
  cmd->add_option("--shards", o->shards,
                  "Measure every stage in this many shards of its sweep (ldmbench sweep --shard), merged; "
                  "with --launcher slurm each shard is an array task on a GPU node of its own")
      ->check(CLI::Range(1u, 4096u));
  cmd->add_option("--launcher", o->launcher,
                  "local: the stages' sweeps (or their shards, one after another) on this machine; slurm: "
                  "each stage a job array plus merge through scripts/slurm-sweep.sh, waited for "
                  "(LDM_SLURM_GPUS, LDM_SLURM_GPU_ARGS, SBATCH_ARGS apply; docs/guide/advise.md)")
      ->check(CLI::IsMember({"local", "slurm"}));
  cmd->add_flag("--overwrite", o->overwrite, "Replace an earlier advise of another question in --out");
  add_gpu_option(cmd, o->gpu);
  return [o]() {
    check_options(*o);
    export_gpu_option(o->gpu);  // its stages' sweeps read LDM_GPU
    const std::string script = find_tool_script(python_tool("advise"));
    const std::string python = find_tool_python(python_tool("advise"));
    const std::string exe = executable_path();
    if (exe.empty()) throw UserError("cannot find this ldmbench binary's path (/proc/self/exe)");
    std::string scratch = (fs::temp_directory_path() / "ldmbench-advise-XXXXXX").string();
    if (!mkdtemp(scratch.data())) throw UserError("cannot make a temporary folder for the axis registry");
    const fs::path axes = fs::path(scratch) / "axes.json";
    {
      std::ofstream file(axes);
      file << axes_json().dump() << "\n";
      if (!file) throw UserError(axes.string() + ": cannot write the axis registry for advise");
    }
    std::vector<std::string> argv = {python, script, "--ldmbench", exe, "--axes", axes.string(),
                                     "--scene", o->scene, "--pass", o->pass, "--out", o->out,
                                     "--image-size", o->image_size};
    if (o->budget_ms) argv.insert(argv.end(), {"--budget-ms", number(*o->budget_ms)});
    if (o->budget_mib) argv.insert(argv.end(), {"--budget-mib", number(*o->budget_mib)});
    if (o->max_error) argv.insert(argv.end(), {"--max-error", number(*o->max_error)});
    if (o->min_mssim) argv.insert(argv.end(), {"--min-mssim", number(*o->min_mssim)});
    if (!o->structures.empty()) {
      std::string list;
      for (const auto& s : o->structures) list += (list.empty() ? "" : ",") + s;
      argv.insert(argv.end(), {"--structures", list});
    }
    if (!o->space.empty()) argv.insert(argv.end(), {"--space", o->space});
    if (!o->cache_dir.empty()) argv.insert(argv.end(), {"--cache-dir", o->cache_dir});
    if (o->reference_max_spp) argv.insert(argv.end(), {"--reference-max-spp", std::to_string(*o->reference_max_spp)});
    if (o->levels) argv.insert(argv.end(), {"--levels", std::to_string(*o->levels)});
    if (o->cost_share) argv.insert(argv.end(), {"--cost-share", number(*o->cost_share)});
    if (o->overwrite) argv.push_back("--overwrite");
    argv.insert(argv.end(), {"--shards", std::to_string(o->shards), "--launcher", o->launcher});
    const ProcessResult result = run_process(argv, /*capture=*/false, /*forward_stop=*/true);
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
    if (!result.started) throw UserError(python + ": cannot run: " + result.output);
    return result.status;
  };
}

}  // namespace ldm::cli
