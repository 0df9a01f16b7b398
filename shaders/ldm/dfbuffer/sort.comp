// DF-buffer step 4, sorting (thesis §3.2.10, §3.3.3): one invocation per LDM pixel of all
// views sorts the pixel's contiguous range: through the local array when it fits, else by
// heap sort in place in the depth array (counted; ldm/common/heap_sort.glsl says why heap sort).
layout(local_size_x = 64) in;

#include "ldm/common/compute_grid.glsl"
#include "ldm/common/post_sort.glsl"
#include "ldm/dfbuffer/layout.glsl"

layout(std430, binding = DF_OFFSETS_BINDING) readonly restrict buffer DfOffsets {
  uint df_offsets[];
};
layout(std430, binding = DF_DEPTHS_BINDING) restrict buffer DfDepths {
  uint df_depths[];  // float bits
};
layout(binding = LDM_COUNTER_BINDING, offset = 8) uniform atomic_uint lists_sorted_in_place;

// The pixel's range, first .. end, for the in-place heap sort (the slow path).
uint heap_first;
uint heap_load(uint i) { return df_depths[heap_first + i]; }
void heap_store(uint i, uint bits) { df_depths[heap_first + i] = bits; }
#include "ldm/common/heap_sort.glsl"

void main() {
  const uint pixel = linear_invocation_index();
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint first = df_offsets[pixel];
  const uint end = min(df_offsets[pixel + 1u], LDM_DF_CAPACITY);
  if (end <= first + 1u) return;  // empty or one fragment: sorted already
  const uint count = end - first;
  if (count > LDM_SORT_LOCAL) {
    heap_first = first;
    heap_sort_in_place(count);
    atomicCounterIncrement(lists_sorted_in_place);
    return;
  }
  for (uint i = 0u; i < count; ++i) sort_local[i] = df_depths[first + i];
  insertion_sort_local(count);
  for (uint i = 0u; i < count; ++i) df_depths[first + i] = sort_local[i];
}
