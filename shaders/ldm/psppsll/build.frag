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
//
// Work counted (Psppsll::work_counters(), tallied in locals, added once per fragment): the
// node counter's increments; compare-and-swaps and failed ones; the insertion's steps; the
// head read, the walk's node reads, the node's depth and first link, and its link rewritten
// after each failed compare-and-swap. Everything the walk does depends on the order the
// fragments arrive, except the head read and the node's own depth and first link.
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

#if WORK_COUNTING
bool work_allocated = false;  // the insertion got a node (its tally is flushed)
uint work_steps = 0u, work_cas = 0u, work_cas_failed = 0u;
uint work_node_loads = 0u;  // walk reads of nodes (a depth or a next index)
uint work_links = 0u;       // writes of the new node's next index
#define PSPPSLL_COUNT(statement) statement
// The insertion's tally, added once after psppsll_insert() returns (not at the returns inside
// its loop, where a SIMD rasteriser would run these atomics, masked, on every iteration).
void psppsll_work_flush() {
  if (!work_allocated) return;
  work_add(atomic_add, 1u);
  work_add(bytes_loaded_heads, 4u);
  work_add(bytes_stored_nodes, 4u + 4u * min(work_links, 1u));
  work_add(bytes_stored_nodes_relinked, 4u * (work_links - min(work_links, 1u)));
  work_add(bytes_loaded_nodes, 4u * work_node_loads);
  work_add(atomic_cas, work_cas);
  work_add(atomic_cas_failed, work_cas_failed);
  work_sample(insert_steps, work_steps);
}
#define PSPPSLL_FLUSH() psppsll_work_flush()
#else
#define PSPPSLL_COUNT(statement)
#define PSPPSLL_FLUSH()
#endif

// One fragment's insertion: a node allocated and linked in depth order, or lost.
void psppsll_insert() {
  const uint pixel = ldm_fragment_pixel();
  const uint node = atomicCounterIncrement(node_counter) + 1u;
  if (node > LDM_NODE_CAPACITY) {
    work_add(atomic_add, 1u);
    return;
  }
  PSPPSLL_COUNT(work_allocated = true);
  const float depth = v_depth;
  const uint node_slot = list_next_slot(node);
  data[list_depth_slot(node)] = floatBitsToUint(depth);

  uint previous_slot = pixel;  // the head index acts as the "next" field of a virtual node 0
  uint current = READ_NEXT(previous_slot);
  for (uint step = 0u; step < LDM_MAX_INSERT_STEPS; ++step) {
    PSPPSLL_COUNT(++work_steps);
    if (current == 0u || depth < uintBitsToFloat(data[list_depth_slot(current)])) {
      PSPPSLL_COUNT(work_node_loads += current == 0u ? 0u : 1u);
      // Complete the new node before it becomes visible to other invocations.
      data[node_slot] = current;
      PSPPSLL_COUNT(++work_links);
      memoryBarrier();
      const uint seen = atomicCompSwap(data[previous_slot], current, node);
      PSPPSLL_COUNT(++work_cas);
      if (seen == current) return;
      // Another invocation inserted here first: continue from its node. Acquire: its depth
      // and next index were written before its compare-and-swap published it (the barrier
      // above, on its side); this barrier keeps our reads of them after our atomic.
      LDM_COUNT_RETRY();
      PSPPSLL_COUNT(++work_cas_failed);
      memoryBarrier();
      current = seen;
    } else {
      PSPPSLL_COUNT(work_node_loads += 2u);  // current's depth, then its next index
      previous_slot = list_next_slot(current);
      current = READ_NEXT(previous_slot);
    }
  }
  atomicCounterIncrement(lost_counter);
  work_add(atomic_add, 1u);  // the lost counter's increment
}

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  psppsll_insert();
  PSPPSLL_FLUSH();
}
