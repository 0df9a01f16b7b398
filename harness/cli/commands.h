#pragma once
// The subcommands of the ldmbench CLI, each registering its options and returning a runner.
#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ldm::cli {

using Runner = std::function<int()>;  // returns the process exit status

// `arguments` are argv after the program: a child process (--isolation process) repeats them.
Runner add_run_command(CLI::App& app, const std::string& command_line,
                       const std::vector<std::string>& arguments);
// CLI11 silently drops the empty item of "-N 4,,8"; its intended value is unknown, so the
// comma lists of `run` are checked on the raw arguments first. Throws UserError.
void reject_empty_list_items(int argc, const char* const* argv);
// `--out ""` (and --scene, --cache-dir) would be taken as "not given" (a folder under
// results/runs/): an empty path is refused on the raw arguments. Throws UserError.
void reject_empty_paths(int argc, const char* const* argv);
Runner add_sweep_command(CLI::App& app, const std::string& command_line,
                         const std::vector<std::string>& arguments);  // ldmbench sweep FILE
// ldmbench interleave: two builds alternately on one sweep (harness/compare/interleaved_session.h)
Runner add_interleave_command(CLI::App& app);
// ldmbench calibrate: this machine's run-to-run spread (harness/measuring/calibration.h)
Runner add_calibrate_command(CLI::App& app);
Runner add_merge_command(CLI::App& app, const std::string& command_line);  // ldmbench merge OUT RUN...
Runner add_reference_command(CLI::App& app);
Runner add_report_command(CLI::App& app);  // ldmbench report RUN... (plots, pages)
Runner add_advise_command(CLI::App& app);  // ldmbench advise (scripts/advise/)
Runner add_model_command(CLI::App& app);   // ldmbench model RUN... (scripts/model/)
Runner add_compare_command(CLI::App& app);
Runner add_compare_runs_command(CLI::App& app);  // ldmbench compare BASE NEW
Runner add_listing_commands(CLI::App& app);
// ldmbench view (harness/viewer); `program` is argv[0], for the command lines it saves.
Runner add_view_command(CLI::App& app, const std::string& program);  // scenes, structures, passes, columns, info

// --gpu N of every command that opens a context (docs/guide/gpu-nodes.md#choosing-the-gpu):
// the option wins over LDM_GPU. `text()` is the value when given.
struct GpuOption {
  std::string value;
  CLI::Option* option = nullptr;
  std::optional<std::string> text() const {
    return option && option->count() ? std::optional<std::string>(value) : std::nullopt;
  }
};
void add_gpu_option(CLI::App* command, GpuOption& gpu);
// Commands that measure through child processes (advise, interleave): a --gpu given is
// checked, then handed to the children as LDM_GPU.
void export_gpu_option(const GpuOption& gpu);

// `ldmbench completion bash` and `ldmbench man` describe `app` itself (harness/cli/cli_model.h):
// call them after every other subcommand is added.
Runner add_completion_command(CLI::App& app);
Runner add_man_command(CLI::App& app);

}  // namespace ldm::cli
