// Counting what one invocation loops, for llvmpipe's loop limiter: Mesa's gallivm counts
// every loop iteration of a SIMD group of invocations against one limit of 65,535 (shared by
// all loops of the shader) and then ends every loop silently. A trace through long lists at
// large N could so return a wrong image that no other check notices. Recorded here, per
// view, the most iterations any invocation's walk (and the structure's own query loops) ran
// there, and in the last slot the most any invocation ran in all, its view loop included;
// harness/passes/trace_steps.h bounds from them what any group ran.
#include "passes/ldm_trace.glsl"

layout(std430, binding = TRACE_STEPS_BINDING) restrict buffer TraceSteps {
  uint trace_steps[];  // [0, LDM_VIEW_COUNT): per view; [LDM_VIEW_COUNT]: one invocation's total
};

uint trace_steps_so_far() { return ldm_walk_steps + ldm_query_loop_steps; }

// The maximum only grows: an invocation that reads one at least as large as its own count
// needs no atomic (most do, once the first invocations have run).
void trace_steps_max(uint slot, uint steps) {
  if (steps > trace_steps[slot]) atomicMax(trace_steps[slot], steps);
}
