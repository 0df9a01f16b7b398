// PSPPFLA construction (thesis §3.2.7, "Fragment Storing"): insertion sort by atomicMin.
// The fragment's ordered depth walks its pixel's k entries; at each, atomicMin leaves the
// smaller of the entry and the carried value there and the larger one is carried on. Taking
// an empty entry ends the walk. Because each step is one atomic, concurrent insertions into
// the same pixel cannot corrupt it: every value is always either in one entry or carried by
// one invocation, and entries only decrease, so the array ends sorted and holds the pixel's
// k nearest depths. A value still carried after the k-th entry is dropped and counted; with
// FA_TRACK_OVERFLOW (the previous_frame sizing policy) also per pixel, so that the host
// learns the k this build needed (k + the most any pixel dropped).
#include "ldm/ldm_fragment.glsl"
#include "ldm/fixed_arrays/fixed_array.glsl"
#include "ldm/fixed_arrays/ordered_depth.glsl"

const uint FA_EMPTY = 0xFFFFFFFFu;  // the clear value; no depth maps to it

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PsppflaEntries {
  uint psppfla_entries[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint dropped_fragments;
#if FA_TRACK_OVERFLOW
layout(std430, binding = LDM_STRUCTURE_BINDING1) restrict buffer PsppflaOverflow {
  uint psppfla_overflow[];  // per pixel: fragments dropped beyond k
};
#endif

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  const uint pixel = ldm_fragment_pixel();
  const uint base = fa_entry(pixel, 0u);
  uint carried = ordered_depth_bits(v_depth);
  for (uint i = 0u; i < FA_K; ++i) {
    const uint previous = atomicMin(psppfla_entries[base + i], carried);
    if (previous == FA_EMPTY) return;  // the entry was free: the carried value now sits there
    carried = max(previous, carried);
  }
  atomicCounterIncrement(dropped_fragments);
#if FA_TRACK_OVERFLOW
  atomicAdd(psppfla_overflow[pixel], 1u);
#endif
}
