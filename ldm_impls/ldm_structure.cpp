#include "ldm_impls/ldm_structure.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "harness/gl/gl_api.h"
#include "harness/util/error.h"

namespace ldm {

std::string FragmentPayload::describe() const {
  std::string s = "depth";
  if (normal) s += "+normal";
  if (albedo) s += "+albedo";
  return s;
}

namespace {
std::string param_context(const std::string& context, const std::string& key) {
  return (context.empty() ? std::string("structure parameter") : context) + " '" + key + "'";
}
}  // namespace

const AxisSpec& StructureParams::spec(const std::string& key) const {
  if (const AxisSpec* s = find_axis(specs_, key)) return *s;
  throw std::logic_error("parameter '" + key + "' is read but not declared");
}

std::string StructureParams::text(const std::string& key, AxisKind kind) const {
  const AxisSpec& declared = spec(key);
  if (declared.kind != kind)
    throw std::logic_error("parameter '" + key + "' is read as another kind than declared");
  const auto it = values_.find(key);
  if (it != values_.end()) return canonical_axis_value(declared, it->second, param_context(context_, key));
  if (declared.default_value.empty())
    throw std::logic_error("parameter '" + key + "' has no default: read it only when has()");
  return declared.default_value;
}

uint64_t StructureParams::get_uint(const std::string& key) const {
  return std::strtoull(text(key, AxisKind::UInt).c_str(), nullptr, 10);
}

double StructureParams::get_double(const std::string& key) const {
  return std::strtod(text(key, AxisKind::Real).c_str(), nullptr);
}

std::string StructureParams::get_choice(const std::string& key) const {
  return text(key, AxisKind::Choice);
}

bool StructureParams::get_bool(const std::string& key) const { return text(key, AxisKind::Bool) == "true"; }

void StructureParams::check(const std::string& owner) const {
  for (const auto& [key, value] : values_) {
    const AxisSpec* declared = find_axis(specs_, key);
    if (!declared) {
      std::string known;
      for (const auto& s : specs_)
        if (s.pass_parameter.empty()) known += (known.empty() ? "" : ", ") + s.key;
      throw UserError(owner + " has no parameter '" + key + "' (its parameters: " +
                      (known.empty() ? "none" : known) + ")");
    }
    canonical_axis_value(*declared, value, param_context(context_, key));
  }
}

uint64_t checked_storage_block(const std::string& structure, const std::string& buffer,
                               uint64_t bytes, uint32_t entries_per_pixel) {
  GLint64 limit = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
  if (bytes > uint64_t(limit)) {
    auto mib = [](uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
    throw StorageBlockExceeded(structure + " needs " + mib(bytes) + " in its storage block '" +
                                   buffer + "', more than this device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " +
                                   mib(uint64_t(limit)) + "; lower N or R_LDM",
                               structure, buffer, bytes, uint64_t(limit), entries_per_pixel);
  }
  return bytes;
}

ShaderDefines common_structure_defines(const BuildInputs& in) {
  return common_structure_defines(in.views.views().total_pixels());
}

ShaderDefines common_structure_defines(uint64_t ldm_pixels) {
  ShaderDefines d;
  d.set("LDM_HEADS_TOTAL", std::to_string(ldm_pixels) + "u");
  d.set("LDM_MAX_LIST_LENGTH", std::to_string(kMaxListWalk) + "u");
  return d;
}

std::string size_source(const SizingPlan& plan, bool explicit_parameter) {
  return explicit_parameter ? "parameter" : sizing_policy_name(plan.policy);
}

uint64_t budget_after(const std::string& structure, const SizingPlan& plan, uint64_t fixed_bytes) {
  if (plan.budget_bytes <= fixed_bytes) {
    auto mib = [](uint64_t b) { return std::to_string(double(b) / double(1u << 20)) + " MiB"; };
    throw UserError(structure + ": the sizing budget of " + mib(plan.budget_bytes) +
                    " does not hold its fixed buffers (" + mib(fixed_bytes) +
                    "); raise --sizing-budget-mib or lower N or R_LDM");
  }
  return plan.budget_bytes - fixed_bytes;
}

std::vector<WorkCounter> draw_work_counters(const std::string& subpass,
                                            const std::string& vertices_what,
                                            const std::string& fragments_what) {
  return {{subpass, "vertices", WorkShape::Total, "invocations", subpass + ": " + vertices_what},
          {subpass, "fragments", WorkShape::Total, "fragments", subpass + ": " + fragments_what}};
}

std::vector<WorkCounter> geometry_work_counters(const std::string& subpass) {
  return draw_work_counters(subpass,
                            "vertex shader invocations of the LDM geometry pass (every view's "
                            "instance; an indexed draw's post-transform cache may shade a shared "
                            "vertex once)",
                            "fragments shaded (helper invocations left out), counted by the shader");
}

}  // namespace ldm
