// The list of passes `--pass` accepts, each with its declared parameters and record columns.
// A new pass adds one line here.
#include <cstdlib>
#include <functional>
#include <stdexcept>

#include "harness/passes/ambient_occlusion.h"
#include "harness/passes/gtao.h"
#include "harness/passes/hbao.h"
#include "harness/passes/indirect_lighting.h"
#include "harness/passes/pass.h"
#include "harness/passes/rtao.h"
#include "harness/passes/rtao_gpu.h"
#include "harness/util/error.h"
#include "harness/axes/named_registry.h"

namespace ldm {
namespace {

using Entry = PassRegistration;

std::vector<Entry>& registry() {
  static std::vector<Entry> entries = {
      {"ao", AmbientOcclusion::parameters, AmbientOcclusion::columns, [](StructureParams& p) { return std::make_unique<AmbientOcclusion>(p); }, AmbientOcclusion::work_counters, {"ao"}},
      {"hbao", Hbao::parameters, Hbao::columns, [](StructureParams& p) { return std::make_unique<Hbao>(p); }, Hbao::work_counters},
      {"gtao", Gtao::parameters, Gtao::columns, [](StructureParams& p) { return std::make_unique<Gtao>(p); }, Gtao::work_counters},
      {"rtao", Rtao::parameters, Rtao::columns, [](StructureParams& p) { return std::make_unique<Rtao>(p); }},
      {"rtao_gpu", RtaoGpu::parameters, RtaoGpu::columns, [](StructureParams& p) { return std::make_unique<RtaoGpu>(p); }, RtaoGpu::work_counters},
      {"indirect", IndirectLighting::parameters, IndirectLighting::columns, [](StructureParams& p) { return std::make_unique<IndirectLighting>(p); }, IndirectLighting::work_counters, {"photon_tracing", "photon_census", "photon_rebuild"}},
  };
  return entries;
}

const Entry& entry(const std::string& name) { return registry_entry(registry(), name, "--pass", "pass"); }

}  // namespace

std::vector<std::string> pass_names() { return registry_names(registry()); }

std::vector<AxisSpec> pass_parameters(const std::string& name) { return registry_parameters(entry(name)); }

// A parameter's column, declared by the parameter itself: its unit, its description and the
// option that sets it, so that the pass's columns() need not (and must not) repeat them.
ColumnSpec parameter_column(const AxisSpec& parameter) {
  const ColumnKind kind = parameter.kind == AxisKind::UInt || parameter.kind == AxisKind::Real ? ColumnKind::Number
                          : parameter.kind == AxisKind::Bool                                   ? ColumnKind::Flag
                                                                                                : ColumnKind::Text;
  std::string choices;
  for (const std::string& choice : parameter.choices) choices += (choices.empty() ? "; one of " : ", ") + choice;
  return {"pass", parameter.column, parameter.unit,
          parameter.owner + ": " + parameter.description + " (--param " + parameter.owner + ":" + parameter.key + "=" +
              choices + ")",
          kind};
}

// Whether a parameter has a record column of its own. The AO axes the AO passes share (their
// pass_parameter versions) are the AO settings' columns (ao_setting_columns(): the value in
// effect, the scene's where not given), which the passes' describe() writes.
bool has_parameter_column(const AxisSpec& parameter) {
  return !parameter.column.empty() && parameter.pass_parameter.empty();
}

std::vector<ColumnSpec> pass_columns(const std::string& name) {
  std::vector<ColumnSpec> columns;
  for (const AxisSpec& parameter : pass_parameters(name))
    if (has_parameter_column(parameter)) columns.push_back(parameter_column(parameter));
  for (ColumnSpec& column : entry(name).columns()) columns.push_back(std::move(column));
  return columns;
}

std::vector<std::pair<std::string, RecordValue>> pass_parameter_values(const std::string& name,
                                                                       const AxisValues& values) {
  std::vector<std::pair<std::string, RecordValue>> out;
  for (const AxisSpec& parameter : pass_parameters(name)) {
    if (!has_parameter_column(parameter)) continue;
    // Canonical text: given (checked against the declaration), or the declared default,
    // which is what StructureParams hands the pass when the configuration gives none.
    const std::string text = axis_text(values, parameter.qualified()).value_or(parameter.default_value);
    if (text.empty()) continue;  // no default: the value the pass derives (its describe())
    switch (parameter.kind) {
      case AxisKind::UInt: out.emplace_back(parameter.column, int64_t(std::strtoull(text.c_str(), nullptr, 10))); break;
      case AxisKind::Real: out.emplace_back(parameter.column, std::strtod(text.c_str(), nullptr)); break;
      case AxisKind::Bool: out.emplace_back(parameter.column, text == "true"); break;
      default: out.emplace_back(parameter.column, text);
    }
  }
  return out;
}

std::vector<std::string> pass_query_subpasses(const std::string& name) { return entry(name).query_subpasses; }

std::vector<WorkCounter> pass_work_counters(const std::string& name) {
  const Entry& e = entry(name);
  return e.work ? e.work() : std::vector<WorkCounter>();
}

void register_pass(PassRegistration registration) {
  for (const auto& e : registry())
    if (e.name == registration.name) throw std::logic_error("pass '" + e.name + "' is registered twice");
  registry().push_back(std::move(registration));
}

std::unique_ptr<Pass> make_pass(const std::string& name, StructureParams params) {
  return registry_make(entry(name), std::move(params), "pass");
}

}  // namespace ldm
