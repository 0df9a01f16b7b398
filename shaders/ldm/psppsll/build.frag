// PSPPSLL construction (thesis §3.4.2, Listing 3): every fragment allocates a node with the
// atomic counter and inserts it into its pixel's list in ascending depth, lock-free, by
// atomicCompSwap on the predecessor's next index. All views share one data buffer
// (ldm/common/list_nodes.glsl). A node past LDM_NODE_CAPACITY is not written: the host
// compares the counter with the capacity and records the overflow. An insertion that does not finish within
// LDM_MAX_INSERT_STEPS steps (impossible on a conforming device) is counted as lost.
//
// The barriers are memoryBarrier(), not the narrower memoryBarrierBuffer() that would do: the
// insertion loop is left by invocations at different iterations, and Mesa 22.3's lavapipe
// (under zink) runs every memory barrier but memoryBarrier() as a work-group execution barrier
// in compute shaders, which lost invocations mid-loop (1,500 of 3,500 fragments of the
// contention test). Both order this invocation's buffer writes the same way; the driver
// self-test (harness/gl/driver_probe.h) checks memoryBarrier() in such a loop on every driver,
// and the structure refuses to build where it fails.
#include "ldm/common/list_nodes.glsl"
#include "ldm/ldm_fragment.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) coherent restrict buffer PsppsllData {
  uint data[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint node_counter;
layout(binding = LDM_COUNTER_BINDING, offset = 4) uniform atomic_uint lost_counter;

// The thesis's driver workaround (§3.4.3): read next indices with a no-op atomic.
#if LDM_ATOMIC_READS
#define READ_NEXT(slot) atomicAdd(data[slot], 0u)
#else
#define READ_NEXT(slot) data[slot]
#endif

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  const uint pixel = ldm_fragment_pixel();
  const uint node = atomicCounterIncrement(node_counter) + 1u;
  if (node > LDM_NODE_CAPACITY) return;
  const float depth = v_depth;
  const uint node_slot = list_next_slot(node);
  data[list_depth_slot(node)] = floatBitsToUint(depth);

  uint previous_slot = pixel;  // the head index acts as the "next" field of a virtual node 0
  uint current = READ_NEXT(previous_slot);
  for (uint step = 0u; step < LDM_MAX_INSERT_STEPS; ++step) {
    if (current == 0u || depth < uintBitsToFloat(data[list_depth_slot(current)])) {
      // Complete the new node before it becomes visible to other invocations.
      data[node_slot] = current;
      memoryBarrier();
      const uint seen = atomicCompSwap(data[previous_slot], current, node);
      if (seen == current) return;
      // Another invocation inserted here first: continue from its node. Acquire: its depth
      // and next index were written before its compare-and-swap published it (the barrier
      // above, on its side); this barrier keeps our reads of them after our atomic.
      LDM_COUNT_RETRY();
      memoryBarrier();
      current = seen;
    } else {
      previous_slot = list_next_slot(current);
      current = READ_NEXT(previous_slot);
    }
  }
  atomicCounterIncrement(lost_counter);
}
