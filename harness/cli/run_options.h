#pragma once
// The options of `ldmbench run`, shared with `ldmbench view` (which shows one configuration
// of them), so that both read a command line alike.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "harness/app/run_settings.h"

namespace ldm::cli {

struct RunOptions {
  RunSettings settings;
  std::vector<std::string> params, visibility, traces, estimators, sizing;
  std::string platform = "auto";
  std::string isolation = "context";
  float normal_offset = 0.0f;
  CLI::Option* normal_offset_option = nullptr;
};

// Registers every option of `run` on `command`; `o` must outlive the parse.
void add_run_options(CLI::App* command, RunOptions* o);
// The settings after the parse, checked (throws UserError naming the option).
RunSettings run_settings_from(RunOptions* o);

}  // namespace ldm::cli
