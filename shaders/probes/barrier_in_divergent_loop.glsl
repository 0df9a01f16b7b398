// The driver self-test for a memory barrier inside a loop whose invocations leave at
// different iterations (harness/gl/driver_probe.h; docs/reference/structures.md#driver-conformance).
// GLSL allows memoryBarrier*() anywhere; only barrier() must be reached in uniform control
// flow. A driver that runs a memory barrier as a work-group execution barrier loses the
// invocations whose SIMD vector passes it more often than another vector of its group: they
// wait for the others at a barrier those never reach. PSPPSLL's lock-free insertion (its
// retry loop) is such a loop.
//
// Invocation i passes PROBE_BARRIER() 1 + i / 8 times (each SIMD vector of 8 lanes a different
// number of times; 1 + i % 8 would vary the lanes of one vector instead), then marks its word.
// Every word must be 1 afterwards.
layout(std430, binding = PROBE_MARKS_BINDING) restrict buffer ProbeMarks {
  uint probe_marks[];
};

void probe_invocation(uint i) {
  for (uint pass = 0u; pass <= i / 8u; ++pass) PROBE_BARRIER();
#if PROBE_DROP_SOME
  // The self-test of the self-test: a driver that loses these invocations must be caught.
  if (i % 8u == 3u) return;
#endif
  probe_marks[i] = 1u;
}
