#pragma once
// The command line as data, read from the CLI11 definitions themselves (every subcommand's
// options, positionals and descriptions) and from the axis registry (the values an option
// accepts: structure, pass and scene names, a choice axis's names, OWNER:KEY of --param).
// What is generated from it, the bash completion (completion_command.cpp) and the man page
// (man_command.cpp), therefore cannot drift from the options the binary parses.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace ldm::cli {

struct OptionModel {
  std::vector<std::string> names;  // "--views", "-N" (long names first); empty for a positional
  std::string positional;          // its name ("base") when it is a positional
  std::string value_name;          // "TEXT", "INT", ...; empty for a flag
  std::string description;
  std::string default_value;       // as --help shows it ("" when none is shown)
  bool required = false;
  bool list = false;               // takes a comma list (an axis)
  bool files = false;              // a path, or a value a path may replace (--scene)
  std::vector<std::string> values; // the names it accepts, when they are known
  bool takes_value() const { return !value_name.empty(); }
};

struct CommandModel {
  std::string name;                 // the subcommand ("run"); "" for the program itself
  std::string description;
  std::string footer;
  std::vector<OptionModel> options;      // named options, in --help order
  std::vector<OptionModel> positionals;  // in order
};

// The subcommands of `app` in --help order.
std::vector<const CLI::App*> subcommands_of(const CLI::App& app);
CommandModel command_model(const CLI::App& command);

// --param OWNER:KEY=VALUE: every structure's and pass's parameter as "owner:key", and the
// values a choice or boolean one accepts (empty when any number or text goes).
struct ParameterModel {
  std::string qualified;
  std::vector<std::string> values;
  std::string description;
};
std::vector<ParameterModel> parameter_models();

// The name of `known` closest to `given` (Damerau-free edit distance at most a third of
// its length, at least 1, or a prefix), or "" when none is close.
std::string closest_name(const std::string& given, const std::vector<std::string>& known);

}  // namespace ldm::cli
