#include "harness/passes/trace_steps.h"

#include <cstring>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_api.h"

namespace ldm {
namespace {

// After the harness's passes and the materials' bindings (harness/gl/bindings.h).
constexpr uint32_t kTraceStepsBinding = kPassBinding0 + 6;

// gallivm's LP_MAX_TGSI_LOOP_ITERATIONS (Mesa src/gallium/auxiliary/gallivm/lp_bld_limits.h:
// "Maximum iterations before loop termination. Shared between every loop in a TGSI shader").
constexpr uint32_t kLlvmpipeLoopLimit = 65535;

}  // namespace

uint32_t shader_loop_iteration_limit() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer && std::strstr(renderer, "llvmpipe") ? kLlvmpipeLoopLimit : 0;
}

TraceStepCounter::TraceStepCounter(uint32_t views, uint32_t walk_sites, uint32_t fixed_iterations)
    : views_(views),
      walk_sites_(walk_sites),
      fixed_(fixed_iterations),
      counts_("trace_steps", (uint64_t(views) + 1) * sizeof(uint32_t)) {
  clear();
}

void TraceStepCounter::clear() { counts_.clear_to_zero(); }

void TraceStepCounter::bind() const { counts_.bind_storage(kTraceStepsBinding); }

TraceStepCounts TraceStepCounter::read() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  const std::vector<uint32_t> counts = counts_.download_all<uint32_t>();
  TraceStepCounts c;
  c.device_limit = shader_loop_iteration_limit();
  c.max_per_invocation = counts[views_];
  // The view loop's iterations, the other loops', and each walk site's longest walk per view.
  uint64_t walks = 0;
  for (uint32_t v = 0; v < views_; ++v) walks += counts[v];
  c.group_bound = uint64_t(fixed_) + views_ + uint64_t(walk_sites_) * walks;
  return c;
}

void add_trace_step_defines(ShaderDefines& defines) {
  defines.set("TRACE_STEPS_BINDING", kTraceStepsBinding);
}

uint32_t trace_walk_sites(bool plane_trace) { return plane_trace ? 2 : 1; }

std::vector<std::pair<std::string, RecordValue>> trace_step_fields(const TraceStepCounts& c) {
  return {{"trace_steps_max", int64_t(c.max_per_invocation)},
          {"trace_steps_bound", int64_t(c.group_bound)},
          {"loop_iteration_limit", int64_t(c.device_limit)}};
}

std::string trace_step_problem(const TraceStepCounts& c) {
  if (c.device_limit == 0 || c.group_bound < c.device_limit) return {};
  return "the trace may have been cut short: a group of shader invocations may have looped up "
         "to " + std::to_string(c.group_bound) + " times (one invocation at most " +
         std::to_string(c.max_per_invocation) + "), and this device ends every loop of an "
         "invocation silently after " + std::to_string(c.device_limit) +
         " iterations in all (llvmpipe); lower N, or use shorter lists";
}

}  // namespace ldm
