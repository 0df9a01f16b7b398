// PPFLA construction (thesis §3.2.6, "Fragment Storing"): a fragment takes entry
// count[pixel]++ of its pixel's array (atomicAdd, so concurrent fragments get distinct
// entries) and stores its depth there unsorted; the sort pass orders the entries afterwards.
// A fragment arriving after k others finds no entry: it is dropped and counted, so the build
// reports exactly sum over pixels of max(0, count - k) lost fragments.
// Work counted (Ppfla::work_counters(), all deterministic: which fragment gets which entry
// depends on arrival, how many entries each pixel fills does not).
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
  // An atomic reads and writes its word: counted as loaded and stored.
  work_add(atomic_add, 1u);
  work_add(bytes_loaded_counts, 4u);
  work_add(bytes_stored_counts, 4u);
  if (slot < FA_K) {
    ppfla_entries[fa_entry(pixel, slot)] = floatBitsToUint(v_depth);
    work_add(bytes_stored_entries, 4u);
  } else {
    atomicCounterIncrement(dropped_fragments);
    work_add(atomic_add, 1u);
    work_add(fragments_dropped, 1u);
  }
}
