#pragma once
// The command-line options of the harness axes, made from their declarations
// (harness/settings/harness_axes.h): one CLI11 option per axis with flags, its help from the
// description, unit, range or choices and default; a comma list where the axis is a list.
// `ldmbench run` and `ldmbench view` add them (harness/cli/run_options.cpp).
#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

#include "harness/settings/run_settings.h"

namespace ldm {

struct AxisOptions {
  std::map<std::string, std::vector<std::string>> texts;  // as given, by axis key
  std::map<std::string, CLI::Option*> options;
  bool given(const std::string& key) const {
    const auto it = options.find(key);
    return it != options.end() && it->second->count() > 0;
  }
};

// Registers every harness axis's option on `command`; `axes` must outlive the parse.
void add_axis_options(CLI::App* command, AxisOptions& axes);
// Stores the values given, each checked by its declaration and made canonical, duplicates
// refused ("-N 4,4"), "all" structures expanded. Throws UserError naming the option.
void apply_axis_options(const AxisOptions& axes, RunSettings& settings);

}  // namespace ldm
