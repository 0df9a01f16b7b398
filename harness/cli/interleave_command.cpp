// `ldmbench interleave A B -- COMMAND...`: two builds measured alternately on one sweep
// (harness/compare/interleaved_session.h), then compared with paired tests.
#include <iostream>
#include <memory>
#include <sstream>

#include "harness/compare/interleaved_session.h"
#include "harness/cli/commands.h"

namespace ldm::cli {

Runner add_interleave_command(CLI::App& app) {
  auto s = std::make_shared<InterleavedSession>();
  auto* cmd = app.add_subcommand(
      "interleave",
      "Measure two builds alternately on one sweep (A B, B A, ... per configuration and "
      "repetition, each in its own process) and compare them with paired tests: the time "
      "verdict to trust on a shared machine. Usage: ldmbench interleave A B [--out DIR] "
      "[--repetitions K] -- run ... | sweep FILE ...");
  cmd->add_option("A", s->binary_a, "The baseline build's ldmbench binary")->required();
  cmd->add_option("B", s->binary_b, "The build to judge")->required();
  cmd->add_option("--out", s->out_dir, "Session folder (a/, b/, session.json, comparison.json)")->required();
  cmd->add_option("--repetitions", s->repetitions, "Repetitions (pairs) of every configuration")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  auto a_args = std::make_shared<std::string>(), b_args = std::make_shared<std::string>();
  auto ignored = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--a-args", *a_args,
                  "Arguments only A's command gets (split at spaces), e.g. --a-args=\"-N 16\": two variants "
                  "of one build");
  cmd->add_option("--b-args", *b_args, "Arguments only B's command gets, e.g. \"-N 20\"");
  cmd->add_option("--ignore-param", *ignored,
                  "Leave this structure parameter (or n_views, r_ldm) out of the identity when "
                  "pairing A's configurations with B's (repeatable)")
      ->allow_extra_args(false);  // one value each time: the command after -- stays positional
  auto gpu = std::make_shared<GpuOption>();
  add_gpu_option(cmd, *gpu);
  cmd->add_option("command", s->command, "After --: `run ...` or `sweep FILE ...`, as for one build")
      ->required();
  return [s, a_args, b_args, ignored, gpu]() {
    export_gpu_option(*gpu);  // both builds' children read LDM_GPU
    const auto words = [](const std::string& text) {
      std::vector<std::string> out;
      std::istringstream in(text);
      for (std::string w; in >> w;) out.push_back(w);
      return out;
    };
    s->a_arguments = words(*a_args);
    s->b_arguments = words(*b_args);
    s->ignored_params.insert(ignored->begin(), ignored->end());
    return run_interleaved_session(*s, std::cout);
  };
}

}  // namespace ldm::cli
