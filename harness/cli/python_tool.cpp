#include "harness/cli/python_tool.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "harness/util/error.h"
#include "harness/util/process.h"

namespace ldm::cli {

namespace fs = std::filesystem;

const PythonTool& python_tool(const std::string& command) {
  static const std::vector<PythonTool> tools = {
      // Tables, plots and pages (pandas, matplotlib).
      {"report", "report", "ldmbench_report.py", "LDMBENCH_REPORT_SCRIPT", {"matplotlib", "pandas", "numpy"},
       "python3-matplotlib python3-pandas"},
      // The search and its report's plot (numpy, matplotlib).
      {"advise", "advise", "ldmbench_advise.py", "LDMBENCH_ADVISE_SCRIPT", {"matplotlib", "numpy"},
       "python3-matplotlib python3-numpy"},
      // The cost model's non-negative least squares (scipy).
      {"model", "model", "ldmbench_model.py", "LDMBENCH_MODEL_SCRIPT", {"numpy", "scipy"},
       "python3-numpy python3-scipy"},
  };
  for (const PythonTool& tool : tools)
    if (tool.command == command) return tool;
  throw std::logic_error("no Python tool for the subcommand '" + command + "'");
}

std::string find_tool_script(const PythonTool& tool) {
  if (const char* env = std::getenv(tool.script_env.c_str()); env && *env) {
    if (!fs::is_regular_file(env)) throw UserError(tool.script_env + "=" + env + ": no such file");
    return env;
  }
  std::vector<fs::path> candidates;
  if (const std::string exe = executable_path(); !exe.empty()) {
    const fs::path bin = fs::path(exe).parent_path();
    candidates.push_back(bin / tool.folder / tool.script);
    candidates.push_back(bin.parent_path() / "share" / "ldmbench" / tool.folder / tool.script);
  }
  candidates.push_back(fs::path(LDM_SOURCE_DIR) / "scripts" / tool.folder / tool.script);
  std::string tried;
  for (const fs::path& c : candidates) {
    if (fs::is_regular_file(c)) return c.string();
    tried += "\n  " + c.string();
  }
  throw UserError("the " + tool.command + " script " + tool.script + " is not installed; looked in:" +
                  tried + "\nset " + tool.script_env + " to its path (scripts/" + tool.folder +
                  "/ in the sources)");
}

std::string find_tool_python(const PythonTool& tool) {
  std::string modules_list, listed;
  for (const std::string& m : tool.modules) {
    modules_list += (modules_list.empty() ? "'" : ", '") + m + "'";
    listed += (listed.empty() ? "" : ", ") + m;
  }
  const std::string probe_code =
      "import importlib.util, sys\n"
      "missing = [m for m in (" + modules_list + ",) if importlib.util.find_spec(m) is None]\n"
      "sys.exit('No module named ' + ', '.join(missing) if missing else 0)\n";
  std::vector<std::string> candidates;
  if (const char* env = std::getenv(kPythonEnv); env && *env)
    candidates = {env};
  else
    candidates = {"python3", "/usr/bin/python3"};
  std::string tried;
  for (const std::string& python : candidates) {
    const ProcessResult probe = run_process({python, "-c", probe_code}, /*capture=*/true);
    if (probe.started && probe.status == 0) return python;
    std::string why = probe.output;  // its last line
    if (const size_t last = why.find_last_not_of("\n"); last != std::string::npos)
      why = why.substr(why.rfind('\n', last) + 1, last - why.rfind('\n', last));
    tried += "\n  " + python + ": " +
             (probe.started ? (why.empty() ? "exit " + std::to_string(probe.status) : why)
                            : "cannot run (" + probe.output + ")");
  }
  throw UserError("ldmbench " + tool.command + " needs python3 with " + listed + "; tried:" + tried +
                  "\nrun scripts/setup.sh (Debian: " + tool.debian_packages + "), or set " +
                  kPythonEnv + " to a python that has them");
}

}  // namespace ldm::cli
