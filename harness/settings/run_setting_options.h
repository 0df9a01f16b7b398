#pragma once
// The command-line options of the run-wide settings, made from their declarations
// (harness/settings/run_setting_table.h): one CLI11 option per setting, with its help, range
// or choices and default; a flag setting's option turns it off (--no-images). `ldmbench run`
// and `ldmbench view` add them (harness/cli/run_options.cpp), as they add the axes'
// (harness/settings/axis_options.h).
#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

#include "harness/settings/run_settings.h"

namespace ldm {

struct RunSettingOptions {
  // The settings stored as enums (--isolation), as given, by their path; the others are
  // bound to their fields of RunSettings directly.
  std::map<std::string, std::string> texts;
};

// Registers every run-wide setting's option on `command`, bound to `settings` (its defaults
// shown in the help); both must outlive the parse.
void add_run_setting_options(CLI::App* command, RunSettings& settings, RunSettingOptions& options);
// Stores the settings given as text (checked by their choices) into `settings`.
void apply_run_setting_options(const RunSettingOptions& options, RunSettings& settings);

// Options that override some run-wide settings of a file (`ldmbench sweep --repetitions`):
// one per named setting, its flag, help, range or choices from its declaration, kept as
// given until applied to the settings the file planned.
struct RunSettingOverrides {
  std::map<std::string, std::string> given;  // by path; empty: not given
  std::vector<CLI::Option*> options;         // in the order of `paths`
};
// Registers the overrides of the settings at `paths` on `command`, each help ending with
// "(default: `default_from`'s settings.PATH)". A path the table lacks, or a flag setting, is
// a logic_error.
void add_run_setting_overrides(CLI::App* command, RunSettingOverrides& overrides,
                               const std::vector<std::string>& paths, const std::string& default_from);
// Sets every given override in `settings`.
void apply_run_setting_overrides(const RunSettingOverrides& overrides, RunSettings& settings);

}  // namespace ldm
