#include "harness/settings/record_schema.h"

#include <algorithm>
#include <set>

#include "harness/settings/harness_axes.h"
#include "harness/passes/pass.h"
#include "harness/records/harness_columns.h"
#include "harness/util/text.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

const std::vector<std::string>& always_written_columns() {
  using namespace columns;
  static const std::vector<std::string> columns = {
      kConfigId.name, kStatus.name, kStatusDetail.name, kScene.name, kStructure.name, kPass.name,
      kNViews.name,   kRLdm.name,   kWidth.name,        kHeight.name, kLdmbenchVersion.name,
      kGitCommit.name, kWallSeconds.name};
  return columns;
}

std::string declared_columns_text() {
  std::vector<std::string> names;
  for (const auto& column : record_columns()) names.push_back(column.name);
  return joined(names, " ");
}

std::string always_written_columns_text() { return joined(always_written_columns(), " "); }

std::vector<WorkCounter> configuration_work_counters(const std::string& structure, const std::string& pass) {
  std::vector<WorkCounter> counters;
  if (structure != "none" && !structure.empty()) {
    counters = structure_work_counters(structure);
    // The census sizing policy's count pass runs the same geometry pass in every frame.
    for (WorkCounter c : geometry_work_counters("census")) counters.push_back(std::move(c));
  }
  for (WorkCounter c : pass_work_counters(pass)) counters.push_back(std::move(c));
  if (structure != "none" && !structure.empty())
    for (const auto& subpass : pass_query_subpasses(pass))
      for (WorkCounter c : structure_query_work_counters(structure, subpass)) counters.push_back(std::move(c));
  return counters;
}

namespace {
// Every counter any configuration can record: the columns of group "work".
std::vector<ColumnSpec> all_work_columns() {
  std::vector<WorkCounter> counters;
  for (const auto& structure : structure_names())
    for (WorkCounter c : structure_work_counters(structure)) counters.push_back(std::move(c));
  for (WorkCounter c : geometry_work_counters("census")) counters.push_back(std::move(c));
  for (const auto& pass : pass_names()) {
    for (WorkCounter c : pass_work_counters(pass)) counters.push_back(std::move(c));
    for (const auto& subpass : pass_query_subpasses(pass))
      for (const auto& structure : structure_names())
        for (WorkCounter c : structure_query_work_counters(structure, subpass)) counters.push_back(std::move(c));
  }
  std::vector<ColumnSpec> columns = work_columns(counters);
  // The driver's pipeline statistics of every sub-pass that declares counters: the driver's
  // count, which another driver may count differently (not deterministic across drivers).
  for (const PipelineStatistic& statistic : pipeline_statistics()) {
    ColumnSpec c("work", std::string("work_<subpass>_gl_") + statistic.name, statistic.unit,
                 std::string("<subpass>: ") + statistic.description +
                     ", from GL_ARB_pipeline_statistics_query in the counting replay, where the driver has it",
                 ColumnKind::Number, VariesBetweenRuns::Yes, Better::Lower);
    c.deterministic = false;  // compared within --work-tolerance; another driver counts otherwise
    columns.push_back(std::move(c));
  }
  return columns;
}
}  // namespace

const std::vector<ColumnSpec>& record_columns() {
  static const std::vector<ColumnSpec> columns = [] {
    std::vector<ColumnSpec> passes;
    std::set<std::string> seen;
    for (const auto& name : pass_names())
      for (ColumnSpec c : pass_columns(name)) {
        if (!seen.insert(c.name).second) continue;
        c.group = "pass";
        passes.push_back(std::move(c));
      }
    std::vector<ColumnSpec> all = harness_record_columns();
    const auto census = std::find_if(all.begin(), all.end(), [](const ColumnSpec& c) { return c.group == "census"; });
    all.insert(census, passes.begin(), passes.end());
    // A pass's own declaration of a work column (the GPU ray tracer's) stands.
    for (ColumnSpec& c : all_work_columns())
      if (std::none_of(all.begin(), all.end(), [&](const ColumnSpec& d) { return d.name == c.name; }))
        all.push_back(std::move(c));
    return all;
  }();
  return columns;
}

const ColumnSpec* find_column(const std::string& column) { return find_column_in(record_columns(), column); }

bool is_declared_column(const std::string& column) {
  if (find_column(column)) return true;
  const std::vector<std::string> axis_columns = axis_column_names();
  return std::find(axis_columns.begin(), axis_columns.end(), column) != axis_columns.end();
}

Record measurement_record() { return Record(&is_declared_column); }

std::string columns_markdown() { return columns_markdown(record_columns()); }

std::string columns_text() { return columns_text(record_columns()); }

std::string columns_json() { return columns_json(record_columns()); }

}  // namespace ldm
