#include "harness/settings/axis_registry.h"

#include <algorithm>
#include <sstream>

#include "harness/settings/harness_axes.h"
#include "harness/passes/pass.h"
#include "harness/util/text.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {
namespace {

// A Markdown table cell: a literal '|' (as in "sum V|cos|") would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string domain(const AxisSpec& a) {
  switch (a.kind) {
    case AxisKind::Choice: return joined(axis_choices(a), ", ");
    case AxisKind::UInt:
    case AxisKind::Real: return axis_range_text(a);
    case AxisKind::ImageSize: return "WxH, sides in " + axis_range_text(a);
    case AxisKind::Bool: return "true, false";
    default: return "text";
  }
}

std::string default_text(const AxisSpec& a) {
  return a.default_value.empty() ? a.default_note : a.default_value;
}

}  // namespace

std::vector<AxisSpec> registered_axes() {
  std::vector<AxisSpec> out;
  for (const HarnessAxis& axis : harness_axes()) out.push_back(axis.spec);
  auto add_parameters = [&out](const std::vector<AxisSpec>& declared) {
    for (const AxisSpec& p : declared)
      if (p.pass_parameter.empty()) out.push_back(p);  // the others are harness axes above
  };
  for (const auto& name : structure_names()) add_parameters(structure_parameters(name));
  for (const auto& name : pass_names()) add_parameters(pass_parameters(name));
  return out;
}

nlohmann::json axes_json() {
  const std::vector<std::string> structures = structure_names();
  nlohmann::json list = nlohmann::json::array();
  for (const AxisSpec& a : registered_axes()) {
    nlohmann::json j = axis_spec_json(a);
    j["owner_kind"] = a.owner == "harness" ? "harness"
                      : std::find(structures.begin(), structures.end(), a.owner) != structures.end() ? "structure"
                                                                                                     : "pass";
    list.push_back(j);
  }
  return {{"axes", list}};
}

std::string axes_markdown() {
  std::ostringstream out;
  out << "| axis | set by | kind | values | default | unit | identity | description |\n"
      << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const AxisSpec& a : registered_axes()) {
    const std::string set_by = a.owner == "harness"
                                   ? (a.flags.empty() ? "sweep files" : "`" + a.flags + "`")
                                   : "`--param " + a.qualified() + "=`";
    out << "| `" << a.qualified() << "` | " << set_by << " | " << axis_kind_name(a.kind) << " | "
        << cell(domain(a)) << " | " << cell(default_text(a)) << " | " << cell(a.unit) << " | "
        << (a.identity ? "yes" : "no (a note)") << " | " << cell(a.description)
        << (a.ldm_only ? " (LDM passes only)" : "") << " |\n";
  }
  return out.str();
}

std::string axes_text() {
  std::ostringstream out;
  for (const AxisSpec& a : registered_axes()) {
    out << a.qualified() << "\t" << axis_kind_name(a.kind) << "\t" << domain(a) << "\t"
        << "default: " << (default_text(a).empty() ? "-" : default_text(a)) << "\n";
    out << "    " << a.description;
    if (!a.flags.empty()) out << " (" << a.flags << ")";
    out << "\n";
  }
  return out.str();
}

}  // namespace ldm
