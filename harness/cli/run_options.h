#pragma once
// The options of `ldmbench run`, shared with `ldmbench view` (which shows one configuration
// of them), so that both read a command line alike.
#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

#include "harness/settings/axis_options.h"
#include "harness/settings/run_setting_options.h"
#include "harness/settings/run_settings.h"
#include "harness/cli/commands.h"

namespace ldm::cli {

struct RunOptions {
  RunSettings settings;
  AxisOptions axes;  // every harness axis's option (harness/settings/axis_options.h)
  std::vector<std::string> params;
  int width = 0, height = 0;  // --width/--height: the image size's two sides
  std::string platform = "auto";
  RunSettingOptions setting_options;  // the run-wide settings' (harness/settings/run_setting_options.h)
  GpuOption gpu;
};

// Registers every option of `run` on `command`; `o` must outlive the parse.
void add_run_options(CLI::App* command, RunOptions* o);
// The settings after the parse, checked (throws UserError naming the option).
RunSettings run_settings_from(RunOptions* o);

}  // namespace ldm::cli
