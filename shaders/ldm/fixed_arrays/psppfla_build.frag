// PSPPFLA construction (thesis §3.2.7, "Fragment Storing"): insertion sort by atomicMin.
// The fragment's ordered depth walks its pixel's k entries; at each, atomicMin leaves the
// smaller of the entry and the carried value there and the larger one is carried on. Taking
// an empty entry ends the walk. Because each step is one atomic, concurrent insertions into
// the same pixel cannot corrupt it: every value is always either in one entry or carried by
// one invocation, and entries only decrease, so the array ends sorted and holds the pixel's
// k nearest depths. A value still carried after the k-th entry is dropped and counted; with
// FA_TRACK_OVERFLOW (the previous_frame sizing policy) also per pixel, so that the host
// learns the k this build needed (k + the most any pixel dropped).
// Work counted (Psppfla::work_counters()): the atomicMin per fragment are deterministic (each
// walk ends at the first empty entry it meets and every entry ends exactly one walk, so a
// pixel of c fragments takes 1 + 2 + ... + min(c, k) of them, plus k per dropped fragment,
// whatever the order); the entries each one shifted depend on the order they arrived.
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

#if WORK_COUNTING
uint fa_walked = 0u;   // atomicMin: entries walked
uint fa_shifted = 0u;  // entries whose depth the carried one replaced (carried on instead)

void fa_count_insertion() {
  work_add(atomic_min, fa_walked);
  // An atomic reads and writes its word: counted as loaded and stored.
  work_add(bytes_loaded_entries, fa_walked * 4u);
  work_add(bytes_stored_entries, fa_walked * 4u);
  work_sample(slots_shifted, fa_shifted);
}
#define FA_COUNT(statement) statement
#else
#define FA_COUNT(statement)
#endif

// One fragment's insertion, carried along the pixel's k entries by atomicMin. Its tally is
// added once after it returns (fa_count_insertion() in main), not at the return inside the
// loop, where a SIMD rasteriser would run the counting's atomics, masked, on every iteration.
void psppfla_insert() {
  const uint pixel = ldm_fragment_pixel();
  const uint base = fa_entry(pixel, 0u);
  uint carried = ordered_depth_bits(v_depth);
  for (uint i = 0u; i < FA_K; ++i) {
    const uint previous = atomicMin(psppfla_entries[base + i], carried);
    FA_COUNT(++fa_walked);
    if (previous == FA_EMPTY) return;  // the entry was free: the carried value now sits there
    FA_COUNT(fa_shifted += previous > carried ? 1u : 0u);
    carried = max(previous, carried);
  }
  atomicCounterIncrement(dropped_fragments);
  work_add(fragments_dropped, 1u);
  work_add(atomic_add, 1u);
#if FA_TRACK_OVERFLOW
  atomicAdd(psppfla_overflow[pixel], 1u);
  work_add(atomic_add, 1u);
  work_add(bytes_loaded_overflow_counts, 4u);
  work_add(bytes_stored_overflow_counts, 4u);
#endif
}

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  psppfla_insert();
  FA_COUNT(fa_count_insertion());
}
