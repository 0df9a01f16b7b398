// ldmbench: benchmark and compare layered-depth-map structures on the GPU.
//   ldmbench run             measure structures x passes x parameters: records and images
//   ldmbench sweep           the configurations of a sweep file (resumable, sharded)
//   ldmbench merge           join the run folders of a sweep's shards into one
//   ldmbench reference       render a path-traced reference image
//   ldmbench compare-images  error metrics between two images
//   ldmbench report          tables, plots and pages from runs (scripts/report/)
//   ldmbench model           a cost model fitted on work counters (scripts/model/)
//   ldmbench compare         regressions between two runs (time, memory, accuracy, status)
//   ldmbench interleave      two builds measured alternately on one sweep, then compared
//   ldmbench view            interactive viewer of one configuration (GLFW, Dear ImGui)
//   ldmbench axes            every axis: the harness's and the structures' and passes' parameters
//   ldmbench scenes | structures | passes | columns | info
//   ldmbench completion bash | man   the shell completion and the man page, from these definitions
//   ldmbench --version
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <map>
#include <new>

#include "harness/run/exit_codes.h"
#include "harness/cli/cli_model.h"
#include "harness/cli/commands.h"
#include "harness/records/run_lock.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"
#include "harness/util/version.h"

namespace {

// `ldmbench foo`: CLI11 alone would say "A subcommand is required". The first argument is
// the subcommand (the program has no option that takes a value), so an unknown one is named,
// with the closest known one and the list. Empty when `argument` is a known subcommand.
std::string unknown_subcommand_error(const CLI::App& app, const std::string& argument) {
  if (argument.empty() || argument[0] == '-') return "";
  std::vector<std::string> names;
  for (const CLI::App* sub : ldm::cli::subcommands_of(app)) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), argument) != names.end()) return "";
  std::string message = "unknown subcommand '" + argument + "'";
  const std::string closest = ldm::cli::closest_name(argument, names);
  if (!closest.empty()) message += " (did you mean '" + closest + "'?)";
  message += "\nsubcommands:";
  for (const std::string& name : names) message += " " + name;
  return message + "\n`ldmbench --help` describes each";
}

}  // namespace

int main(int argc, char** argv) {
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  const std::vector<std::string> arguments(argv + 1, argv + argc);  // for child processes

  CLI::App app{"ldmbench: benchmark layered-depth-map structures on the GPU"};
  app.require_subcommand(1);
  std::map<std::string, ldm::cli::Runner> runners = {
      {"run", ldm::cli::add_run_command(app, command_line, arguments)},
      {"sweep", ldm::cli::add_sweep_command(app, command_line, arguments)},
      {"interleave", ldm::cli::add_interleave_command(app)},
      {"calibrate", ldm::cli::add_calibrate_command(app)},
      {"merge", ldm::cli::add_merge_command(app, command_line)},
      {"reference", ldm::cli::add_reference_command(app)},
      {"compare-images", ldm::cli::add_compare_command(app)},
      {"report", ldm::cli::add_report_command(app)},
      {"advise", ldm::cli::add_advise_command(app)},
      {"model", ldm::cli::add_model_command(app)},
      {"compare", ldm::cli::add_compare_runs_command(app)},
      {"listing", ldm::cli::add_listing_commands(app)},
      {"view", ldm::cli::add_view_command(app, argv[0])},
      {"completion", ldm::cli::add_completion_command(app)},
      {"man", ldm::cli::add_man_command(app)},
  };
  // Set after the subcommands, which would inherit the footer.
  app.set_version_flag("--version", ldm::version_line("ldmbench"), "Print the version and the commit it was built from");
  app.footer(ldm::version_line("ldmbench"));
  try {
    ldm::cli::reject_empty_list_items(argc, argv);
    ldm::cli::reject_empty_paths(argc, argv);
    if (argc > 1)
      if (const std::string error = unknown_subcommand_error(app, argv[1]); !error.empty())
        throw ldm::UserError(error);
  } catch (const ldm::UserError& e) {
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return ldm::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return ldm::kExitUsage;
  }
  // Exit statuses: docs/guide/reliability.md (harness/run/exit_codes.h kExit*).
  try {
    const std::string name = app.get_subcommands().front()->get_name();
    auto runner = runners.find(name);
    return (runner != runners.end() ? runner->second : runners.at("listing"))();
  } catch (const ldm::FolderInUse& e) {
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return ldm::kExitBusy;
  } catch (const ldm::UserError& e) {
    std::cerr << "ldmbench: error: " << e.what() << "\n";
    return ldm::kExitUsage;
  } catch (const ldm::IoError& e) {
    std::cerr << "ldmbench: I/O error: " << e.what() << "\n";
    return ldm::kExitIoError;
  } catch (const std::bad_alloc&) {
    std::cerr << "ldmbench: failed: out of memory (std::bad_alloc); inputs are limited to "
              << (ldm::max_input_bytes() >> 20) << " MiB (" << ldm::kMaxInputEnv << ")\n";
    return ldm::kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "ldmbench: failed: " << e.what() << "\n";
    return ldm::kExitFailure;
  }
}
