#pragma once
// What one shader invocation of an LDM trace loops (shaders/passes/trace_steps.glsl), and
// whether the device could have cut it short. llvmpipe (Mesa's gallivm, LP_MAX_TGSI_LOOP_
// ITERATIONS) ends every loop of a SIMD group of invocations after 65,535 iterations in all,
// without an error: a hairball at large N walks N views x the list length and can pass it,
// returning a wrong image as if it were right. The passes count their walks' iterations per
// view; from the per-view maxima a bound on what any group ran follows (a group runs each
// loop as often as its longest invocation, so at most the sum over the loops of the most
// any invocation ran there). A bound at or past the device's limit makes the record invalid.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"
#include "harness/records/record.h"

namespace ldm {

struct TraceStepCounts {
  uint64_t max_per_invocation = 0;  // the most loop iterations one invocation ran
  uint64_t group_bound = 0;         // at least what any SIMD group of invocations ran
  uint32_t device_limit = 0;        // the device's loop limit per invocation; 0: none known
};

// The limit of the current context's device: 65,535 on llvmpipe, 0 (none) elsewhere.
uint32_t shader_loop_iteration_limit();

class TraceStepCounter {
 public:
  // `walk_sites`: the places in the shader a walk loop is compiled (the plane trace walks at
  // two, the grazing fallback and the main one: a group may run both for one view);
  // `fixed_iterations`: what the shader's other loops add per invocation.
  TraceStepCounter(uint32_t views, uint32_t walk_sites, uint32_t fixed_iterations);
  void clear();  // before the first frame: the counts are maxima over every frame since
  void bind() const;
  TraceStepCounts read() const;

 private:
  uint32_t views_, walk_sites_, fixed_;
  GlBuffer counts_;
};

// TRACE_STEPS_BINDING for the shaders.
void add_trace_step_defines(ShaderDefines& defines);
// The walk sites of a trace variant (see TraceStepCounter).
uint32_t trace_walk_sites(bool plane_trace);

// The record fields: trace_steps_max, trace_steps_bound, loop_iteration_limit.
std::vector<std::pair<std::string, RecordValue>> trace_step_fields(const TraceStepCounts& counts);
// Why the image may be wrong, or "" when the bound stays below the device's limit.
std::string trace_step_problem(const TraceStepCounts& counts);

}  // namespace ldm
