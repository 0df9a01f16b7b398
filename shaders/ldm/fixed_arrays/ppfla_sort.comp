// PPFLA "Sorting" (thesis §3.2.6): one invocation per LDM pixel sorts the pixel's
// min(count, k) entries in place by ascending depth. The thesis names bubble sort; heap sort
// does the same job in O(k log k) steps, which k up to the scene's depth complexity (1,024 and
// more) needs (ldm/common/heap_sort.glsl says why). Entries move as raw bits, bit-exact.
layout(local_size_x = 64) in;

#include "ldm/fixed_arrays/fixed_array.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PpflaEntries {
  uint ppfla_entries[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer PpflaCounts {
  uint ppfla_counts[];
};

// The pixel's entries, for the heap sort.
uint heap_base;
uint heap_load(uint i) { return ppfla_entries[heap_base + i]; }
void heap_store(uint i, uint bits) { ppfla_entries[heap_base + i] = bits; }
#include "ldm/common/heap_sort.glsl"

void main() {
  const uint pixel = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 64u) + gl_GlobalInvocationID.x;
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint count = min(ppfla_counts[pixel], FA_K);
  heap_base = fa_entry(pixel, 0u);
  heap_sort_in_place(count);
}
