// DF-buffer step 3, fragment storing (thesis §3.2.10): a fragment of pixel p goes to slot
// offset[p] + (--count[p]), the decrement atomic. The slots of a pixel are handed out from
// the top of its range, and count[p] ends at 0 again once every fragment has been stored.
// A fragment that finds no slot is counted, never dropped silently:
//   lost_beyond_count     count[p] was already 0: more fragments than the count pass saw
//   lost_beyond_capacity  its slot lies past the depth array (the scan's total exceeds it)
// Work counted (DfBuffer::work_counters(), "construct", deterministic): the atomics (the
// decrement; a lost fragment's counter), the two offsets read and the depth stored.
#include "ldm/ldm_fragment.glsl"
#include "ldm/dfbuffer/layout.glsl"

layout(std430, binding = DF_COUNTS_BINDING) restrict buffer DfCounts { uint df_counts[]; };
layout(std430, binding = DF_OFFSETS_BINDING) readonly restrict buffer DfOffsets {
  uint df_offsets[];
};
layout(std430, binding = DF_DEPTHS_BINDING) writeonly restrict buffer DfDepths {
  uint df_depths[];  // float bits
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint lost_beyond_count;
layout(binding = LDM_COUNTER_BINDING, offset = 4) uniform atomic_uint lost_beyond_capacity;

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  const uint pixel = ldm_fragment_pixel();
  const uint first = df_offsets[pixel];
  const uint length = df_offsets[pixel + 1u] - first;
  // atomicAdd of -1 returns the old count: k = --count. A count already at 0 wraps, and so
  // does k, past any length.
  const uint k = atomicAdd(df_counts[pixel], 0xffffffffu) - 1u;
  work_add(bytes_loaded_offsets, 8u);
  if (k >= length) {
    atomicCounterIncrement(lost_beyond_count);
    work_add(atomic_add, 2u);
    return;
  }
  const uint slot = first + k;
  if (slot >= LDM_DF_CAPACITY) {
    atomicCounterIncrement(lost_beyond_capacity);
    work_add(atomic_add, 2u);
    return;
  }
  df_depths[slot] = floatBitsToUint(v_depth);
  work_add(atomic_add, 1u);
  work_add(bytes_stored_depths, 4u);
}
