#include "harness/passes/ldm_trace_defines.h"

#include <cctype>
#include <cstdio>
#include <string>

#include "harness/passes/trace_steps.h"

namespace ldm {
namespace {

std::string upper(std::string text) {
  for (char& c : text) c = char(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

std::string glsl_float(double value) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  std::string text = buffer;
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

void add_ldm_trace_defines(ShaderDefines& defines, const LdmStructure& structure,
                           size_t view_count, AoTrace trace) {
  const ShaderDefines query = structure.query_defines();
  defines.values.insert(defines.values.end(), query.values.begin(), query.values.end());
  defines.set("LDM_VIEW_COUNT", std::to_string(view_count) + "u");
  defines.set("LDM_TRACE", "LDM_TRACE_" + upper(ao_trace_name(trace)));
  defines.set("LDM_PLANE_TOLERANCE_CONSTANT", glsl_float(kPlaneToleranceConstant));
  defines.set("LDM_PLANE_TOLERANCE_SLOPE", glsl_float(kPlaneToleranceSlope));
  defines.set("LDM_PLANE_MAX_SLOPE", glsl_float(kPlaneMaxSlope));
  add_trace_step_defines(defines);
}

}  // namespace ldm
