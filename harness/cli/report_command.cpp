// `ldmbench report RUN... [--out DIR]`: a folder of tables, plots and pages from runs. The
// work is done by the Python script scripts/report/ldmbench_report.py (matplotlib and
// pandas); this command checks every argument first, so that bad input exits 2 with
// nothing written and no Python started, then finds the script and a Python that has the
// plotting packages, and runs it.
#include <algorithm>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "harness/settings/axis_registry.h"
#include "harness/run/exit_codes.h"
#include "harness/cli/commands.h"
#include "harness/cli/python_tool.h"
#include "harness/compare/run_comparison.h"
#include "harness/records/columns.h"
#include "harness/records/journal.h"
#include "harness/settings/record_schema.h"
#include "harness/records/record_validation.h"
#include "harness/records/run_folder.h"
#include "harness/util/error.h"
#include "harness/util/process.h"

namespace ldm::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kManifest = "manifest.json";  // what marks a folder as a report

struct ReportOptions {
  std::vector<std::string> runs, axes, formats;
  std::string out, title;
  bool svg = false;
};

// The figures' formats (the script's style.FORMATS): checked here, so that a typo exits 2
// before anything is written or Python starts.
constexpr const char* kFigureFormats[] = {"png", "svg", "pdf"};

void check_formats(const std::vector<std::string>& formats) {
  for (const std::string& format : formats)
    if (std::find(std::begin(kFigureFormats), std::end(kFigureFormats), format) == std::end(kFigureFormats))
      throw UserError("--format: '" + format + "' is not one of png, svg, pdf");
}

// A records.csv must at least name its configurations and their status.
void check_csv_header(const fs::path& path) {
  std::ifstream in(path);
  std::string header;
  if (!in || !std::getline(in, header))
    throw UserError(path.string() + ": cannot read, or empty (expected ldmbench records)");
  std::vector<std::string> names;
  std::stringstream s(header);
  for (std::string name; std::getline(s, name, ',');) names.push_back(name);
  for (const char* needed : {"config_id", "status"})
    if (std::find(names.begin(), names.end(), needed) == names.end())
      throw UserError(path.string() + ": not ldmbench records (no column " + needed + ")");
}

// The records file a RUN argument names; throws UserError naming the path otherwise.
fs::path records_file_of(const std::string& run) {
  const fs::path path(run);
  if (fs::is_directory(path)) {
    if (fs::is_regular_file(path / "records.csv")) return path / "records.csv";
    if (fs::is_regular_file(path / "records.json")) return path / "records.json";
    throw UserError(run + ": a folder without records.csv or records.json (expected an "
                    "ldmbench run folder)");
  }
  if (!fs::exists(path)) throw UserError(run + ": no such file or folder");
  if (path.extension() != ".csv" && path.extension() != ".json")
    throw UserError(run + ": expected a run folder, a records.csv or a records.json");
  return path;
}

// A records.csv without its journal: its columns against the schema (those of another
// build's records are not this build's to judge).
void check_csv_columns(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const auto rows = parse_csv(text.str());
  if (rows.size() < 2) return;
  const auto& header = rows[0];
  bool this_build = false;
  for (size_t r = 1; r < rows.size(); ++r) {
    Record stamp;
    for (size_t c = 0; c < header.size() && c < rows[r].size(); ++c)
      if (header[c] == "git_commit" || header[c] == "ldmbench_version") stamp.set(header[c], rows[r][c]);
    this_build |= !from_other_build(stamp);
  }
  if (!this_build) return;
  for (const std::string& column : header)
    if (!find_column(column))
      throw UserError(path.string() + ": column '" + column +
                      "' is not in the record schema (`ldmbench columns` lists them)");
}

void check_run(const std::string& run) {
  const fs::path records = records_file_of(run);
  // A run folder's tables are derived from its journal: they must be what it gives (a
  // tampered records.csv, a truncated records.json are refused), and its records must
  // follow the schema.
  const fs::path dir = records.parent_path().empty() ? fs::path(".") : records.parent_path();
  if (check_tables_match_journal(dir.string())) {
    const std::string journal = (dir / kJournalFile).string();
    check_records_schema(latest_per_configuration(read_journal(journal).records), record_columns(), journal);
  }
  if (records.extension() == ".csv") {
    check_csv_header(records);
    check_csv_columns(records);
  } else {
    load_run_records(records.string());  // throws UserError naming the file
  }
}

