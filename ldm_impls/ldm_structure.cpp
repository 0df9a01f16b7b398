#include "ldm_impls/ldm_structure.h"

#include <algorithm>
#include <cstdlib>

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

uint64_t StructureParams::get_uint(const std::string& key, uint64_t fallback, uint64_t lo,
                                   uint64_t hi) {
  read_.push_back(key);
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(it->second.c_str(), &end, 10);
  if (it->second.empty() || *end != '\0' || it->second[0] == '-')
    throw UserError(param_context(context_, key) + ": '" + it->second +
                    "' is not a non-negative integer");
  if (v < lo || v > hi)
    throw UserError(param_context(context_, key) + ": " + it->second + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

double StructureParams::get_double(const std::string& key, double fallback, double lo, double hi) {
  read_.push_back(key);
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0')
    throw UserError(param_context(context_, key) + ": '" + it->second + "' is not a number");
  if (!(v >= lo && v <= hi))
    throw UserError(param_context(context_, key) + ": " + it->second + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

std::string StructureParams::get_choice(const std::string& key, const std::string& fallback,
                                        const std::vector<std::string>& allowed) {
  read_.push_back(key);
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  if (std::find(allowed.begin(), allowed.end(), it->second) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw UserError(param_context(context_, key) + ": '" + it->second + "' is not one of " + list);
  }
  return it->second;
}

bool StructureParams::get_bool(const std::string& key, bool fallback) {
  const std::string v = get_choice(key, fallback ? "1" : "0", {"0", "1", "true", "false"});
  return v == "1" || v == "true";
}

void StructureParams::finish(const std::string& owner) const {
  for (const auto& [key, value] : values_)
    if (std::find(read_.begin(), read_.end(), key) == read_.end())
      throw UserError(owner + " has no parameter '" + key + "'");
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

}  // namespace ldm
