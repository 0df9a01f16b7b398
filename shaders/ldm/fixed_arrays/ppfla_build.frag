// PPFLA construction (thesis §3.2.6, "Fragment Storing"): a fragment takes entry
// count[pixel]++ of its pixel's array (atomicAdd, so concurrent fragments get distinct
// entries) and stores its depth there unsorted; the sort pass orders the entries afterwards.
// A fragment arriving after k others finds no entry: it is dropped and counted, so the build
// reports exactly sum over pixels of max(0, count - k) lost fragments.
#include "ldm/ldm_fragment.glsl"
#include "ldm/fixed_arrays/fixed_array.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) writeonly restrict buffer PpflaEntries {
  uint ppfla_entries[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) restrict buffer PpflaCounts {
  uint ppfla_counts[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint dropped_fragments;

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  const uint pixel = ldm_fragment_pixel();
  const uint slot = atomicAdd(ppfla_counts[pixel], 1u);
  if (slot < FA_K)
    ppfla_entries[fa_entry(pixel, slot)] = floatBitsToUint(v_depth);
  else
    atomicCounterIncrement(dropped_fragments);
}
