// `ldmbench merge OUT RUN...`: the shards of a sweep joined into one run folder
// (harness/records/run_merge.h).
#include <iostream>
#include <memory>

#include "harness/run/exit_codes.h"
#include "harness/settings/record_schema.h"
#include "harness/cli/commands.h"
#include "harness/records/run_merge.h"

namespace ldm::cli {

Runner add_merge_command(CLI::App& app, const std::string& command_line) {
  auto out = std::make_shared<std::string>();
  auto runs = std::make_shared<std::vector<std::string>>();
  auto options = std::make_shared<MergeOptions>();
  auto* merge = app.add_subcommand(
      "merge", "Join the run folders of a sweep's shards (ldmbench sweep --shard i/n) into one");
  merge->add_option("OUT", *out, "Merged run folder (missing or empty, or --overwrite)")->required();
  merge->add_option("RUN", *runs, "Run folders to join")->required();
  merge->add_flag("--allow-mismatch", options->allow_mismatch,
                  "Merge runs of different ldmbench builds, devices or sweep files (warned)");
  merge->add_flag("--overwrite", options->overwrite, "Replace the records and images in OUT");
  return [out, runs, options, command_line]() {
    options->command = command_line;
    options->columns = record_columns();
    options->always_written = always_written_columns();
    const MergeResult result = merge_runs(*out, *runs, *options);
    for (const auto& warning : result.warnings) std::cerr << "ldmbench: warning: " << warning << "\n";
    std::cout << "merged " << result.records << " records of " << runs->size() << " runs into " << *out
              << "\nnext: ldmbench report " << *out << "\n";
    return kExitOk;
  };
}

}  // namespace ldm::cli
