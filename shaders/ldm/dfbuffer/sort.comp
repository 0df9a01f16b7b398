// DF-buffer step 4, sorting (thesis §3.2.10, §3.3.3): one invocation per LDM pixel of all
// views sorts the pixel's contiguous range: through the local array when it fits, else by
// heap sort in place in the depth array (counted; ldm/common/heap_sort.glsl says why heap sort).
//
// Work counted (DfBuffer::work_counters(), "sort"): invocations, each range's length, the
// sorts' comparisons and moves (post_sort.glsl, heap_sort.glsl), the offsets read, and the
// depths read and written: by the copy into and out of the local array (bytes_*_depths,
// which depend only on the ranges' lengths) and by the heap sort in place
// (bytes_*_depths_heap: how many depends on the order the range arrived in).
layout(local_size_x = 64) in;

#include "common/work_counters.glsl"
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
#if WORK_COUNTING
uint work_heap_loads = 0u, work_heap_stores = 0u;
#define DF_COUNT(statement) statement
#else
#define DF_COUNT(statement)
#endif
uint heap_load(uint i) {
  DF_COUNT(++work_heap_loads);
  return df_depths[heap_first + i];
}
void heap_store(uint i, uint bits) {
  DF_COUNT(++work_heap_stores);
  df_depths[heap_first + i] = bits;
}
#include "ldm/common/heap_sort.glsl"

void main() {
  // Every invocation of the dispatch, those past the last pixel included: one add per group.
  if (gl_LocalInvocationIndex == 0u) work_add(invocations, gl_WorkGroupSize.x);
  const uint pixel = linear_invocation_index();
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint first = df_offsets[pixel];
  const uint end = min(df_offsets[pixel + 1u], LDM_DF_CAPACITY);
  work_add(bytes_loaded_offsets, 8u);
  work_sample(list_length, end > first ? end - first : 0u);
  if (end <= first + 1u) return;  // empty or one fragment: sorted already
  const uint count = end - first;
  if (count > LDM_SORT_LOCAL) {
    heap_first = first;
    heap_sort_in_place(count);
    atomicCounterIncrement(lists_sorted_in_place);
    work_add(atomic_add, 1u);
    work_add(bytes_loaded_depths_heap, 4u * work_heap_loads);
    work_add(bytes_stored_depths_heap, 4u * work_heap_stores);
    return;
  }
  for (uint i = 0u; i < count; ++i) sort_local[i] = df_depths[first + i];
  insertion_sort_local(count);
  for (uint i = 0u; i < count; ++i) df_depths[first + i] = sort_local[i];
  work_add(bytes_loaded_depths, 4u * count);
  work_add(bytes_stored_depths, 4u * count);
}