// --out: a new or empty folder, or an earlier report (replaced); never a run's own folder.
void check_out_folder(const std::string& out, const std::vector<std::string>& runs) {
  const fs::path target = fs::weakly_canonical(fs::absolute(out));
  for (const std::string& run : runs) {
    const fs::path folder = fs::weakly_canonical(fs::absolute(records_file_of(run)).parent_path());
    if (target == folder) throw UserError("--out: '" + out + "' is the folder of " + run + "; choose another");
  }
  if (!fs::exists(target)) return;
  if (!fs::is_directory(target)) throw UserError("--out: '" + out + "' exists and is not a folder");
  if (fs::is_empty(target)) return;
  std::ifstream manifest(target / kManifest);
  bool is_report = false;
  if (manifest) {
    const auto root = nlohmann::json::parse(manifest, nullptr, /*allow_exceptions=*/false);
    is_report = root.is_object() && root.contains("ldmbench_report");
  }
  if (!is_report)
    throw UserError("--out: '" + out + "' is not empty and holds no earlier report (" +
                    kManifest + "); choose an empty or new folder");
}

std::string default_out(const std::vector<std::string>& runs) {
  if (runs.size() != 1) throw UserError("--out: needed when reporting several runs");
  return (fs::path(records_file_of(runs[0])).parent_path() / "report").string();
}


}  // namespace

Runner add_report_command(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand(
      "report", "Tables, plots (trade-offs with Pareto fronts, memory, sub-pass bars, "
                "scaling slopes, image grids) and pages (index.html, summary.md) from runs");
  cmd->add_option("runs", o->runs, "Run folders, or their records.csv / records.json")
      ->required()
      ->expected(1, -1);
  cmd->add_option("--out", o->out,
                  "Report folder: new, empty, or an earlier report (replaced). Default: "
                  "RUN/report for one run");
  cmd->add_option("--format", o->formats,
                  "Figure formats: png, svg, pdf; repeatable or a comma list (default png; "
                  "figures are sized for a two-column paper)")
      ->delimiter(',');
  cmd->add_flag("--svg", o->svg, "The same as --format png,svg (kept for earlier scripts)");
  cmd->add_option("--title", o->title, "Title of the pages");
  cmd->add_option("--axis", o->axes,
                  "A further record column that tells configurations apart (a new pass's "
                  "setting), repeatable");
  return [o]() {
    check_formats(o->formats);
    for (const std::string& run : o->runs) check_run(run);
    const std::string out = o->out.empty() ? default_out(o->runs) : o->out;
    check_out_folder(out, o->runs);
    const std::string script = find_tool_script(python_tool("report"));
    const std::string python = find_tool_python(python_tool("report"));
    // The axes the report groups and labels by: the registry's declarations, as JSON.
    std::string scratch = (std::filesystem::temp_directory_path() / "ldmbench-report-XXXXXX").string();
    if (!mkdtemp(scratch.data())) throw UserError("cannot make a temporary folder for the report's axis registry");
    const std::filesystem::path axes = std::filesystem::path(scratch) / "axes.json";
    {
      std::ofstream file(axes);
      file << axes_json().dump() << "\n";
      if (!file) throw UserError(axes.string() + ": cannot write the axis registry for the report");
    }
    std::vector<std::string> argv = {python, script};
    argv.insert(argv.end(), o->runs.begin(), o->runs.end());
    argv.insert(argv.end(), {"--out", out, "--axes", axes.string()});
    if (o->svg) argv.push_back("--svg");
    for (const std::string& format : o->formats) argv.insert(argv.end(), {"--format", format});
    if (!o->title.empty()) argv.insert(argv.end(), {"--title", o->title});
    for (const std::string& axis : o->axes) argv.insert(argv.end(), {"--axis", axis});
    const ProcessResult result = run_process(argv, /*capture=*/false);
    std::error_code ignored;
    std::filesystem::remove_all(scratch, ignored);
    if (!result.started) throw UserError(python + ": cannot run: " + result.output);
    return result.status;
  };
}

}  // namespace ldm::cli
