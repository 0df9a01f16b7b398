// The probe of barrier_in_divergent_loop.glsl in the compute stage: one work group of 64.
layout(local_size_x = PROBE_INVOCATIONS) in;
#include "probes/barrier_in_divergent_loop.glsl"

void main() { probe_invocation(gl_LocalInvocationID.x); }
