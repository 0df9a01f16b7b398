// The uniform add of the DF-buffer's prefix sum (ldm_impls/dfbuffer/prefix_sum.h): every
// value of block g gains the scanned sum of the blocks before it, scan_block_offsets[g].
// Work counted (DfBuffer::work_counters(), "prefix_sum", deterministic): invocations and the
// bytes read and written: the values are the offsets at level 0, block sums above.
layout(local_size_x = SCAN_GROUP_SIZE) in;

#include "common/work_counters.glsl"
#include "ldm/common/compute_grid.glsl"

const uint SCAN_BLOCK = SCAN_GROUP_SIZE * SCAN_PER_INVOCATION;

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer ScanValues {
  uint scan_values[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer ScanBlockOffsets {
  uint scan_block_offsets[];
};

uniform uint scan_count;
uniform uint scan_group_count;
#if WORK_COUNTING
uniform uint work_scan_level;  // the level whose values this adds to (PrefixSum::add_block_offsets)
#endif

void main() {
  if (gl_LocalInvocationIndex == 0u) work_add(invocations, gl_WorkGroupSize.x);
  const uint group = linear_workgroup_index();
  if (group == 0u || group >= scan_group_count) return;  // block 0 adds nothing
  const uint offset = scan_block_offsets[group];
#if WORK_COUNTING
  uint work_values = 0u;
#endif
  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i) {
    const uint at = group * SCAN_BLOCK + i * SCAN_GROUP_SIZE + gl_LocalInvocationID.x;
    if (at < scan_count) scan_values[at] += offset;
#if WORK_COUNTING
    if (at < scan_count) ++work_values;
#endif
  }
#if WORK_COUNTING
  work_add(bytes_loaded_scan_block_sums, 4u);  // the block's offset
  if (work_scan_level == 0u) {
    work_add(bytes_loaded_offsets, 4u * work_values);
    work_add(bytes_stored_offsets, 4u * work_values);
  } else {
    work_add(bytes_loaded_scan_block_sums, 4u * work_values);
    work_add(bytes_stored_scan_block_sums, 4u * work_values);
  }
#endif
}
