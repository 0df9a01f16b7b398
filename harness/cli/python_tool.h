#pragma once
// The subcommands whose work is a Python script (`ldmbench report`, `ldmbench advise`): where
// the script is, and a Python that has the packages it imports. One lookup for all of them,
// so that an installed tree, a build tree and the environment overrides behave alike.
#include <string>
#include <vector>

namespace ldm::cli {

// Every tool's Python: this environment variable, else python3 on PATH, else /usr/bin/python3
// (Debian's, where scripts/setup.sh installs the packages).
inline constexpr const char* kPythonEnv = "LDMBENCH_PYTHON";

struct PythonTool {
  std::string command;      // the subcommand, for messages: "report"
  std::string folder;       // scripts/<folder>/ in the sources, <bin>/<folder>/ when installed
  std::string script;       // the script's file name: "ldmbench_report.py"
  std::string script_env;   // overrides the script's path: "LDMBENCH_REPORT_SCRIPT"
  std::vector<std::string> modules;  // what the Python must have: {"matplotlib", "numpy"}
  std::string debian_packages;       // where they come from, for the message
};

// The tool of subcommand `command` (report, advise, model), from one table.
const PythonTool& python_tool(const std::string& command);

// $script_env, else <bin>/<folder>/<script>, <prefix>/share/ldmbench/<folder>/<script>, else
// the source tree the binary was built from; UserError naming every place tried.
std::string find_tool_script(const PythonTool& tool);

// The first candidate Python that finds every module (without importing them: an import of
// matplotlib takes a second); UserError naming each candidate and why it failed.
std::string find_tool_python(const PythonTool& tool);

}  // namespace ldm::cli
