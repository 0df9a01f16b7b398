// PPFLA "Sorting" (thesis §3.2.6): one invocation per LDM pixel sorts the pixel's
// min(count, k) entries in place by ascending depth. The thesis names bubble sort; heap sort
// does the same job in O(k log k) steps, which k up to the scene's depth complexity (1,024 and
// more) needs (ldm/common/heap_sort.glsl says why). Entries move as raw bits, bit-exact.
// Work counted (Ppfla::work_counters()): invocations, each pixel's list length and the bytes
// its sort moves (heap_load/heap_store below; how many depends on the order the entries
// arrived in, as heap_sort.glsl's comparisons and moves do).
layout(local_size_x = 64) in;

#include "common/work_counters.glsl"
#include "ldm/fixed_arrays/fixed_array.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PpflaEntries {
  uint ppfla_entries[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer PpflaCounts {
  uint ppfla_counts[];
};

#if WORK_COUNTING
uint sort_loads = 0u, sort_stores = 0u;  // entries this invocation's sort read and wrote
#define PPFLA_COUNT(statement) statement
#else
#define PPFLA_COUNT(statement)
#endif

// The pixel's entries, for the heap sort.
uint heap_base;
uint heap_load(uint i) {
  PPFLA_COUNT(++sort_loads);
  return ppfla_entries[heap_base + i];
}
void heap_store(uint i, uint bits) {
  PPFLA_COUNT(++sort_stores);
  ppfla_entries[heap_base + i] = bits;
}
#include "ldm/common/heap_sort.glsl"

void main() {
  // Every invocation of the dispatch, those past the last pixel included: one add per group.
  if (gl_LocalInvocationIndex == 0u) work_add(invocations, gl_WorkGroupSize.x);
  const uint pixel = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 64u) + gl_GlobalInvocationID.x;
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint count = min(ppfla_counts[pixel], FA_K);
  heap_base = fa_entry(pixel, 0u);
  heap_sort_in_place(count);
  work_add(bytes_loaded_counts, 4u);
  work_sample(list_length, count);
  work_add(bytes_loaded_entries, sort_loads * 4u);
  work_add(bytes_stored_entries, sort_stores * 4u);
}
